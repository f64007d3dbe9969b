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
}

impl Rod {
    /// The dead loads equivalent to every follower load in `s`'s current material frames.
    pub(super) fn follower_loads<'a>(
        &'a self,
        s: &'a RodState,
    ) -> impl Iterator<Item = FollowerState> + 'a {
        let rest = &self.rest;
        self.followers.iter().map(move |f| {
            let j = f.edge;
            let now = s.material_frame(j);
            let then = rest.material_frame(j);
            // R maps the rest material frame onto the current one.
            let turn = |v: &Vec3| {
                now[0] * then[0].dot(v) + now[1] * then[1].dot(v) + now[2] * then[2].dot(v)
            };
            let force = turn(&f.force);
            let moment = turn(&f.moment);
            let e = s.positions[j + 1] - s.positions[j];
            let len = e.norm();
            let t = e / len;
            FollowerState {
                force,
                couple: moment.cross(&t) / len,
                torque: moment.dot(&t),
            }
        })
    }

    /// Refreshes the frozen follower loads of `s` from its frames; returns the largest change
    /// relative to the loads' size (0 without follower loads).
    pub(super) fn refresh_followers(&self, s: &mut RodState) -> f64 {
        let mut change: f64 = 0.0;
        let mut size: f64 = 0.0;
        let fresh: Vec<FollowerState> = self.follower_loads(s).collect();
        for (old, new) in s.followers.iter_mut().zip(fresh) {
            let d = (new.force - old.force).norm()
                + (new.couple - old.couple).norm()
                + (new.torque - old.torque).abs() / self.length;
            size = size.max(new.force.norm() + new.couple.norm() + new.torque.abs() / self.length);
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
