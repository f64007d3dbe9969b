//! The lateral-buckling benchmark run on the shell model (seed §5): a heavy clamped strip,
//! length along x, width along gravity (−z). The planar state is decided stable or not by the
//! Hessian inertia (the stability route, Γ_c by bisection), and by the seed's perturbation
//! protocol. The master curves it is scored against live in [`crate::lateral_buckling`].

pub mod acceptance;
pub mod case;
pub mod convergence;
pub mod decisions;
pub mod sensitivity;
pub mod sweep;

pub use acceptance::{
    branch_switch, branch_switch_cases, branch_switch_check, branch_switch_checks,
    convergence_checks, decision_checks, decision_target, sensitivity_checks, BranchSwitchCase,
};
pub use case::{BuckledState, LateralBucklingCase, ProtocolOutcome};
pub use convergence::{richardson, CriticalConvergence, Extrapolation};
pub use decisions::{score_decisions, DecisionScore, UNDECIDABLE_BAND};
pub use sweep::{
    critical_record, CriticalRecord, LateralBucklingRecord, LateralBucklingSweep, ProtocolPoint,
};

use slender_core::solver::SolverParams;

use crate::lateral_buckling::{critical_gamma, MasterCurve};

/// The solver settings of the lateral-buckling benchmark: the defaults, every stage of the
/// protocol (a gravity increment or a clamp rotation) first tried in one step.
///
/// History: before the shells' mixed-integration-point Newton update (see
/// `slender_core::shell::mixed_update`), a Newton step from a thin strip's start was good only
/// over about a thickness and stages were first tried in tenths (≈ 700 Newton iterations per
/// protocol run on Ω_shell, n_L = 30, w/L = 0.1, Γ = 20); with it, a whole stage converges
/// in about five iterations (46 per run, measured).
pub fn solver_params() -> SolverParams {
    SolverParams::default()
}

/// The Vlasov-beam band of Γ_c at `width_ratio` for Poisson's ratio `poisson`: (weak-axis
/// stiffness E w h³/12, weak-axis stiffness D w); `None` outside the master curve's range.
pub fn vlasov_band(poisson: f64, width_ratio: f64) -> Option<(f64, f64)> {
    let beam = critical_gamma(width_ratio, poisson, MasterCurve::VlasovBeamStiffness).ok()?;
    let plate = critical_gamma(width_ratio, poisson, MasterCurve::VlasovPlateStiffness).ok()?;
    Some((beam, plate))
}
