//! Implicit time integration: the equations of motion M ẍ + C ẋ + ∇E(x) = 0 stepped by the
//! same Newton solver that finds equilibria.
//!
//! Each step is a minimization. Backward Euler solves M (v_{n+1} − vₙ)/h + C v_{n+1} +
//! ∇E(x_{n+1}) = 0 with v_{n+1} = (x_{n+1} ⊖ xₙ)/h: the stationarity condition of the
//! *incremental potential*
//!
//! Π(y) = E(y) + ‖y ⊖ xₙ − h vₙ‖²_M / (2h²) + (damping terms),
//!
//! whose Hessian is K + M/h² (+ damping). The implicit midpoint rule is the same with h/2 for
//! the midpoint, and the energy-conserving scheme replaces E by the average of the energy
//! along the step (see [`IncrementalProblem`] for the three). [`IncrementalProblem`] is that
//! potential as an [`EquilibriumProblem`](crate::solver::EquilibriumProblem) wrapping the
//! model, so the Newton loop, line search and convergence tests are reused unchanged;
//! [`TimeStepper`] owns state, velocity and time and advances them.
//!
//! Rods with material frames (the Cosserat rod, the SE(3) beam) are stepped too: their frames'
//! rotations live on SO(3), their rotary inertia turns with them, and the step measures them
//! by log maps whose derivatives (dexp⁻¹) it carries exactly (see [`IncrementalProblem`]).
//!
//! Quasi-static solves are untouched: nothing here is used unless a [`TimeStepper`] is made.

pub mod energy;
pub mod flat;
pub mod frames;
pub mod incremental;
pub mod mass;
pub mod params;
mod pullback;
pub mod quadrature;
pub mod report;
pub mod scheme;
pub mod stepper;

pub use energy::MechanicalEnergy;
pub use flat::FlatDofs;
pub use frames::FrameInertia;
pub use incremental::IncrementalProblem;
pub use mass::LumpedMass;
pub use params::DynamicsParams;
pub use report::StepReport;
pub use scheme::Scheme;
pub use stepper::TimeStepper;
