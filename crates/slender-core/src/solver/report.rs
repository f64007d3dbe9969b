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
    /// `residual` divided by `force_scale` (0 when there is no force at all).
    pub relative_residual: f64,
    /// The force scale (N) the residual is measured against: the largest external nodal force,
    /// or, in a structure loaded only by the motion of its supports, the internal forces they
    /// impose (half the largest Σ|term force| on a DOF).
    #[serde(default)]
    pub force_scale: f64,
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
    /// True if the solve converged only because its residual reached the round-off floor,
    /// above the force tolerance relative to the force scale: the equilibrium is as accurate
    /// as double precision allows for this stiffness ratio, and no better.
    pub fn floor_limited(&self, force_tolerance: f64) -> bool {
        self.converged() && self.residual > force_tolerance * self.force_scale
    }

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
