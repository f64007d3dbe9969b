//! The time-integration schemes: what the implicit unknown is and how it becomes the next
//! state.

use serde::{Deserialize, Serialize};

/// An implicit one-step scheme, each step one minimization (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scheme {
    /// Backward Euler: the unknown is the new state (stage τ = h). First order; dissipates
    /// energy, most in the modes that are poorly resolved (ωh ≳ 1), which makes it robust.
    BackwardEuler,
    /// The implicit midpoint rule: the unknown is the midpoint (τ = h/2) and the new state is
    /// extrapolated through it, x_{n+1} = y ⊕ (y ⊖ xₙ), v_{n+1} = 2 v_s − vₙ. Second order,
    /// symplectic, no numerical damping, one assembly per Newton iteration. Energy is exact
    /// for quadratic energies (small vibrations) but not for large rotations of a rod with
    /// stiff, unresolved stretching: there it drifts (measured in `tests/dynamics.rs`).
    ImplicitMidpoint,
    /// The average-vector-field (discrete-gradient) method: the unknown is the new state and
    /// the force is the mean of ∇E along the straight step, ∫₀¹ ∇E(xₙ + s d) ds, taken by
    /// Gauss–Legendre quadrature of `quadrature_points` nodes. Second order, symmetric, and
    /// energy-conserving: kinetic + potential energy changes only by the quadrature error
    /// (exact for polynomial energies of degree ≤ 2q, e.g. gravity and small vibrations).
    /// Costs q assemblies per Newton iteration; q = 1 is the implicit midpoint rule.
    #[default]
    EnergyConserving,
}

impl Scheme {
    /// Order of accuracy in the time step.
    pub fn order(self) -> u32 {
        match self {
            Self::BackwardEuler => 1,
            Self::ImplicitMidpoint | Self::EnergyConserving => 2,
        }
    }
}
