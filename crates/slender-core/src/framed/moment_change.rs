//! Changing a dead point moment along the load path, for the rods with material frames: the
//! interactive edit of a moment, as the discrete elastic rod does it (`rod/moment_change.rs`).
//!
//! During the edit the core carries the new moment in the old one's place, weighted λ, and
//! the old one appended last, weighted 1 − λ, each with its unwrapped angles in the state. At
//! λ = 0 the loads are exactly the old ones; at λ = 1 the new ones. The axial part's axis is
//! the frame's rest tangent for both, so its angle carries over; the bending part's angle
//! carries over when its axis is the same (±), else it starts from the frame's rotation from
//! rest (whole turns about a new axis are not known: they shift the potential by a constant).

use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::lie::twist_angle::twist_angle;

use super::core::FramedCore;
use super::moment::FrameMoment;
use super::state::FramedState;

impl FramedCore {
    /// Makes the load path the change of the dead point moment on vertex `v` from `old` to
    /// `new` (N m), in place (see the module docs). Returns the moment's index (for
    /// [`Self::undo_moment_change`]). Errors (nothing changed): no moment `old` on `v`, a
    /// value not finite.
    pub fn set_moment_change(
        &mut self,
        s: &mut FramedState,
        v: usize,
        old: Vec3,
        new: Vec3,
    ) -> Result<usize, ModelError> {
        if old.iter().chain(new.iter()).any(|c| !c.is_finite()) {
            return Err(ModelError::structure("moment_change", "must be finite"));
        }
        self.end_moment_change();
        let n = self.n_edges();
        if v > n {
            return Err(ModelError::structure(
                "moment_change.vertex",
                format!("vertex {v} is beyond the rod's {} vertices", n + 1),
            ));
        }
        let frame = (self.moment_slot)(v, n);
        let rest = self.rest.frames[frame];
        let before = FrameMoment::new(frame, old, rest);
        let Some(i) = self.moments.iter().position(|m| *m == before) else {
            return Err(ModelError::structure(
                "moment_change.vertex",
                format!("no dead moment {old:?} (N m) acts on vertex {v}"),
            ));
        };
        if s.moment_angles.len() != self.moments.len() {
            return Err(ModelError::structure(
                "moment_change",
                "the state does not belong to this rod (its moment angles)",
            ));
        }
        let after = FrameMoment::new(frame, new, rest);
        let angles_old = s.moment_angles[i];
        let (a_new, a_old) = (after.axes[0], before.axes[0]);
        let bending = if a_new.cross(&a_old).norm() <= 16.0 * f64::EPSILON {
            angles_old[0] * a_new.dot(&a_old).signum()
        } else {
            twist_angle(&after.relative(&s.frames[frame]), &a_new).value
        };
        self.load_path.begin_moment_change(
            &mut self.moments,
            &mut s.moment_angles,
            i,
            after,
            [bending, angles_old[1]],
        );
        Ok(i)
    }

    /// Ends a converged moment change in `s` (at λ = 1): the old moment, weighted zero there,
    /// and its angles are dropped and the load path cleared.
    pub fn finish_moment_change(&mut self, s: &mut FramedState) {
        self.load_path.end_moment_change(&mut self.moments);
        s.moment_angles.truncate(self.moments.len());
        self.clear_load_path();
    }

    /// Undoes [`Self::set_moment_change`] of moment `i`: its old value back in place, the load
    /// path cleared. The state is the caller's to restore.
    pub fn undo_moment_change(&mut self, i: usize) {
        self.load_path.undo_moment_change(&mut self.moments, i);
        self.clear_load_path();
    }

    /// See `RodLoadPath::end_moment_change`.
    pub(crate) fn end_moment_change(&mut self) {
        self.load_path.end_moment_change(&mut self.moments);
    }
}
