//! What the rods whose degrees of freedom carry material frames share: the discrete Cosserat
//! rod ([`crate::cosserat`], a frame per edge) and the geometrically exact SE(3) beam
//! ([`crate::se3`], a frame per node).
//!
//! Their states hold vertex positions and frame orientations (unit quaternions); the free DOFs
//! are position increments and *spatial* rotation-vector increments of the frames, applied by
//! the exponential map (see [`crate::lie`]). Everything but the elastic terms lives here: DOF
//! layout, supports (clamps hold the exact pose of the rest curve's end), gravity and point
//! loads, moments as conservative potentials, the retraction and log-map difference the
//! solver and its secant predictor use, support motion along the load path, and reactions.

pub mod builder;
pub mod core;
pub mod equilibrium;
pub mod full_stencil;
pub mod groups;
pub mod layout;
pub mod load_path;
pub mod loads;
pub mod moment;
pub mod moment_change;
pub mod reactions;
pub mod retraction;
pub mod section;
pub mod state;

pub use builder::FramedRodBuilder;
pub use core::FramedCore;
pub use equilibrium::FramedModel;
pub use layout::{DofSlot, FramedDofs};
pub use moment::FrameMoment;
pub use retraction::rotation_vector;
pub use section::ShearStiffness;
pub use state::FramedState;
