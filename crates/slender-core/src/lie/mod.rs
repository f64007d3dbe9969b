//! Rotations and rigid motions with exact first and second derivatives, for the models whose
//! degrees of freedom carry material frames (the discrete Cosserat rod and the SE(3) beam).
//!
//! Conventions, shared by every file here:
//! * a rotation is a unit quaternion; in derivative code it is the 4-vector (w, x, y, z);
//! * a rotation DOF is a *spatial* rotation-vector increment ω: R ← exp([ω]×) R, i.e. the
//!   quaternion p ← e(ω) ⊗ p with e(ω) = (cos(|ω|/2), sin(|ω|/2) ω/|ω|). Spatial increments
//!   make a planar restriction a restriction of coordinates (only ω along the plane normal
//!   is free) and moments about fixed axes simple;
//! * derivatives are those of dx ↦ f(exp(dx) state) at dx = 0 (the models' chart), obtained
//!   by the chain rule through the exact second-order expansion of the quaternions involved
//!   ([`quaternion`]) and maps of a quaternion with their own derivatives ([`darboux`],
//!   [`twist_angle`], [`se3`]). Only contractions of second derivatives with a weight vector
//!   are ever needed, so that is what the Hessian functions return;
//! * rotation vectors measured from a fixed frame (log maps, as a time step's inertia does)
//!   are differentiated in the same chart by [`rotation_chart`] (dexp⁻¹ and dexp, with their
//!   derivatives), through the quaternion exponential of [`exp_map`].

pub mod darboux;
pub mod exp_map;
pub mod quaternion;
pub mod rotation_chart;
pub mod se3;
pub mod twist_angle;

pub use darboux::{DarbouxMeasure, QuaternionMap};
pub use quaternion::{Quat, RelativeRotation, SingleRotation};
pub use rotation_chart::{left_jacobian, ExpChart, LogChart};
