//! What every solve reports: converged or not, how, and whether the equilibrium is stable.

use serde::{Deserialize, Serialize};

use crate::linalg::Inertia;

/// Outcome of a solve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum SolveStatus {
    /// An equilibrium at the full load, within the tolerances.
    Converged,
    /// No equilibrium was reached; the state is the last converged load step (or the start)
    /// and must not be used as an equilibrium at the requested load.
    NotConverged {
        /// Why the solver stopped.
        reason: String,
    },
}

/// Report attached to every solution.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SolveReport {
    /// Converged or not.
    pub status: SolveStatus,
    /// Load factor of the returned state (1 when converged).
    pub load_reached: f64,
    /// Newton iterations over all load steps.
    pub iterations: usize,
    /// Accepted load steps.
    pub load_steps: usize,
    /// Load steps that failed and were retried with a smaller increment.
    pub rejected_steps: usize,
    /// Load steps that needed a long minimization (the structure snapped past a fold).
    pub snaps: usize,
    /// Bifurcations crossed where the solver followed the unstable mode to the stable branch
    /// (with `follow_stable`).
    #[serde(default)]
    pub branch_switches: usize,
    /// Largest residual force (N; moments divided by a length) of the returned state at the
    /// requested load: small when converged, large when the state is not an equilibrium.
    pub residual: f64,
    /// `residual` divided by the largest external nodal force (0 when there is no load).
    pub relative_residual: f64,
    /// Round-off floor of the residual (N) at the returned state.
    pub residual_floor: f64,
    /// Newton decrement gᵀH⁻¹g (J) at the returned state.
    pub energy_decrement: f64,
    /// Total energy (J) at the returned state.
    pub energy: f64,
    /// Inertia of the Hessian at the returned state (negative count > 0: unstable).
    pub inertia: Option<Inertia>,
    /// Smallest eigenvalue of the Hessian in the mass metric (1/s², a squared natural
    /// frequency; negative: unstable), when computed.
    pub lambda_min: Option<f64>,
    /// `lambda_min` divided by EI/(ρA L⁴): a mesh-independent distance to instability.
    pub lambda_min_normalized: Option<f64>,
    /// Unstable and null modes told apart with a round-off band around zero (computed when the
    /// solver follows the stable branch, i.e. in scenes); `None` otherwise.
    #[serde(default)]
    pub modes: Option<super::stability::ModeCounts>,
}

impl SolveReport {
    /// True if the solve converged.
    pub fn converged(&self) -> bool {
        self.status == SolveStatus::Converged
    }

    /// `Some(true)` if the converged equilibrium is stable (no negative Hessian eigenvalue; with
    /// `modes` known, null modes within round-off of zero allowed), `Some(false)` if unstable,
    /// `None` if not converged or the inertia is unknown.
    pub fn stable(&self) -> Option<bool> {
        if !self.converged() {
            return None;
        }
        if let Some(m) = self.modes {
            // Null modes (symmetries) do not make an equilibrium unstable.
            return Some(m.unstable == 0);
        }
        self.inertia.map(|i| super::stability::is_stable(&i))
    }
}
