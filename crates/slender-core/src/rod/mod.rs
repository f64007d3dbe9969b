//! Discrete elastic rods (Bergou et al. 2008/2010): vertex positions plus one material angle
//! per edge, time-parallel reference frames, extensible stretching, anisotropic bending with
//! natural curvature, twisting, clamps with a ghost edge and half Voronoi cell, and dead loads.

pub mod bending;
pub mod builder;
pub mod clamp;
pub mod dofs;
pub mod equilibrium;
pub mod follower;
pub mod frames;
pub mod gravity;
pub mod groups;
pub mod hinge;
pub mod load_path;
pub mod loads;
pub mod mesh;
pub mod model;
pub mod moment;
pub mod moment_change;
pub mod point_loads;
pub mod reactions;
pub mod rest_curve;
pub mod retraction;
pub mod section;
pub mod snapshot;
pub mod state;
pub mod strains;
pub mod stretching;
pub mod supports;
pub mod twisting;

pub use builder::RodBuilder;
pub use follower::{FollowerLoad, FollowerState};
pub use load_path::{RodLoadPath, SavedLoads, SupportMotion};
pub use mesh::Grading;
pub use model::{Rod, RodContext};
pub use point_loads::{PointForce, PointMoment};
pub use reactions::{FullGradient, LoadResultant, SupportReaction};
pub use rest_curve::RestCurve;
pub use section::{CrossSection, Material, RodProperties, SectionStiffness};
pub use snapshot::{ClampHold, RodSnapshot};
pub use state::RodState;
pub use strains::HingeStrain;
pub use supports::Supports;
