//! Scenes: rods and shell strips described in a file (TOML or JSON, parsed by the binary),
//! validated with errors that name the place in the file, compiled into structures and solved,
//! edited and re-solved warm through a [`Session`] (prescribed motion, interactive editing),
//! or stepped in time through a [`TimeRun`] (a `[time]` table).
//!
//! No file I/O here: the binary reads files and writes outputs.

mod carry;
pub mod compile;
mod contact_report;
mod contact_solve;
pub mod error;
pub mod magnitudes;
pub mod result;
pub mod session;
mod shell_contact_run;
pub mod shell_run;
pub mod shells;
pub mod solve;
pub mod spec;
pub mod time_run;

pub use compile::{CompiledRod, CompiledScene, CompiledSupport, RodPart};
pub use error::SceneError;
pub use result::{
    ContactResult, EdgeThroughObstacle, FrameEnergy, ObstacleResult, RodResult, SceneStep,
    SegmentContactKind, SegmentContactResult, StabilityResult, StructureResult, SupportResult,
    TimeFrame,
};
pub use session::{EditReport, Session, StructureList, SupportPose};
pub use shell_run::ShellRun;
pub use shells::{CompiledShell, CompiledShellClamp, ShellResult, StripModel};
pub use spec::Scene;
pub use time_run::{TimeRun, TimeStepOutcome};
