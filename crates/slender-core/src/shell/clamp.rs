//! The clamp of the edge x = 0: it fixes the vertex positions *and* the surface normal along
//! the clamp line (design.md §3.2).
//!
//! Fixing only the vertices would leave a hinge; fixing two rows of vertices clamps a whole
//! element row (too stiff). The exact director clamp instead sets the director of every clamp
//! edge to the clamp normal n_c, so the face next to the clamp sees α = ∠(n_f, n_c) about the
//! edge (see `bending.rs`, `EdgeDirector::Clamped`). The clamp may be rotated about the x axis
//! by σ (the lateral-buckling perturbation of the seed, §5).

use nalgebra::Rotation3;

use crate::geometry::Vec3;

/// Orientation of the clamp: a rotation by `sigma` (rad) about the x axis through the origin.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Clamp {
    /// Rotation of the clamp about x (rad).
    pub sigma: f64,
}

impl Clamp {
    fn rotation(&self) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vec3::x_axis(), self.sigma)
    }

    /// Clamp normal: the rest normal +y rotated by σ about x.
    pub fn normal(&self) -> Vec3 {
        self.rotation() * Vec3::y()
    }

    /// Prescribed position (m) of a clamped vertex with rest position `rest`.
    pub fn position(&self, rest: &Vec3) -> Vec3 {
        self.rotation() * rest
    }
}
