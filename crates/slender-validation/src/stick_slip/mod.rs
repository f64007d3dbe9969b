//! Romero et al.'s fourth benchmark: dry Coulomb friction, stick or slip.
//!
//! A straight rod lies on a plane inclined at α with Coulomb coefficient μ. Coulomb's law
//! says that it sticks, whatever its stiffness, while tan α ≤ μ, and that otherwise it slides
//! with the acceleration a = g (sin α − μ cos α): the closed form the measurement is scored
//! against ([`exact_acceleration`]). A friction model that regularizes stick by a slip
//! velocity creeps below the threshold; slender's sticking contacts are anchored, so the rod
//! must not move by more than its anchors' elastic deflection.
//!
//! [`case`] holds one run (a rod released at rest on the inclined plane and stepped in time,
//! friction updated every step); [`fit`] the measured acceleration; [`sweep`] the sweep over
//! rods, μ and tan α / μ, its scored rows and acceptance checks.

pub mod case;
pub mod fit;
pub mod sweep;

pub use case::{StickSlipCase, StickSlipError, StickSlipResult};

/// a = g (sin α − μ cos α) (m/s²) for gravity `g` (m/s²), inclination `alpha` (rad) and
/// Coulomb coefficient `mu`; negative means the rod sticks (a = 0).
pub fn exact_acceleration(g: f64, alpha: f64, mu: f64) -> f64 {
    g * (alpha.sin() - mu * alpha.cos())
}
