//! The cantilever sweep of the seed's Fig. 2: Γ log-spaced × element counts × meshes ×
//! material sets, each case solved from the straight state and compared with the master curve.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slender_core::solver::{SolveStatus, SolverParams};
use slender_core::ModelError;

use super::case::{CantileverCase, MeshKind};
use super::master_curve::{master_ratio, MasterCurveError};
use crate::materials::{RodMaterialSet, ROD_SETS};
use crate::rod_model::RodModel;

/// The parameter grid of a cantilever sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct CantileverSweep {
    /// Gravito-bending parameters Γ (> 0).
    pub gammas: Vec<f64>,
    /// Element counts (≥ 1).
    pub element_counts: Vec<usize>,
    /// Mesh families.
    pub meshes: Vec<MeshKind>,
    /// Material sets.
    pub materials: Vec<RodMaterialSet>,
}

/// `count` values log-spaced from `lo` to `hi` inclusive.
pub fn log_space(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    match count {
        0 => Vec::new(),
        1 => vec![lo],
        _ => (0..count)
            .map(|k| {
                let t = k as f64 / (count - 1) as f64;
                (lo.ln() + t * (hi.ln() - lo.ln())).exp()
            })
            .collect(),
    }
}

impl Default for CantileverSweep {
    /// The default: 40 values of Γ from 10⁻¹ to 10⁴, N ∈ {5, 10, 20, 50}, all three
    /// mesh families, Ω_rod and Ω_bundle.
    fn default() -> Self {
        Self {
            gammas: log_space(0.1, 1e4, 40),
            element_counts: vec![5, 10, 20, 50],
            meshes: MeshKind::ALL.to_vec(),
            materials: ROD_SETS.to_vec(),
        }
    }
}

/// One finished case, as written to `results.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CantileverRecord {
    /// Material set name.
    pub material: String,
    /// Mesh family name.
    pub mesh: String,
    /// Number of elements.
    pub n_elements: usize,
    /// Γ.
    pub gamma: f64,
    /// Computed Δy/Δx (NaN if not converged).
    pub ratio: f64,
    /// Master-curve Δy/Δx.
    pub master: f64,
    /// (ratio − master)/master.
    pub rel_error: f64,
    /// Whether the solve converged.
    pub converged: bool,
    /// Newton iterations.
    pub iterations: usize,
    /// Accepted load steps (1: solved in one step).
    pub load_steps: usize,
    /// Final residual relative to the largest external nodal force.
    pub relative_residual: f64,
    /// Negative eigenvalues of the Hessian at the solution (0: stable).
    pub negative_eigenvalues: Option<usize>,
    /// Smallest Hessian eigenvalue in the mass metric, divided by EI/(ρA L⁴).
    pub lambda_min_normalized: Option<f64>,
    /// Reason for non-convergence, empty when converged.
    pub failure: String,
}

/// Errors of a sweep.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A case could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The master curve failed at some Γ.
    #[error(transparent)]
    MasterCurve(#[from] MasterCurveError),
    /// The grid is empty or invalid.
    #[error("invalid sweep: {0}")]
    Invalid(String),
}

impl CantileverSweep {
    /// Checks the grid; errors name the field.
    pub fn validate(&self) -> Result<(), SweepError> {
        if self.gammas.is_empty()
            || self.element_counts.is_empty()
            || self.meshes.is_empty()
            || self.materials.is_empty()
        {
            return Err(SweepError::Invalid(
                "gammas, element counts, meshes and materials must all be non-empty".into(),
            ));
        }
        if let Some(g) = self.gammas.iter().find(|g| !(g.is_finite() && **g > 0.0)) {
            return Err(ModelError::parameter("gamma", *g, "finite and > 0").into());
        }
        if self.element_counts.contains(&0) {
            return Err(
                ModelError::structure("n_elements", "got 0; need at least 1 element").into(),
            );
        }
        Ok(())
    }

    /// The cases in a fixed order: material, mesh, element count, Γ.
    pub fn cases(&self) -> Vec<CantileverCase> {
        let mut cases = Vec::new();
        for &material in &self.materials {
            for &mesh in &self.meshes {
                for &n_elements in &self.element_counts {
                    for &gamma in &self.gammas {
                        cases.push(CantileverCase {
                            material,
                            mesh,
                            n_elements,
                            gamma,
                        });
                    }
                }
            }
        }
        cases
    }

    /// Runs every case on the current rayon pool and returns the records in [`Self::cases`]
    /// order, whatever the number of threads (each case is independent and deterministic).
    /// `progress` is called once per finished case.
    pub fn run(
        &self,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<CantileverRecord>, SweepError> {
        self.run_with(RodModel::Der, params, progress)
    }

    /// As [`Self::run`] with the rod formulation `model`.
    pub fn run_with(
        &self,
        model: RodModel,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<CantileverRecord>, SweepError> {
        self.validate()?;
        params.validate()?;
        self.cases()
            .par_iter()
            .map(|case| {
                let r = run_case_with(case, model, params);
                progress();
                r
            })
            .collect()
    }
}

/// Runs one case and scores it against the master curve at its Γ.
pub fn run_case(
    case: &CantileverCase,
    params: &SolverParams,
) -> Result<CantileverRecord, SweepError> {
    run_case_with(case, RodModel::Der, params)
}

/// Runs one case with the rod formulation `model` and scores it against the master curve.
pub fn run_case_with(
    case: &CantileverCase,
    model: RodModel,
    params: &SolverParams,
) -> Result<CantileverRecord, SweepError> {
    let master = master_ratio(case.gamma)?;
    let run = case.run_with(model, params)?;
    let (converged, failure) = match &run.report.status {
        SolveStatus::Converged => (true, String::new()),
        SolveStatus::NotConverged { reason } => (false, reason.clone()),
    };
    Ok(CantileverRecord {
        material: case.material.name.to_string(),
        mesh: case.mesh.name().to_string(),
        n_elements: case.n_elements,
        gamma: case.gamma,
        ratio: run.ratio,
        master,
        rel_error: run.ratio / master - 1.0,
        converged,
        iterations: run.report.iterations,
        load_steps: run.report.load_steps,
        relative_residual: run.report.relative_residual,
        negative_eigenvalues: run.report.inertia.map(|i| i.negative),
        lambda_min_normalized: run.report.lambda_min_normalized,
        failure,
    })
}

/// Worst relative errors of one discretization (material, mesh, N) over Γ.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiscretizationSummary {
    /// Material set name.
    pub material: String,
    /// Mesh family name.
    pub mesh: String,
    /// Number of elements.
    pub n_elements: usize,
    /// Largest |relative error| for Γ ∈ [10, 10³] (the seed's cable range); NaN if none.
    pub worst_in_cable_range: f64,
    /// Largest |relative error| over the whole sweep.
    pub worst_overall: f64,
    /// Cases that did not converge.
    pub not_converged: usize,
    /// Largest Newton iteration count of a case.
    pub max_iterations: usize,
}

/// The seed's meaningful range of Γ for cables.
pub const CABLE_RANGE: (f64, f64) = (10.0, 1e3);

/// Summarizes records per (material, mesh, N), in record order.
pub fn summarize(records: &[CantileverRecord]) -> Vec<DiscretizationSummary> {
    let mut out: Vec<DiscretizationSummary> = Vec::new();
    for r in records {
        let idx = match out.iter().position(|s| {
            s.material == r.material && s.mesh == r.mesh && s.n_elements == r.n_elements
        }) {
            Some(i) => i,
            None => {
                out.push(DiscretizationSummary {
                    material: r.material.clone(),
                    mesh: r.mesh.clone(),
                    n_elements: r.n_elements,
                    worst_in_cable_range: f64::NAN,
                    worst_overall: 0.0,
                    not_converged: 0,
                    max_iterations: 0,
                });
                out.len() - 1
            }
        };
        let s = &mut out[idx];
        if !r.converged {
            s.not_converged += 1;
            continue;
        }
        let e = r.rel_error.abs();
        s.worst_overall = s.worst_overall.max(e);
        if r.gamma >= CABLE_RANGE.0 * (1.0 - 1e-9) && r.gamma <= CABLE_RANGE.1 * (1.0 + 1e-9) {
            s.worst_in_cable_range = if s.worst_in_cable_range.is_nan() {
                e
            } else {
                s.worst_in_cable_range.max(e)
            };
        }
        s.max_iterations = s.max_iterations.max(r.iterations);
    }
    out
}
