//! The lateral-buckling benchmark run on the shell model (seed §5): a heavy clamped strip,
//! length along x, width along gravity (−z). The planar state is decided stable or not by the
//! Hessian inertia (the stability route, Γ_c by bisection), and by the seed's perturbation
//! protocol. (The master curves the shell is scored against live in `lateral_buckling` where
//! present; `vlasov_fd` here is a small finite-difference Vlasov solver used for the plots.)

pub mod acceptance;
pub mod case;
pub mod sweep;
pub mod vlasov_fd;

pub use acceptance::lateral_buckling_checks;
pub use case::{LateralBucklingCase, ProtocolOutcome};
pub use sweep::{CriticalRecord, LateralBucklingRecord, LateralBucklingSweep};
