//! The cantilever for every rod model: errors against Γ, order of convergence, iterations and
//! time per solve.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;

use crate::cantilever::acceptance::convergence_slope;
use crate::cantilever::master_curve::master_ratio;
use crate::cantilever::{log_space, CantileverCase, MeshKind, SweepError, CABLE_RANGE};
use crate::materials::{RodMaterialSet, OMEGA_ROD};
use crate::rod_model::RodModel;

/// The grid of the comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCantileverSweep {
    /// Rod formulations.
    pub models: Vec<RodModel>,
    /// Γ values.
    pub gammas: Vec<f64>,
    /// Element counts.
    pub element_counts: Vec<usize>,
    /// Mesh families.
    pub meshes: Vec<MeshKind>,
    /// Material set.
    pub material: RodMaterialSet,
}

impl Default for ModelCantileverSweep {
    /// Every model, 25 values of Γ in [0.1, 10⁴], N ∈ {5, 10, 20, 50}, uniform and graded
    /// meshes, Ω_rod.
    fn default() -> Self {
        Self {
            models: RodModel::ALL.to_vec(),
            gammas: log_space(0.1, 1e4, 25),
            element_counts: vec![5, 10, 20, 50],
            meshes: vec![MeshKind::Uniform, MeshKind::Graded],
            material: OMEGA_ROD,
        }
    }
}

/// One solve of the comparison.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelCantileverRecord {
    /// Model name.
    pub model: String,
    /// Mesh family.
    pub mesh: String,
    /// Elements.
    pub n_elements: usize,
    /// Γ.
    pub gamma: f64,
    /// Computed Δy/Δx (NaN if not converged).
    pub ratio: f64,
    /// (ratio − master)/master.
    pub rel_error: f64,
    /// Converged.
    pub converged: bool,
    /// Newton iterations.
    pub iterations: usize,
    /// Wall time of the solve (s), build excluded; measured on the sweep's threads.
    pub seconds: f64,
}

impl ModelCantileverSweep {
    /// The cases in a fixed order: model, mesh, N, Γ.
    pub fn cases(&self) -> Vec<(RodModel, CantileverCase)> {
        let mut out = Vec::new();
        for &model in &self.models {
            for &mesh in &self.meshes {
                for &n_elements in &self.element_counts {
                    for &gamma in &self.gammas {
                        out.push((
                            model,
                            CantileverCase {
                                material: self.material,
                                mesh,
                                n_elements,
                                gamma,
                            },
                        ));
                    }
                }
            }
        }
        out
    }

    /// Runs every case (in parallel; results other than the times do not depend on threads).
    pub fn run(
        &self,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<ModelCantileverRecord>, SweepError> {
        params.validate()?;
        self.cases()
            .par_iter()
            .map(|(model, case)| {
                let r = run_model_case(*model, case, params);
                progress();
                r
            })
            .collect()
    }
}

/// Runs one case of the comparison on `model` and scores it against the master curve.
pub fn run_model_case(
    model: RodModel,
    case: &CantileverCase,
    params: &SolverParams,
) -> Result<ModelCantileverRecord, SweepError> {
    let master = master_ratio(case.gamma)?;
    let run = case.run_with(model, params)?;
    Ok(ModelCantileverRecord {
        model: model.name().into(),
        mesh: case.mesh.name().into(),
        n_elements: case.n_elements,
        gamma: case.gamma,
        ratio: run.ratio,
        rel_error: run.ratio / master - 1.0,
        converged: run.report.converged(),
        iterations: run.report.iterations,
        seconds: run.seconds,
    })
}

/// Per model, mesh and N: the worst errors and the solver's effort.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelSummary {
    /// Model name.
    pub model: String,
    /// Mesh family.
    pub mesh: String,
    /// Elements.
    pub n_elements: usize,
    /// Largest |error| (%) over all Γ.
    pub worst_percent: f64,
    /// The same error with its sign (positive: too much sag, the model too soft).
    pub worst_signed_percent: f64,
    /// Γ where it occurs.
    pub worst_at_gamma: f64,
    /// Largest |error| (%) over Γ ∈ [10, 10³].
    pub worst_cable_percent: f64,
    /// Mean Newton iterations per solve.
    pub mean_iterations: f64,
    /// Largest Newton iteration count.
    pub max_iterations: usize,
    /// Mean wall time per solve (ms).
    pub mean_milliseconds: f64,
    /// Solves that did not converge.
    pub not_converged: usize,
}

/// Summaries in record order.
pub fn summarize_models(records: &[ModelCantileverRecord]) -> Vec<ModelSummary> {
    let mut out: Vec<ModelSummary> = Vec::new();
    let mut counts: Vec<usize> = Vec::new();
    for r in records {
        let i = match out
            .iter()
            .position(|s| s.model == r.model && s.mesh == r.mesh && s.n_elements == r.n_elements)
        {
            Some(i) => i,
            None => {
                out.push(ModelSummary {
                    model: r.model.clone(),
                    mesh: r.mesh.clone(),
                    n_elements: r.n_elements,
                    worst_percent: 0.0,
                    worst_signed_percent: 0.0,
                    worst_at_gamma: f64::NAN,
                    worst_cable_percent: 0.0,
                    mean_iterations: 0.0,
                    max_iterations: 0,
                    mean_milliseconds: 0.0,
                    not_converged: 0,
                });
                counts.push(0);
                out.len() - 1
            }
        };
        let s = &mut out[i];
        counts[i] += 1;
        let k = counts[i] as f64;
        s.mean_iterations += (r.iterations as f64 - s.mean_iterations) / k;
        s.mean_milliseconds += (1e3 * r.seconds - s.mean_milliseconds) / k;
        s.max_iterations = s.max_iterations.max(r.iterations);
        if !r.converged {
            s.not_converged += 1;
            continue;
        }
        let e = 100.0 * r.rel_error.abs();
        if e > s.worst_percent {
            s.worst_percent = e;
            s.worst_signed_percent = 100.0 * r.rel_error;
            s.worst_at_gamma = r.gamma;
        }
        if r.gamma >= CABLE_RANGE.0 * (1.0 - 1e-9) && r.gamma <= CABLE_RANGE.1 * (1.0 + 1e-9) {
            s.worst_cable_percent = s.worst_cable_percent.max(e);
        }
    }
    out
}

/// The observed order of convergence of one model at one Γ (graded mesh).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ModelConvergence {
    /// Model name.
    pub model: String,
    /// Γ.
    pub gamma: f64,
    /// Element counts.
    pub element_counts: Vec<usize>,
    /// Relative errors.
    pub errors: Vec<f64>,
    /// Least-squares slope of log|error| against log N over all counts.
    pub slope: f64,
    /// Slope over the two finest meshes (the asymptotic rate).
    pub finest_slope: f64,
}

/// Element counts of the order check (as the cantilever benchmark's).
pub const ORDER_MESHES: [usize; 4] = [10, 20, 40, 80];
/// Γ values of the order check.
pub const ORDER_GAMMAS: [f64; 2] = [1.0, 100.0];

/// The cases of the order check for `models`, in a fixed order: model, Γ, N (graded mesh).
pub fn order_cases(
    models: &[RodModel],
    material: RodMaterialSet,
) -> Vec<(RodModel, CantileverCase)> {
    models
        .iter()
        .flat_map(|&model| {
            ORDER_GAMMAS.iter().flat_map(move |&gamma| {
                ORDER_MESHES.iter().map(move |&n_elements| {
                    (
                        model,
                        CantileverCase {
                            material,
                            mesh: MeshKind::Graded,
                            n_elements,
                            gamma,
                        },
                    )
                })
            })
        })
        .collect()
}

/// The orders of convergence of `models` read off `records`, which must hold every case of
/// [`order_cases`] (missing ones count as NaN errors).
pub fn orders_from_records(
    models: &[RodModel],
    records: &[ModelCantileverRecord],
) -> Vec<ModelConvergence> {
    let k = ORDER_MESHES.len();
    models
        .iter()
        .flat_map(|&model| ORDER_GAMMAS.iter().map(move |&gamma| (model, gamma)))
        .map(|(model, gamma)| {
            let errors: Vec<f64> = ORDER_MESHES
                .iter()
                .map(|&n| {
                    records
                        .iter()
                        .find(|r| {
                            r.model == model.name()
                                && r.mesh == MeshKind::Graded.name()
                                && r.n_elements == n
                                && r.gamma == gamma
                        })
                        .map_or(f64::NAN, |r| r.rel_error)
                })
                .collect();
            ModelConvergence {
                model: model.name().into(),
                gamma,
                element_counts: ORDER_MESHES.to_vec(),
                slope: convergence_slope(&ORDER_MESHES, &errors),
                finest_slope: convergence_slope(&ORDER_MESHES[k - 2..], &errors[k - 2..]),
                errors,
            }
        })
        .collect()
}

/// Orders of convergence of every model of `models` at Γ = 1 and 100 (graded mesh, `material`).
pub fn convergence_orders(
    models: &[RodModel],
    material: RodMaterialSet,
    params: &SolverParams,
) -> Result<Vec<ModelConvergence>, SweepError> {
    params.validate()?;
    let records = order_cases(models, material)
        .par_iter()
        .map(|(model, case)| run_model_case(*model, case, params))
        .collect::<Result<Vec<_>, SweepError>>()?;
    Ok(orders_from_records(models, &records))
}
