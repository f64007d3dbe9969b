//! Follower loads: a force or moment given in the rod's material frame at a vertex, turning
//! with the rod there.
//!
//! A follower load has no potential (it does work around closed paths), so it cannot enter the
//! energy the solver minimizes as it stands. It is applied *lagged*: the state carries its
//! current direction, which acts as a dead load during a Newton solve; after the solve the
//! direction is refreshed from the new material frame
//! ([`EquilibriumProblem::refresh_loads`](crate::solver::EquilibriumProblem::refresh_loads))
//! and the solve repeated until the direction no longer changes. The end state is an
//! equilibrium under the follower load. (Its Hessian inertia is that of the frozen load: the
//! stability of a non-conservative load is a dynamic question, and is reported as such.)
//!
//! A moment M on edge j acts as the couple of forces ±(M × t)/|e| on the edge's vertices (the
//! part that turns the tangent) plus the torque M·t on the edge angle.

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::model::Rod;
use super::state::RodState;

/// A follower load on a vertex, turning with the material frame of `edge`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FollowerLoad {
    /// The loaded vertex.
    pub vertex: usize,
    /// The edge whose material frame the load turns with (the one starting at the vertex; the
    /// last edge at the rod's end).
    pub edge: usize,
    /// Force (N) in world axes at rest.
    pub force: Vec3,
    /// Moment (N m) in world axes at rest.
    pub moment: Vec3,
}

/// The current (frozen) dead loads standing in for a follower load.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct FollowerState {
    /// Force on the vertex (N).
    pub force: Vec3,
    /// Force on the edge's end vertex, minus on its start vertex (N): the moment's couple.
    pub couple: Vec3,
    /// Torque on the edge angle (N m).
    pub torque: f64,
    /// While the load path changes this follower force (an interactive edit, see
    /// [`RodLoadPath::follower_change`](super::RodLoadPath::follower_change)): its force at
    /// λ = 0 minus its force at λ = 1, turned like `force` (N); the vertex carries this times
    /// (1 − λ) on top of `force`. Zero otherwise.
    pub transition: Vec3,
    /// As `transition`, for a follower moment changed along the path
    /// ([`RodLoadPath::follower_moment_change`](super::RodLoadPath::follower_moment_change)):
    /// the couple of the moment at λ = 0 minus at λ = 1 (N). Zero otherwise.
    pub transition_couple: Vec3,
    /// The same change's torque on the edge angle (N m). Zero otherwise.
    pub transition_torque: f64,
}

impl Rod {
    /// The force (N) on the vertex of follower load `i` in its frozen state `now`, at load
    /// factor `load` (the path's factor on the loads) and path parameter `lambda`: the
    /// transition counts only while the path changes this follower (a state keeps the last
    /// one it was refreshed with until its next refresh).
    pub(super) fn follower_force(
        &self,
        i: usize,
        now: &FollowerState,
        load: f64,
        lambda: f64,
    ) -> Vec3 {
        match self.load_path.follower_change {
            Some((k, _)) if k == i => now.force * load + now.transition * (1.0 - lambda),
            _ => now.force * load,
        }
    }

    /// The couple (N) and torque (N m) of follower load `i` in its frozen state `now`, at load
    /// factor `load` and path parameter `lambda` (the moment's transition counts only while
    /// the path changes this follower's moment, as for the force).
    pub(super) fn follower_couple(
        &self,
        i: usize,
        now: &FollowerState,
        load: f64,
        lambda: f64,
    ) -> (Vec3, f64) {
        match self.load_path.follower_moment_change {
            Some((k, _)) if k == i => (
                now.couple * load + now.transition_couple * (1.0 - lambda),
                now.torque * load + now.transition_torque * (1.0 - lambda),
            ),
            _ => (now.couple * load, now.torque * load),
        }
    }

    /// The dead loads equivalent to every follower load in `s`'s current material frames.
    pub(super) fn follower_loads<'a>(
        &'a self,
        s: &'a RodState,
    ) -> impl Iterator<Item = FollowerState> + 'a {
        let rest = &self.rest;
        let change = self.load_path.follower_change;
        let moment_change = self.load_path.follower_moment_change;
        self.followers.iter().enumerate().map(move |(i, f)| {
            let j = f.edge;
            let now = s.material_frame(j);
            let then = rest.material_frame(j);
            // R maps the rest material frame onto the current one.
            let turn = |v: &Vec3| {
                now[0] * then[0].dot(v) + now[1] * then[1].dot(v) + now[2] * then[2].dot(v)
            };
            let force = turn(&f.force);
            let moment = turn(&f.moment);
            let transition = match change {
                Some((k, delta)) if k == i => turn(&delta),
                _ => Vec3::zeros(),
            };
            let moment_transition = match moment_change {
                Some((k, delta)) if k == i => turn(&delta),
                _ => Vec3::zeros(),
            };
            let e = s.positions[j + 1] - s.positions[j];
            let len = e.norm();
            let t = e / len;
            FollowerState {
                force,
                couple: moment.cross(&t) / len,
                torque: moment.dot(&t),
                transition,
                transition_couple: moment_transition.cross(&t) / len,
                transition_torque: moment_transition.dot(&t),
            }
        })
    }

    /// Refreshes the frozen follower loads of `s` from its frames; returns the largest change
    /// relative to the loads' size (0 without follower loads).
    pub(super) fn refresh_followers(&self, s: &mut RodState) -> f64 {
        let mut change: f64 = 0.0;
        let mut size: f64 = 0.0;
        let fresh: Vec<FollowerState> = self.follower_loads(s).collect();
        let change_of = self.load_path.follower_change.map(|(k, _)| k);
        let moment_change_of = self.load_path.follower_moment_change.map(|(k, _)| k);
        for (i, (old, new)) in s.followers.iter_mut().zip(fresh).enumerate() {
            // A transition left from an earlier path is not applied (see `follower_force`):
            // its clearing is no change of the loads.
            let transition = if change_of == Some(i) {
                (new.transition - old.transition).norm()
            } else {
                0.0
            };
            let moment_transition = if moment_change_of == Some(i) {
                (new.transition_couple - old.transition_couple).norm()
                    + (new.transition_torque - old.transition_torque).abs() / self.length
            } else {
                0.0
            };
            let d = (new.force - old.force).norm()
                + transition
                + moment_transition
                + (new.couple - old.couple).norm()
                + (new.torque - old.torque).abs() / self.length;
            size = size.max(
                new.force.norm()
                    + new.transition.norm()
                    + new.transition_couple.norm()
                    + new.transition_torque.abs() / self.length
                    + new.couple.norm()
                    + new.torque.abs() / self.length,
            );
            change = change.max(d);
            *old = new;
        }
        if size > 0.0 {
            change / size
        } else {
            0.0
        }
    }
}

/// Which part of a follower load an edit changes.
#[derive(Clone, Copy)]
enum FollowerPart {
    Force,
    Moment,
}

/// Numbers per follower load in [`Rod::append_lagged_loads`]: force (3), couple (3), torque
/// (1), the transitions of force (3), couple (3) and torque (1).
const LAGGED_PER_FOLLOWER: usize = 14;

impl Rod {
    /// True if the rod carries follower loads.
    pub fn has_follower_loads(&self) -> bool {
        !self.followers.is_empty()
    }

    /// Appends the frozen follower loads of `s` to `out` ([`LAGGED_PER_FOLLOWER`] numbers
    /// each: force and couple (N), torque (N m), the transitions of force and couple (N) and
    /// of torque (N m)).
    pub(crate) fn append_lagged_loads(&self, s: &RodState, out: &mut Vec<f64>) {
        for f in &s.followers {
            out.extend(f.force.iter().chain(f.couple.iter()));
            out.push(f.torque);
            out.extend(f.transition.iter().chain(f.transition_couple.iter()));
            out.push(f.transition_torque);
        }
    }

    /// Sets the frozen follower loads of `s` from the front of `values` (as
    /// [`Self::append_lagged_loads`] lists them) and returns the rest.
    pub(crate) fn take_lagged_loads<'a>(&self, s: &mut RodState, values: &'a [f64]) -> &'a [f64] {
        let n = s.followers.len() * LAGGED_PER_FOLLOWER;
        let (mine, rest) = values.split_at(n.min(values.len()));
        for (f, v) in s
            .followers
            .iter_mut()
            .zip(mine.chunks_exact(LAGGED_PER_FOLLOWER))
        {
            f.force = Vec3::new(v[0], v[1], v[2]);
            f.couple = Vec3::new(v[3], v[4], v[5]);
            f.torque = v[6];
            f.transition = Vec3::new(v[7], v[8], v[9]);
            f.transition_couple = Vec3::new(v[10], v[11], v[12]);
            f.transition_torque = v[13];
        }
        rest
    }
}

impl Rod {
    /// Makes the load path the change of the follower force on vertex `v` from `old` to `new`
    /// (N, given at rest like the scene's `force`), in place: that follower's rest force becomes
    /// `new`, the path carries `old − new` times (1 − λ) turned with the rod, and the frozen
    /// loads of `s` are refreshed so that at λ = 0 the vertex carries exactly the old load.
    /// Returns the follower's index (for [`Self::undo_follower_force_change`]). Errors (nothing
    /// changed) if no follower force `old` (without a moment) acts on `v`, or a value is not
    /// finite.
    pub fn set_follower_force_change(
        &mut self,
        s: &mut RodState,
        v: usize,
        old: Vec3,
        new: Vec3,
    ) -> Result<usize, ModelError> {
        self.change_follower(s, v, old, new, FollowerPart::Force)
    }

    /// The force (N) in space now of the follower force `force` (given at rest) on vertex `v`
    /// in state `s`: turned with the material frame of its edge. `None` if there is no such
    /// follower force.
    pub fn follower_force_in(&self, s: &RodState, v: usize, force: Vec3) -> Option<Vec3> {
        let i = self
            .followers
            .iter()
            .position(|f| f.vertex == v && f.force == force && f.moment == Vec3::zeros())?;
        self.follower_loads(s).nth(i).map(|f| f.force)
    }

    /// The moment (N m) in space now of the follower moment `moment` (given at rest) on vertex
    /// `v` in state `s`: turned with the material frame of its edge. `None` if there is no
    /// such follower moment.
    pub fn follower_moment_in(&self, s: &RodState, v: usize, moment: Vec3) -> Option<Vec3> {
        let f = self
            .followers
            .iter()
            .find(|f| f.vertex == v && f.moment == moment && f.force == Vec3::zeros())?;
        let (now, then) = (s.material_frame(f.edge), self.rest.material_frame(f.edge));
        Some(
            now[0] * then[0].dot(&moment)
                + now[1] * then[1].dot(&moment)
                + now[2] * then[2].dot(&moment),
        )
    }

    /// Undoes [`Self::set_follower_force_change`]: follower `i`'s rest force back to `old`
    /// (N), the load path cleared. The state's frozen loads are the caller's to restore.
    pub fn undo_follower_force_change(&mut self, i: usize, old: Vec3) {
        self.followers[i].force = old;
        self.clear_load_path();
    }

    /// As [`Self::set_follower_force_change`], for the follower moment on vertex `v`: from
    /// `old` to `new` (N m, given at rest like the scene's `moment`). The path carries
    /// `old − new` times (1 − λ), turned with the rod, as a couple on the edge's vertices and a
    /// torque on its angle. Returns the follower's index (for
    /// [`Self::undo_follower_moment_change`]). Errors (nothing changed) if no follower moment
    /// `old` (without a force) acts on `v`, or a value is not finite.
    pub fn set_follower_moment_change(
        &mut self,
        s: &mut RodState,
        v: usize,
        old: Vec3,
        new: Vec3,
    ) -> Result<usize, ModelError> {
        self.change_follower(s, v, old, new, FollowerPart::Moment)
    }

    /// The change of `part` of the follower on vertex `v` (the other part zero) from `old` to
    /// `new`, given at rest, as [`Self::set_follower_force_change`] and
    /// [`Self::set_follower_moment_change`] describe it.
    fn change_follower(
        &mut self,
        s: &mut RodState,
        v: usize,
        old: Vec3,
        new: Vec3,
        part: FollowerPart,
    ) -> Result<usize, ModelError> {
        let (field, what, unit) = match part {
            FollowerPart::Force => ("follower_change", "force", "N"),
            FollowerPart::Moment => ("follower_moment_change", "moment", "N m"),
        };
        if old.iter().chain(new.iter()).any(|c| !c.is_finite()) {
            return Err(ModelError::structure(field, "must be finite"));
        }
        let Some(i) = self.followers.iter().position(|f| {
            let (this, other) = match part {
                FollowerPart::Force => (f.force, f.moment),
                FollowerPart::Moment => (f.moment, f.force),
            };
            f.vertex == v && this == old && other == Vec3::zeros()
        }) else {
            return Err(ModelError::structure(
                format!("{field}.vertex"),
                format!("no follower {what} {old:?} ({unit}) acts on vertex {v}"),
            ));
        };
        self.end_moment_change();
        self.load_path.clear();
        self.load_path.loads = [1.0, 1.0];
        let change = Some((i, old - new));
        match part {
            FollowerPart::Force => {
                self.load_path.follower_change = change;
                self.followers[i].force = new;
            }
            FollowerPart::Moment => {
                self.load_path.follower_moment_change = change;
                self.followers[i].moment = new;
            }
        }
        // The frames are those of `s`: the refresh only re-splits the same load into the new
        // value and the transition.
        self.refresh_followers(s);
        Ok(i)
    }

    /// Undoes [`Self::set_follower_moment_change`]: follower `i`'s rest moment back to `old`
    /// (N m), the load path cleared. The state's frozen loads are the caller's to restore.
    pub fn undo_follower_moment_change(&mut self, i: usize, old: Vec3) {
        self.followers[i].moment = old;
        self.clear_load_path();
    }
}
