//! The seed's perturbation protocol (seed §4.1): gravity |g|/100 along +y, then the full
//! gravity along −z, then the y-part removed; the result is classified by thresholds on the
//! measures Ξ₁[ξ_y] and Ξ₁[ξ_τ].

use serde::{Deserialize, Serialize};
use slender_core::geometry::Vec3;
use slender_core::solver::{EquilibriumSolver, SolveStatus, SolverParams};
use slender_core::ModelError;

use super::case::BendTwistCase;
use super::measures::{shape_measures, ShapeMeasures};
use crate::rod_model::{BenchmarkRod, RodModel};

/// Settings of the protocol and of its threshold decisions.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ProtocolSettings {
    /// Perturbing gravity along +y as a fraction of |g| (seed: 1/100).
    pub perturbation: f64,
    /// Threshold ε on Ξ₁[ξ_y]/L² above which a state counts as 3-D.
    pub threshold_y: f64,
    /// Threshold ε on Ξ₁[ξ_τ] (rad); the seed finds it must be of order 1 with its noise.
    pub threshold_tau: f64,
}

impl Default for ProtocolSettings {
    fn default() -> Self {
        Self {
            perturbation: 0.01,
            threshold_y: 1e-6,
            threshold_tau: 1e-3,
        }
    }
}

/// What the protocol produced at one (X, Y).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProtocolOutcome {
    /// All three stages converged.
    pub converged: bool,
    /// Why not, if they did not.
    pub failure: String,
    /// Measures of the final state (meaningless if not converged).
    pub measures: ShapeMeasures,
    /// Newton iterations over the three stages.
    pub iterations: usize,
    /// Negative Hessian eigenvalues at the final state (> 0: it stopped on a saddle).
    pub negative_eigenvalues: Option<usize>,
}

impl ProtocolOutcome {
    /// 3-D by the y-measure threshold; `None` if not converged.
    pub fn by_y(&self, s: &ProtocolSettings) -> Option<bool> {
        self.converged.then_some(self.measures.xi_y > s.threshold_y)
    }

    /// 3-D by the torsion threshold; `None` if not converged.
    pub fn by_tau(&self, s: &ProtocolSettings) -> Option<bool> {
        self.converged
            .then_some(self.measures.xi_tau > s.threshold_tau)
    }

    /// The combination the seed recommends: 3-D only if both measures say so (each covers
    /// the other's noise).
    pub fn combined(&self, s: &ProtocolSettings) -> Option<bool> {
        Some(self.by_y(s)? && self.by_tau(s)?)
    }
}

/// Runs the three stages on the discrete elastic rod; returns the outcome and the final
/// vertex positions.
pub fn run_protocol(
    case: &BendTwistCase,
    settings: &ProtocolSettings,
    params: &SolverParams,
) -> Result<(ProtocolOutcome, Vec<Vec3>), ModelError> {
    run_protocol_with(case, RodModel::Der, settings, params)
}

/// Runs the three stages on the rod formulation `model`.
pub fn run_protocol_with(
    case: &BendTwistCase,
    model: RodModel,
    settings: &ProtocolSettings,
    params: &SolverParams,
) -> Result<(ProtocolOutcome, Vec<Vec3>), ModelError> {
    crate::with_rod_model!(model, P => run_protocol_for::<P>(case, model, settings, params))
}

fn run_protocol_for<P: BenchmarkRod>(
    case: &BendTwistCase,
    model: RodModel,
    settings: &ProtocolSettings,
    params: &SolverParams,
) -> Result<(ProtocolOutcome, Vec<Vec3>), ModelError> {
    if !(settings.perturbation.is_finite() && settings.perturbation >= 0.0) {
        return Err(ModelError::parameter(
            "perturbation",
            settings.perturbation,
            "finite and >= 0",
        ));
    }
    let g = case.gravity();
    let side = Vec3::new(0.0, settings.perturbation * g, 0.0);
    let down = Vec3::new(0.0, 0.0, -g);
    // Each stage ramps one gravity change on top of what the previous stage left on.
    let stages = [(side, Vec3::zeros()), (down, side), (-side, side + down)];
    let build = |ramped: Vec3, preload: Vec3| {
        P::from_spec(&case.spec(ramped, preload, None)?.for_model(model))
    };
    let rod0 = build(stages[0].0, stages[0].1)?;
    let mut state = rod0.rest().clone();
    let mut solver = EquilibriumSolver::new(&rod0, &state, *params);
    let mut iterations = 0;
    let mut last = None;
    for (ramped, preload) in stages {
        let rod = build(ramped, preload)?;
        let sol = solver.solve(&rod, &state, 0.0, 1.0);
        iterations += sol.report.iterations;
        let converged = sol.report.converged();
        let failure = match &sol.report.status {
            SolveStatus::Converged => String::new(),
            SolveStatus::NotConverged { reason } => reason.clone(),
        };
        state = sol.state;
        last = Some((
            rod,
            converged,
            failure,
            sol.report.inertia.map(|i| i.negative),
        ));
        if !converged {
            break;
        }
    }
    let (rod, converged, failure, negative) = last.expect("three stages");
    let positions = P::positions(&state);
    let outcome = ProtocolOutcome {
        converged,
        failure,
        measures: shape_measures(positions, rod.element_lengths(), rod.rod_length()),
        iterations,
        negative_eigenvalues: negative,
    };
    Ok((outcome, positions.to_vec()))
}
