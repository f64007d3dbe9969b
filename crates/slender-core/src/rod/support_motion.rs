//! Prescribed motion of supports: moving or rotating a clamp or a pin.
//!
//! The fixed DOFs of a rod live in its state (positions of fixed vertices, clamp frames), so
//! moving a support is a new state: the support's vertices moved rigidly, a clamp's ghost
//! edge rotated with it, and the free vertices moved by a blend of the same rigid motion as a
//! first guess for the next equilibrium (weight 1 next to the moving support, 0 next to a
//! support that stays, linear in arc length between them).

use nalgebra::Rotation3;

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::frames::{EdgeFrame, GhostEdge};
use super::model::Rod;
use super::state::RodState;

/// A rigid motion of one support: x ↦ pivot + R (x − pivot) + translation.
#[derive(Clone, Debug, PartialEq)]
pub struct SupportMotion {
    /// The support's fixed vertices (one for a clamp or pin, two for a clip).
    pub vertices: Vec<usize>,
    /// Centre of the rotation (m), usually the support's vertex.
    pub pivot: Vec3,
    /// Rotation vector (rad): axis × angle.
    pub rotation: Vec3,
    /// Translation (m).
    pub translation: Vec3,
}

impl SupportMotion {
    /// The motion scaled by `w` ∈ [0, 1] (rotation angle and translation), applied to `x`.
    fn apply(&self, x: &Vec3, w: f64) -> Vec3 {
        let r = Rotation3::new(self.rotation * w);
        self.pivot + r * (x - self.pivot) + self.translation * w
    }
}

impl Rod {
    /// A state like `state` with the support moved by `motion`: its vertices (and a clamp's
    /// frame) moved exactly, the free vertices moved by a blended guess, frames transported.
    /// The result is not an equilibrium; solve from it. Rotations per call should stay well
    /// below π so that the reference twists can be continued.
    pub fn with_support_moved(
        &self,
        state: &RodState,
        motion: &SupportMotion,
    ) -> Result<RodState, ModelError> {
        let n = self.n_edges();
        for &v in &motion.vertices {
            if !self.fixed_vertices.contains(&v) {
                return Err(ModelError::structure(
                    "support_motion.vertices",
                    format!("vertex {v} is not held by a support; only supports can be moved"),
                ));
            }
        }
        let finite = motion
            .pivot
            .iter()
            .chain(motion.rotation.iter())
            .chain(motion.translation.iter())
            .all(|c| c.is_finite());
        if !finite {
            return Err(ModelError::structure(
                "support_motion",
                "pivot, rotation and translation must be finite",
            ));
        }
        // Weight of every vertex: 1 on moved supports, 0 on the others, interpolated in
        // arc length between consecutive supports and constant past the outermost ones.
        let arclength: Vec<f64> = std::iter::once(0.0)
            .chain(self.rest_lengths.iter().scan(0.0, |s, l| {
                *s += l;
                Some(*s)
            }))
            .collect();
        let weight_of = |v: usize| f64::from(u8::from(motion.vertices.contains(&v)));
        let fixed = &self.fixed_vertices;
        let mut w = vec![0.0; n + 1];
        for (v, wv) in w.iter_mut().enumerate() {
            let left = fixed.iter().rev().find(|&&f| f <= v).copied();
            let right = fixed.iter().find(|&&f| f >= v).copied();
            *wv = match (left, right) {
                (Some(a), Some(b)) if a == b => weight_of(a),
                (Some(a), Some(b)) => {
                    let u = (arclength[v] - arclength[a]) / (arclength[b] - arclength[a]);
                    weight_of(a) * (1.0 - u) + weight_of(b) * u
                }
                (Some(a), None) => weight_of(a),
                (None, Some(b)) => weight_of(b),
                (None, None) => 0.0,
            };
        }
        let mut moved = state.clone();
        for ((p, x), &wv) in moved.positions.iter_mut().zip(&state.positions).zip(&w) {
            *p = motion.apply(x, wv);
        }
        let r = Rotation3::new(motion.rotation);
        let rotate_ghost = |g: &Option<GhostEdge>, v: usize| {
            g.map(|g| {
                if motion.vertices.contains(&v) {
                    GhostEdge {
                        frame: EdgeFrame {
                            tangent: r * g.frame.tangent,
                            a1: r * g.frame.a1,
                        },
                        ..g
                    }
                } else {
                    g
                }
            })
        };
        // Frames are continued from the old ones, whose ghosts are replaced first so that the
        // clamp hinges' reference twists are continued across the rotation.
        let mut old = state.clone();
        old.frames.ghost_start = rotate_ghost(&state.frames.ghost_start, 0);
        old.frames.ghost_end = rotate_ghost(&state.frames.ghost_end, n);
        let mut out = moved.clone();
        old.frames
            .transport_into(&moved.positions, &self.hinge_edges, &mut out.frames);
        self.update_load_angles(state, &mut out);
        Ok(out)
    }
}
