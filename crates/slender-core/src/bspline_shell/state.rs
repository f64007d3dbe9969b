//! Configuration of a B-spline shell: its control points, the poses of its clamps and the
//! memory of the Newton update.

use nalgebra::Vector3;

use crate::geometry::Vec3;
use crate::shell::Clamp;

/// Control points (m, clamped rows included), clamp poses, and the second-order strain of
/// the Newton step that produced the state.
#[derive(Debug, PartialEq)]
pub struct BsplineState {
    /// Control points, index i·n_v + j (i along the length, j across).
    pub control_points: Vec<Vec3>,
    /// Poses of the clamps at the start (u = 0) and the end (u = L), indexed by
    /// [`StripEnd`](super::StripEnd); the pose of an end that is not clamped is unused.
    pub clamps: [Clamp; 2],
    /// Second-order part (m⁰: the parameters are lengths) of the change of the first
    /// fundamental form at each Gauss point over the Newton step that produced this state
    /// (the mixed-integration-point update, see [`crate::shell::mixed_update`]); empty when
    /// the state was not produced by a step (r = 0 everywhere: the exact Hessian).
    pub membrane_remainder: Vec<Vector3<f64>>,
}
/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone): the
/// solvers copy states into their workspaces on every re-solve.
impl Clone for BsplineState {
    fn clone(&self) -> Self {
        Self {
            control_points: self.control_points.clone(),
            clamps: self.clamps,
            membrane_remainder: self.membrane_remainder.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.control_points.clone_from(&source.control_points);
        self.clamps = source.clamps;
        self.membrane_remainder
            .clone_from(&source.membrane_remainder);
    }
}
