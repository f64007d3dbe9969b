//! Changing a dead point moment along the load path: the interactive edit of a moment.
//!
//! A dead moment's potential is −M_b τ_n̂ − T τ_t̄ (see `moment.rs`), with τ_a the unwrapped
//! twist angle of its edge's material frame about the fixed axis a. A new value generally
//! has another axis n̂, so the old and new potentials cannot be blended in one term. During the edit the rod carries both: the
//! new moment in the old one's place, weighted λ, and the old one appended last, weighted
//! 1 − λ, each with its own angle in the state. At λ = 0 the loads are exactly the old ones
//! (the old angle keeps its whole turns), so the last equilibrium is still an equilibrium;
//! at λ = 1 they are the new ones. [`Rod::finish_moment_change`] then drops the old moment,
//! whose weight is zero.
//!
//! The new moment's angles start from the old ones when the axis is the same (±; the axial
//! axis always is), else the frame's twist angle about the new axis in (−2π, 2π]. Whole turns
//! about a new axis are not known; they shift the potential by a constant and change neither
//! forces nor Hessian.

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::model::Rod;
use super::moment::MomentLoad;
use super::state::RodState;

impl Rod {
    /// Makes the load path the change of the dead point moment on vertex `v` from `old` to
    /// `new` (N m), in place: the moment becomes `new` (weighted λ) and `old` is appended last
    /// (weighted 1 − λ), with their angles in `s`. Returns the moment's index (for
    /// [`Self::undo_moment_change`]). Errors (nothing changed): no dead moment `old` on `v`,
    /// a value not finite.
    pub fn set_moment_change(
        &mut self,
        s: &mut RodState,
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
        // The moment acts on the edge starting at the vertex (the last edge at the end), split
        // against its rest frame as the builder splits it: the same bits.
        let edge = v.min(n - 1);
        let rest = self.rest.material_frame(edge);
        let before = MomentLoad::new(edge, old, &rest);
        let Some(i) = self.moments.iter().position(|m| *m == before) else {
            return Err(ModelError::structure(
                "moment_change.vertex",
                format!("no dead moment {old:?} (N m) acts on vertex {v}"),
            ));
        };
        if s.load_angles.len() != self.moments.len() {
            return Err(ModelError::structure(
                "moment_change",
                "the state does not belong to this rod (its moment angles)",
            ));
        }
        let after = MomentLoad::new(edge, new, &rest);
        let angles_old = s.load_angles[i];
        let (a_new, a_old) = (after.axes()[0], before.axes()[0]);
        // The axial axis is the rest tangent for both: its angle carries on. So does the
        // bending angle about the same (±) axis; about a new one it starts in (−2π, 2π].
        let bending = if a_new.cross(&a_old).norm() <= 16.0 * f64::EPSILON {
            angles_old[0] * a_new.dot(&a_old).signum()
        } else {
            after.angles_of(&s.material_frame(edge))[0]
        };
        let angles_new = [bending, angles_old[1]];
        self.load_path.begin_moment_change(
            &mut self.moments,
            &mut s.load_angles,
            i,
            after,
            angles_new,
        );
        Ok(i)
    }

    /// Ends a converged moment change in `s` (at λ = 1): the old moment, weighted zero there,
    /// and its angle are dropped and the load path cleared. Does nothing without a change.
    pub fn finish_moment_change(&mut self, s: &mut RodState) {
        self.load_path.end_moment_change(&mut self.moments);
        s.load_angles.truncate(self.moments.len());
        self.clear_load_path();
    }

    /// Undoes [`Self::set_moment_change`] of moment `i`: its old value back in place, the load
    /// path cleared. The state is the caller's to restore (it holds one angle too many).
    pub fn undo_moment_change(&mut self, i: usize) {
        self.load_path.undo_moment_change(&mut self.moments, i);
        self.clear_load_path();
    }

    /// See [`RodLoadPath::end_moment_change`](super::RodLoadPath::end_moment_change).
    pub(crate) fn end_moment_change(&mut self) {
        self.load_path.end_moment_change(&mut self.moments);
    }
}
