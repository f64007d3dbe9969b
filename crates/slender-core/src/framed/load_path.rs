//! What the load factor drives on a rod with material frames: the loads' scale
//! ([`RodLoadPath::loads`](crate::rod::RodLoadPath)) and the rigid motion of supports, as for
//! the discrete elastic rod (`rod/load_path.rs`): a moving support carries its vertices and the
//! frames its clamp holds exactly; as a first guess (no secant predictor yet) the free vertices
//! and frames follow a blend of the same motion, weight 1 next to the moving support and 0 next
//! to one that stays, linear in arc length between supports.

use nalgebra::UnitQuaternion;

use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::rod::SupportMotion;

use super::core::FramedCore;
use super::state::FramedState;

impl FramedCore {
    /// Makes the load factor move the support holding `vertices` rigidly, from 0 to 1: a
    /// rotation (vector, rad) about `pivot` and a translation (m); loads stay at their full
    /// value. Errors (and no path set) if a vertex is not held or a value is not finite.
    pub fn set_support_motion(
        &mut self,
        vertices: &[usize],
        pivot: Vec3,
        rotation: Vec3,
        translation: Vec3,
    ) -> Result<(), ModelError> {
        // The last path's vectors are reused: an interactive drag sets a motion per edit.
        self.end_moment_change();
        let mut path = std::mem::take(&mut self.load_path);
        path.set_single_motion(vertices, pivot, rotation, translation);
        // On an error `set_load_path` leaves the plain ramp (the path taken above).
        self.set_load_path(path)
    }

    /// Back to the plain load ramp (vectors kept for reuse: a motion that holds no vertex
    /// moves nothing).
    pub fn clear_load_path(&mut self) {
        self.end_moment_change();
        self.load_path.clear();
    }

    /// Moves the supports of `state` along the load path from `from` to `to`.
    pub(crate) fn impose_path(&self, state: &mut FramedState, from: f64, to: f64, guess: bool) {
        for m in &self.load_path.motions {
            self.move_support(state, m, from, to, guess);
        }
    }

    /// Weight of the point at arc length `s` in the blended guess of `motion`.
    fn blend_weight(&self, motion: &SupportMotion, s: f64) -> f64 {
        let weight_of = |u: usize| f64::from(u8::from(motion.vertices.contains(&u)));
        let at = |v: usize| self.arclengths[v];
        let fixed = &self.fixed_vertices;
        let left = fixed.iter().rev().find(|&&f| at(f) <= s).copied();
        let right = fixed.iter().find(|&&f| at(f) >= s).copied();
        match (left, right) {
            (Some(a), Some(b)) if a == b => weight_of(a),
            (Some(a), Some(b)) => {
                let u = (s - at(a)) / (at(b) - at(a));
                weight_of(a) * (1.0 - u) + weight_of(b) * u
            }
            (Some(a), None) => weight_of(a),
            (None, Some(b)) => weight_of(b),
            (None, None) => 0.0,
        }
    }

    /// Moves `motion`'s support in `state` from load factor `from` to `to`, in place.
    fn move_support(
        &self,
        state: &mut FramedState,
        motion: &SupportMotion,
        from: f64,
        to: f64,
        guess: bool,
    ) {
        if motion.vertices.is_empty() {
            // A cleared motion: nothing moves (every weight below would be 0).
            return;
        }
        let n = self.n_edges();
        // The moment loads' angles are continued from the frames before the move.
        let old = (!self.moments.is_empty()).then(|| state.clone());
        for v in 0..=n {
            let w = if motion.vertices.contains(&v) {
                1.0
            } else if guess {
                self.blend_weight(motion, self.arclengths[v])
            } else {
                0.0
            };
            if w != 0.0 {
                state.positions[v] = motion.carry(&state.positions[v], from, to, w);
            }
        }
        let turn = |w: f64| UnitQuaternion::from_scaled_axis(motion.rotation * ((to - from) * w));
        for j in 0..state.frames.len() {
            let held = self.fixed_frames.contains(&j);
            let w = if held {
                // A clamped node's frame belongs to its vertex.
                if motion.vertices.contains(&j) {
                    1.0
                } else {
                    0.0
                }
            } else if guess {
                self.blend_weight(motion, self.frame_arclengths[j])
            } else {
                0.0
            };
            if w != 0.0 {
                state.frames[j] = turn(w) * state.frames[j];
            }
        }
        for (end, v) in [(0, 0), (1, n)] {
            if let Some(c) = state.clamp_frames[end].as_mut() {
                if motion.vertices.contains(&v) {
                    *c = turn(1.0) * *c;
                }
            }
        }
        if let Some(old) = old {
            self.continue_moment_angles(&old, state);
        }
    }
}
