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

/// Pose of the clamp: a rigid motion (rotation, then translation) of the clamped edge from its
/// rest position. The lateral-buckling protocol turns it about x by σ ([`Clamp::about_x`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clamp {
    /// Rotation of the clamp from its rest orientation.
    pub rotation: Rotation3<f64>,
    /// Translation (m) applied after the rotation.
    pub translation: Vec3,
}

impl Default for Clamp {
    fn default() -> Self {
        Self::about_x(0.0)
    }
}

impl Clamp {
    /// The clamp turned by `sigma` (rad) about the x axis through the origin.
    pub fn about_x(sigma: f64) -> Self {
        Self {
            rotation: Rotation3::from_axis_angle(&Vec3::x_axis(), sigma),
            translation: Vec3::zeros(),
        }
    }

    /// Clamp normal: the rest normal +y rotated with the clamp.
    pub fn normal(&self) -> Vec3 {
        self.rotation * Vec3::y()
    }

    /// Prescribed position (m) of a clamped vertex with rest position `rest`.
    pub fn position(&self, rest: &Vec3) -> Vec3 {
        self.rotation * rest + self.translation
    }

    /// This clamp moved rigidly by x ↦ R x + c.
    pub fn moved(&self, rotation: &Rotation3<f64>, offset: &Vec3) -> Self {
        Self {
            rotation: rotation * self.rotation,
            translation: rotation * self.translation + offset,
        }
    }
}
