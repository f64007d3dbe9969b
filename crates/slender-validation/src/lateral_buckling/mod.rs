//! Lateral buckling of a heavy clamped strip (seed §5): length along x, width along gravity
//! (−z). The planar state is decided stable or not by the Hessian inertia (the stability
//! route, Γ_c by bisection), and by the seed's perturbation protocol.

pub mod acceptance;
pub mod case;
pub mod sweep;
pub mod vlasov;

pub use acceptance::lateral_buckling_checks;
pub use case::{LateralBucklingCase, ProtocolOutcome};
pub use sweep::{CriticalRecord, LateralBucklingRecord, LateralBucklingSweep};
