//! Configuration of a shell: vertex positions and one director angle per edge.

use nalgebra::Vector3;

use crate::geometry::Vec3;

use super::clamp::Clamp;

/// Positions (m) of all vertices (clamped ones included) and angles (rad) of all edges
/// (clamped edges keep 0: their director is the clamp normal), and the memory of the Newton
/// update.
#[derive(Debug, PartialEq)]
pub struct ShellState {
    /// Vertex positions (m).
    pub positions: Vec<Vec3>,
    /// Edge director angles φ (rad).
    pub angles: Vec<f64>,
    /// Poses of the clamps at the start (x = 0) and the end (x = L), indexed by
    /// [`StripEnd::index`](crate::bspline_shell::StripEnd::index) (their prescribed DOFs: the
    /// clamped vertices and the clamp normal); the pose of an end that is not clamped is
    /// unused.
    pub clamps: [Clamp; 2],
    /// Second-order part (m²) of each face's change of first fundamental form over the
    /// Newton step that produced this state (see [`mixed_update`](super::mixed_update));
    /// empty when the state was not produced by a step (then r = 0 on every face).
    pub membrane_remainder: Vec<Vector3<f64>>,
}
/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone): the
/// solvers copy states into their workspaces on every re-solve.
impl Clone for ShellState {
    fn clone(&self) -> Self {
        Self {
            positions: self.positions.clone(),
            angles: self.angles.clone(),
            clamps: self.clamps,
            membrane_remainder: self.membrane_remainder.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.positions.clone_from(&source.positions);
        self.angles.clone_from(&source.angles);
        self.clamps = source.clamps;
        self.membrane_remainder
            .clone_from(&source.membrane_remainder);
    }
}
