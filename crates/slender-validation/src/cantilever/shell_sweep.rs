//! The shell part of the seed's Fig. 2: Γ_shell log-spaced × element counts × shell sets
//! (Table 2), each strip solved and compared with the heavy-elastica master curve.
//!
//! The master curve uses the plate stiffness D·w; with ν ≠ 0 a narrow strip is softer by up
//! to 1/(1 − ν²) (anticlastic curvature, design.md §1.1), so the shell sets of Table 2
//! (ν ≈ 0.35) are expected above the curve at small Γ — a physical, not a numerical, offset.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slender_core::solver::{SolveStatus, SolverParams};

use super::master_curve::master_ratio;
use super::shell_acceptance::cantilever_grading;
use super::shell_case::ShellCantileverCase;
use super::sweep::SweepError;
use crate::materials::ShellMaterialSet;
use crate::shell_model::ShellModel;

/// The parameter grid of a shell cantilever sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellCantileverSweep {
    /// Shell models.
    pub models: Vec<ShellModel>,
    /// Γ_shell values (> 0).
    pub gammas: Vec<f64>,
    /// Elements along the length n_L (≥ 1); n_W follows from w/L.
    pub element_counts: Vec<usize>,
    /// Aspect ratio w/L (> 0).
    pub width_ratio: f64,
    /// Shell sets.
    pub materials: Vec<ShellMaterialSet>,
}

/// One finished shell case, as written to `shell_results.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ShellCantileverRecord {
    /// Shell model.
    pub model: ShellModel,
    /// Material set name.
    pub material: String,
    /// Poisson ratio of the set.
    pub poisson: f64,
    /// Elements along the length.
    pub n_length: usize,
    /// Elements across the width.
    pub n_width: usize,
    /// w/L.
    pub width_ratio: f64,
    /// Γ_shell.
    pub gamma: f64,
    /// Computed Δy/Δx of the centre line (NaN if not converged).
    pub ratio: f64,
    /// Master-curve Δy/Δx (1-D, stiffness D·w).
    pub master: f64,
    /// (ratio − master)/master.
    pub rel_error: f64,
    /// Whether the solve converged.
    pub converged: bool,
    /// Newton iterations.
    pub iterations: usize,
    /// Wall time (s), build excluded.
    pub seconds: f64,
    /// Negative eigenvalues of the Hessian at the solution (0: stable).
    pub negative_eigenvalues: Option<usize>,
    /// Reason for non-convergence, empty when converged.
    pub failure: String,
}

impl ShellCantileverSweep {
    /// The cases in a fixed order: model, material, element count, Γ (each model on its
    /// graded mesh, [`cantilever_grading`]).
    pub fn cases(&self) -> Vec<ShellCantileverCase> {
        let mut cases = Vec::new();
        for &model in &self.models {
            for &material in &self.materials {
                for &n_length in &self.element_counts {
                    for &gamma in &self.gammas {
                        cases.push(ShellCantileverCase {
                            model,
                            material,
                            width_ratio: self.width_ratio,
                            n_length,
                            n_width: ShellCantileverCase::default_width_elements(
                                model,
                                self.width_ratio,
                                n_length,
                            ),
                            grading: cantilever_grading(model, gamma),
                            gamma,
                        });
                    }
                }
            }
        }
        cases
    }

    /// Checks the grid; errors name the field.
    pub fn validate(&self) -> Result<(), SweepError> {
        if self.gammas.is_empty()
            || self.element_counts.is_empty()
            || self.materials.is_empty()
            || self.models.is_empty()
        {
            return Err(SweepError::Invalid(
                "gammas, element counts, materials and models must all be non-empty".into(),
            ));
        }
        Ok(())
    }

    /// Runs every case on the current rayon pool; records in [`Self::cases`] order whatever
    /// the thread count. `progress` is called once per finished case.
    pub fn run(
        &self,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<ShellCantileverRecord>, SweepError> {
        self.validate()?;
        params.validate()?;
        self.cases()
            .par_iter()
            .map(|case| {
                let r = run_shell_case(case, params);
                progress();
                r
            })
            .collect()
    }
}

/// Runs one shell case and scores it against the master curve (stiffness D·w) at its Γ.
pub fn run_shell_case(
    case: &ShellCantileverCase,
    params: &SolverParams,
) -> Result<ShellCantileverRecord, SweepError> {
    let run = case.run(params)?;
    let master = master_ratio(case.gamma)?;
    let (converged, failure) = match &run.report.status {
        SolveStatus::Converged => (true, String::new()),
        SolveStatus::NotConverged { reason } => (false, reason.clone()),
    };
    Ok(ShellCantileverRecord {
        model: case.model,
        material: case.material.name.to_string(),
        poisson: case.material.poisson,
        n_length: case.n_length,
        n_width: case.n_width,
        width_ratio: case.width_ratio,
        gamma: case.gamma,
        ratio: run.ratio,
        master,
        rel_error: run.ratio / master - 1.0,
        converged,
        iterations: run.report.iterations,
        seconds: run.seconds,
        negative_eigenvalues: run.report.inertia.map(|i| i.negative),
        failure,
    })
}
