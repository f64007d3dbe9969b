//! Newton's method with line search, load stepping and stability analysis (design.md §4).

pub mod branch_switch;
pub mod continuation;
pub mod lagged_loads;
pub mod line_search;
pub mod newton;
pub mod params;
pub mod problem;
pub mod report;
pub mod stability;

pub use branch_switch::{follow_unstable_mode, kick_scale, BranchSwitch};
pub use continuation::{EquilibriumSolver, Solution};
pub use newton::{newton, NewtonOutcome, NewtonWorkspace};
pub use params::SolverParams;
pub use problem::{AssemblyInfo, EquilibriumProblem, MassMetric};
pub use report::{SolveReport, SolveStatus};
pub use stability::{
    classify_modes, is_stable, lowest_mode, lowest_mode_with, EigenWorkspace, LowestMode,
    ModeCounts,
};
