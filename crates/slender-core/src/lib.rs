//! slender-core: the physics of slender elastic structures.
//!
//! Discrete elastic rods (positions plus one twist angle per edge, time-parallel reference
//! frames), their energies with exact gradients and Hessians, clamps, meshes, and the Newton
//! solver that finds equilibria and reports their stability (Hessian inertia).
//!
//! Two more rod formulations share that solver, for comparing models side by side: the
//! discrete Cosserat rod ([`cosserat`], a frame per edge, shear) and the geometrically exact
//! SE(3) beam ([`se3`], a pose per node, helicoidal elements); what they share is in
//! [`framed`], their rotation calculus in [`lie`].
//!
//! This crate does no file I/O, no plotting and spawns no threads, so that it builds for
//! `wasm32` and can be embedded anywhere. Units are SI throughout (m, N, kg, s, rad).

// `!(x > 0.0)` is used on purpose: unlike `x <= 0.0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod assembly;
pub mod bspline_shell;
pub mod contact;
pub mod cosserat;
pub mod dynamics;
pub mod error;
pub mod framed;
pub mod geometry;
pub mod lie;
pub mod linalg;
pub mod rod;
pub mod scene;
pub mod scratch;
pub mod se3;
pub mod shell;
pub mod solver;
pub mod structure;
#[cfg(feature = "testing")]
pub mod testing;

pub use error::ModelError;
