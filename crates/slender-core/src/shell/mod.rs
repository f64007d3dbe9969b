//! Discrete Kirchhoff–Love thin shell on triangles (libshell-type, design.md §3): St-Venant–
//! Kirchhoff membrane with 2-D Lamé constants, mid-edge director bending with one angle DOF
//! per edge (`MidedgeAngleTan`, free boundary directors), the exact director clamp, lumped
//! self-weight, on structured strip meshes graded toward the clamp.

pub mod bending;
pub mod builder;
pub mod clamp;
pub mod dofs;
pub mod dual;
pub mod edge_jet;
pub mod equilibrium;
pub mod gravity;
pub mod groups;
pub mod load_path;
pub mod membrane;
pub mod mesh;
pub mod mixed_update;
pub mod model;
pub mod rigid_turn;
pub mod rod_predictor;
pub mod state;
pub mod strip_guess;

pub use builder::ShellBuilder;
pub use clamp::Clamp;
pub use load_path::LoadPath;
pub use mesh::StripMesh;
pub use model::{Shell, ShellContext, ShellProperties};
pub use rigid_turn::turn_vertex_blocks;
pub use rod_predictor::rod_predictor;
pub use state::ShellState;
