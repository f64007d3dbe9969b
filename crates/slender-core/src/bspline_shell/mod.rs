//! A smooth (C¹) Kirchhoff–Love shell strip discretized by one tensor-product B-spline patch
//! (isogeometric, Kiendl et al. 2009; design.md §3.4): St-Venant–Kirchhoff membrane and
//! bending energies from the exact first and second fundamental forms of the surface at
//! Gauss points, with analytic gradients and Hessians on each element's (p+1)² control
//! points; exact clamps by holding the first (last) two control rows at any pose; gravity as
//! the exact consistent load; point forces; a load path that ramps the loads or moves the
//! clamps rigidly.
//!
//! Why a B-spline patch: every benchmark and every flat cable is a rectangle, and a single
//! patch of degree ≥ 2 gives a C¹ surface — curvature is a function of the surface itself, so
//! no director DOFs and no ghost faces are needed — with high accuracy per DOF and an exact
//! clamp, the combination that lets a shell reach the coarse-mesh accuracy the seed
//! attributes to GeoXShell (eight elements along the length).
//!
//! The membrane energy is sampled at patch-wide Greville points along the length (see
//! [`MembraneRule`]): at the bending term's Gauss points a thin strip locks.
//!
//! Geometry: length along x (parameter u ∈ [0, L], graded toward the start like the other
//! models), width along z (v ∈ [−w/2, w/2]), rest normal +y. The Newton iteration uses the
//! mixed-integration-point membrane update (see [`crate::shell::mixed_update`]).

pub mod basis;
pub mod bending;
pub mod builder;
pub mod clamp;
pub mod element;
pub mod equilibrium;
pub mod forms;
pub mod gravity;
pub mod groups;
pub mod load_path;
pub mod loads;
pub mod membrane;
pub mod model;
pub mod patch;
pub mod quadrature;
pub mod state;

pub use builder::{BsplineShellBuilder, MembraneRule};
pub use clamp::StripEnd;
pub use load_path::{BsplineLoadPath, ClampMotion};
pub use loads::PointLoad;
pub use model::BsplineShell;
pub use state::BsplineState;
