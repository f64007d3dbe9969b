//! The cantilever under self-weight (seed §3, Fig. 2).

pub mod acceptance;
pub mod case;
pub mod master_curve;
pub mod shell_acceptance;
pub mod shell_case;
pub mod shell_sweep;
pub mod sweep;

pub use acceptance::{cantilever_checks, Check};
pub use case::{end_point_ratio, CantileverCase, CantileverRun, MeshKind};
pub use shell_acceptance::shell_cantilever_checks;
pub use shell_case::{ShellCantileverCase, ShellCantileverRun};
pub use shell_sweep::{run_shell_case, ShellCantileverRecord, ShellCantileverSweep};
pub use sweep::{
    log_space, run_case, summarize, CantileverRecord, CantileverSweep, DiscretizationSummary,
    SweepError, CABLE_RANGE,
};
