//! Scenes: rods described in a file (TOML or JSON, parsed by the binary), validated with
//! errors that name the place in the file, built into rod models and solved, with prescribed
//! support motion as a sequence of warm-started equilibria.
//!
//! No file I/O here: the binary reads files and writes outputs.

pub mod compile;
pub mod error;
pub mod free_motion;
pub mod magnitudes;
pub mod shells;
pub mod solve;
pub mod spec;

pub use compile::{CompiledRod, CompiledScene, CompiledSupport, Segment};
pub use error::SceneError;
pub use shells::{CompiledShell, ShellResult};
pub use solve::{RodResult, SceneStep, SupportResult};
pub use spec::Scene;
