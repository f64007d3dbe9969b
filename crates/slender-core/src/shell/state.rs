//! Configuration of a shell: vertex positions and one director angle per edge.

use crate::geometry::Vec3;

use super::clamp::Clamp;

/// Positions (m) of all vertices (clamped ones included) and angles (rad) of all edges
/// (clamped edges keep 0: their director is the clamp normal).
#[derive(Clone, Debug, PartialEq)]
pub struct ShellState {
    /// Vertex positions (m).
    pub positions: Vec<Vec3>,
    /// Edge director angles φ (rad).
    pub angles: Vec<f64>,
    /// Pose of the clamp (its prescribed DOFs: the clamped vertices and the clamp normal).
    pub clamp: Clamp,
}
