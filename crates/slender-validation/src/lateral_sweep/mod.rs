//! The lateral-buckling benchmark run on the shell model (seed §5): a heavy clamped strip,
//! length along x, width along gravity (−z). The planar state is decided stable or not by the
//! Hessian inertia (the stability route, Γ_c by bisection), and by the seed's perturbation
//! protocol. The master curves it is scored against live in [`crate::lateral_buckling`].

pub mod acceptance;
pub mod case;
pub mod sensitivity;
pub mod sweep;

pub use acceptance::lateral_buckling_checks;
pub use case::{LateralBucklingCase, ProtocolOutcome};
pub use sweep::{CriticalRecord, LateralBucklingRecord, LateralBucklingSweep, ProtocolPoint};

use crate::lateral_buckling::{critical_gamma, MasterCurve};

/// The Vlasov-beam band of Γ_c at `width_ratio` for Poisson's ratio `poisson`: (weak-axis
/// stiffness E w h³/12, weak-axis stiffness D w); `None` outside the master curve's range.
pub fn vlasov_band(poisson: f64, width_ratio: f64) -> Option<(f64, f64)> {
    let beam = critical_gamma(width_ratio, poisson, MasterCurve::VlasovBeamStiffness).ok()?;
    let plate = critical_gamma(width_ratio, poisson, MasterCurve::VlasovPlateStiffness).ok()?;
    Some((beam, plate))
}
