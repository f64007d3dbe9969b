//! The bend–twist sweep over a log grid in (X, Y) (seed Figs. 7–8): each point decided by the
//! seed's protocol and by stability, both compared with the master curve.

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;
use slender_core::ModelError;

use super::case::BendTwistCase;
use super::master_curve::{critical_boundaries, BendTwistError, StabilityBoundary};
use super::protocol::{run_protocol_with, ProtocolSettings};
use super::stability::decide_by_stability_with;
use crate::cantilever::log_space;
use crate::rod_model::RodModel;

/// The parameter grid.
#[derive(Clone, Debug, PartialEq)]
pub struct BendTwistSweep {
    /// Values of X.
    pub xs: Vec<f64>,
    /// Values of Y.
    pub ys: Vec<f64>,
    /// Elements per unit Y.
    pub elements_per_turn: f64,
    /// Protocol settings and thresholds.
    pub protocol: ProtocolSettings,
}

impl BendTwistSweep {
    /// The quick grid: 12 × 12 points over X, Y ∈ [0.1, 10], 20·Y elements.
    pub fn quick() -> Self {
        Self {
            xs: log_space(0.1, 10.0, 12),
            ys: log_space(0.1, 10.0, 12),
            elements_per_turn: 20.0,
            protocol: ProtocolSettings::default(),
        }
    }

    /// The seed's resolution: 25 × 25 points, 100·Y elements.
    pub fn full() -> Self {
        Self {
            xs: log_space(0.1, 10.0, 25),
            ys: log_space(0.1, 10.0, 25),
            elements_per_turn: 100.0,
            protocol: ProtocolSettings::default(),
        }
    }

    /// Grid points in a fixed order (Y outer, X inner).
    pub fn cases(&self) -> Vec<BendTwistCase> {
        self.ys
            .iter()
            .flat_map(|&y| self.xs.iter().map(move |&x| (x, y)))
            .map(|(x, y)| BendTwistCase::new(x, y, self.elements_per_turn))
            .collect()
    }

    /// Runs every point (in parallel; the order and the results do not depend on threads).
    pub fn run(
        &self,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<BendTwistRecord>, BendTwistSweepError> {
        self.run_with(RodModel::Der, params, progress)
    }

    /// As [`Self::run`] with the rod formulation `model`.
    pub fn run_with(
        &self,
        model: RodModel,
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<BendTwistRecord>, BendTwistSweepError> {
        // The master curve once per row of the grid.
        let c = self.torsion_ratio();
        let boundaries: Vec<StabilityBoundary> = self
            .ys
            .par_iter()
            .map(|&y| critical_boundaries(y, c))
            .collect::<Result<_, _>>()?;
        self.cases()
            .par_iter()
            .map(|case| {
                let k = self
                    .ys
                    .iter()
                    .position(|&y| y == case.y)
                    .expect("row of the grid");
                let r = run_point_with(case, model, &boundaries[k], &self.protocol, params);
                progress();
                r
            })
            .collect()
    }

    /// GJ/EI of the benchmark's material.
    pub fn torsion_ratio(&self) -> f64 {
        let m = BendTwistCase::new(1.0, 1.0, 1.0)
            .material
            .properties
            .stiffness;
        m.gj / m.ei_min()
    }
}

/// Errors of the bend–twist sweep.
#[derive(Debug, thiserror::Error)]
pub enum BendTwistSweepError {
    /// A case could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// The master curve failed.
    #[error(transparent)]
    MasterCurve(#[from] BendTwistError),
}

/// One grid point, as written to `results.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BendTwistRecord {
    /// X = (R/L)Γ^{1/3}.
    pub x: f64,
    /// Y = L/(2πR).
    pub y: f64,
    /// Γ = (2πXY)³.
    pub gamma: f64,
    /// Elements.
    pub n_elements: usize,
    /// Protocol: Ξ₁[ξ_y]/L² of the final state.
    pub xi_y: f64,
    /// Protocol: Ξ₁[ξ_τ] (rad) of the final state.
    pub xi_tau: f64,
    /// Protocol converged (all three stages).
    pub protocol_converged: bool,
    /// Protocol decision by Ξ₁[ξ_y] > ε_y (empty if not converged).
    pub protocol_3d_y: Option<bool>,
    /// Protocol decision by Ξ₁[ξ_τ] > ε_τ.
    pub protocol_3d_tau: Option<bool>,
    /// Protocol decision by both measures.
    pub protocol_3d: Option<bool>,
    /// Negative Hessian eigenvalues where the protocol ended (> 0: a saddle).
    pub protocol_negative: Option<usize>,
    /// Planar equilibrium converged.
    pub planar_converged: bool,
    /// Smallest out-of-plane eigenvalue / (EI/(ρA L⁴)) at the planar state (< 0: unstable).
    pub lambda_min: Option<f64>,
    /// Stability decision (3-D iff the planar state is unstable out of plane).
    pub stability_3d: Option<bool>,
    /// Ξ₁[ξ_y]/L² of the buckled state found by branch switching.
    pub buckled_xi_y: Option<f64>,
    /// Ξ₁[ξ_τ] of the buckled state.
    pub buckled_xi_tau: Option<f64>,
    /// Lower boundary X_c1 of the master curve at this Y (empty: none).
    pub x_c1: Option<f64>,
    /// Upper boundary X_c2 at this Y.
    pub x_c2: Option<f64>,
    /// Ground truth from the master curve: 3-D iff X_c1 < X < X_c2.
    pub truth_3d: bool,
    /// Newton iterations (protocol + stability route).
    pub iterations: usize,
    /// Non-convergence reasons, if any.
    pub failure: String,
}

/// Runs both routes at one point; `boundary` is the master curve at `case.y`.
pub fn run_point(
    case: &BendTwistCase,
    boundary: &StabilityBoundary,
    protocol: &ProtocolSettings,
    params: &SolverParams,
) -> Result<BendTwistRecord, BendTwistSweepError> {
    run_point_with(case, RodModel::Der, boundary, protocol, params)
}

/// Runs both routes at one point with the rod formulation `model`.
pub fn run_point_with(
    case: &BendTwistCase,
    model: RodModel,
    boundary: &StabilityBoundary,
    protocol: &ProtocolSettings,
    params: &SolverParams,
) -> Result<BendTwistRecord, BendTwistSweepError> {
    let truth_3d =
        matches!((boundary.lower, boundary.upper), (Some(l), Some(u)) if case.x > l && case.x < u);
    let (p, _) = run_protocol_with(case, model, protocol, params)?;
    let (s, _) = decide_by_stability_with(case, model, params)?;
    let mut failure = String::new();
    if !p.converged {
        failure += &format!("protocol: {}", p.failure);
    }
    if !s.planar_converged {
        failure += &format!(
            "{}planar: {}",
            if failure.is_empty() { "" } else { "; " },
            s.failure
        );
    }
    Ok(BendTwistRecord {
        x: case.x,
        y: case.y,
        gamma: case.gamma(),
        n_elements: case.n_elements(),
        xi_y: p.measures.xi_y,
        xi_tau: p.measures.xi_tau,
        protocol_converged: p.converged,
        protocol_3d_y: p.by_y(protocol),
        protocol_3d_tau: p.by_tau(protocol),
        protocol_3d: p.combined(protocol),
        protocol_negative: p.negative_eigenvalues,
        planar_converged: s.planar_converged,
        lambda_min: s.lambda_out_normalized,
        stability_3d: s.three_dimensional(),
        buckled_xi_y: s.buckled.map(|m| m.xi_y),
        buckled_xi_tau: s.buckled.map(|m| m.xi_tau),
        x_c1: boundary.lower,
        x_c2: boundary.upper,
        truth_3d,
        iterations: p.iterations + s.iterations,
        failure,
    })
}
