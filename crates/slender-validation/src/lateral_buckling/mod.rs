//! Lateral buckling of a heavy clamped strip (seed §5, design.md §1.3): the master curves
//! `Γ_c(w/L; ν)` that the shell is scored against, computed independently of any shell.
//!
//! * [`vlasov`]: the warping-torsion (Vlasov) beam eigenproblem, by compound-matrix
//!   shooting and by Hermite-element Rayleigh–Ritz, converted to `Γ_shell` with either
//!   weak-axis stiffness convention;
//! * [`plate_buckling`]: the linear buckling load of the clamped Kirchhoff plate under its
//!   in-plane self-weight, by a two-stage Legendre Ritz method;
//! * [`master_curve`]: the public API (`critical_gamma`, samplers) the sweep and plots use.

pub mod error;
pub mod generalized_eigen;
pub mod legendre;
pub mod master_curve;
pub mod master_curve_checks;
pub mod plate_buckling;
pub mod vlasov;

pub use error::LateralBucklingError;
pub use master_curve::{
    critical_gamma, linear_samples, master_curves, narrow_strip_limit, sample_master_curve,
    MasterCurve, MasterCurves,
};
pub use master_curve_checks::master_curve_checks;
pub use vlasov::WeakAxisStiffness;
