//! The members a structure is made of, behind one interface (an enum: a structure may mix
//! formulations).
//!
//! The discrete elastic rod works on the structure's DOF vector in place (its methods take
//! the member's slice of a global vector as a closure). The framed rods (Cosserat, SE(3))
//! work through their [`EquilibriumProblem`] on a local vector gathered from that closure: a
//! short allocation per call, which only structures with framed members pay.

use crate::assembly::Assembler;
use crate::cosserat::CosseratRod;
use crate::framed::{FramedCore, FramedModel, FramedState};
use crate::linalg::SymmetricMatrix;
use crate::rod::{Rod, RodState};
use crate::se3::Se3Rod;
use crate::solver::{EquilibriumProblem, MassMetric};

/// A member of a structure.
#[derive(Clone, Debug)]
pub enum Member {
    /// A discrete elastic rod.
    Der(Rod),
    /// A discrete Cosserat rod.
    Cosserat(CosseratRod),
    /// A geometrically exact SE(3) beam.
    Se3(Se3Rod),
}

/// The state of a member.
#[derive(Debug, PartialEq)]
pub enum MemberState {
    /// A discrete elastic rod's state.
    Der(RodState),
    /// A Cosserat rod's or SE(3) beam's state.
    Framed(FramedState),
}

/// Written out so that `clone_from` between states of the same model reuses the buffers.
impl Clone for MemberState {
    fn clone(&self) -> Self {
        match self {
            Self::Der(s) => Self::Der(s.clone()),
            Self::Framed(s) => Self::Framed(s.clone()),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        match (self, source) {
            (Self::Der(a), Self::Der(b)) => a.clone_from(b),
            (Self::Framed(a), Self::Framed(b)) => a.clone_from(b),
            (a, b) => *a = b.clone(),
        }
    }
}

impl MemberState {
    /// The rod state, if this is a discrete elastic rod.
    pub fn as_der(&self) -> Option<&RodState> {
        match self {
            Self::Der(s) => Some(s),
            Self::Framed(_) => None,
        }
    }

    /// The framed state, if this is a Cosserat rod or an SE(3) beam.
    pub fn as_framed(&self) -> Option<&FramedState> {
        match self {
            Self::Framed(s) => Some(s),
            Self::Der(_) => None,
        }
    }

    /// Vertex positions (m).
    pub fn positions(&self) -> &[crate::geometry::Vec3] {
        match self {
            Self::Der(s) => s.positions(),
            Self::Framed(s) => s.positions(),
        }
    }
}

macro_rules! der {
    ($s:expr) => {
        match $s {
            MemberState::Der(s) => s,
            MemberState::Framed(_) => unreachable!("a discrete elastic rod has a rod state"),
        }
    };
}

macro_rules! framed {
    ($s:expr) => {
        match $s {
            MemberState::Framed(s) => s,
            MemberState::Der(_) => unreachable!("a framed rod has a framed state"),
        }
    };
}

/// Runs `$body` with `$r` bound to the framed model of `$m` (Cosserat or SE(3)), or `$der`
/// for a discrete elastic rod bound to `$d`.
macro_rules! by_model {
    ($m:expr, $d:ident => $der:expr, $r:ident => $body:expr) => {
        match $m {
            Member::Der($d) => $der,
            Member::Cosserat($r) => $body,
            Member::Se3($r) => $body,
        }
    };
}

/// The member's own free DOF step as a local vector.
fn gather(n: usize, dx: impl Fn(usize) -> f64) -> Vec<f64> {
    (0..n).map(dx).collect()
}

/// Calls `f` with every term's stencil of a framed model (its Hessian's sparsity pattern).
fn framed_stencils<T: FramedModel + EquilibriumProblem>(r: &T, f: impl FnMut(&[usize])) {
    // The framed models' terms touch a contiguous band of their DOF layout: the band of
    // half-width HALF_BANDWIDTH is a (slightly conservative) cover of every stencil.
    let mut f = f;
    let n = r.n_free();
    let hb = T::HALF_BANDWIDTH;
    let mut window = Vec::with_capacity(hb + 1);
    for i in 0..n {
        window.clear();
        window.extend(i..(i + hb + 1).min(n));
        f(&window);
    }
}

impl Member {
    /// The rod, if this is a discrete elastic rod.
    pub fn as_der(&self) -> Option<&Rod> {
        match self {
            Self::Der(r) => Some(r),
            _ => None,
        }
    }

    /// Mutable access to the rod.
    pub fn as_der_mut(&mut self) -> Option<&mut Rod> {
        match self {
            Self::Der(r) => Some(r),
            _ => None,
        }
    }

    /// The shared part of a Cosserat rod or SE(3) beam.
    pub fn as_framed(&self) -> Option<&FramedCore> {
        match self {
            Self::Der(_) => None,
            Self::Cosserat(r) => Some(&r.core),
            Self::Se3(r) => Some(&r.core),
        }
    }

    /// Mutable access to the shared part of a Cosserat rod or SE(3) beam.
    pub fn as_framed_mut(&mut self) -> Option<&mut FramedCore> {
        match self {
            Self::Der(_) => None,
            Self::Cosserat(r) => Some(&mut r.core),
            Self::Se3(r) => Some(&mut r.core),
        }
    }

    /// The formulation's name in scene files (`der`, `cosserat`, `se3`).
    pub fn model_name(&self) -> &'static str {
        match self {
            Self::Der(_) => "der",
            Self::Cosserat(_) => "cosserat",
            Self::Se3(_) => "se3",
        }
    }

    /// Rest length (m).
    pub fn length(&self) -> f64 {
        by_model!(self, r => r.length(), r => r.length())
    }

    /// Number of elements (edges).
    pub fn n_edges(&self) -> usize {
        by_model!(self, r => r.n_edges(), r => r.n_edges())
    }

    /// Number of the member's own free DOFs.
    pub fn n_free(&self) -> usize {
        by_model!(self, r => r.n_free(), r => EquilibriumProblem::n_free(r))
    }

    /// The rest state.
    pub fn rest_state(&self) -> MemberState {
        by_model!(self, r => MemberState::Der(r.rest_state().clone()),
            r => MemberState::Framed(r.rest_state().clone()))
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.n_edges() + 1
    }

    /// Runs the member's terms through `asm` (a part assembler mapping its DOFs).
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        state: &MemberState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        by_model!(self, r => r.assemble_into(der!(state), load, asm),
            r => r.assemble_into(framed!(state), load, asm))
    }

    /// The retraction with the member's step given by `dx`.
    pub fn displace_by(
        &self,
        state: &MemberState,
        dx: impl Fn(usize) -> f64,
        alpha: f64,
        out: &mut MemberState,
    ) {
        match (self, out) {
            (Self::Der(r), MemberState::Der(o)) => r.retract_by(der!(state), dx, alpha, o),
            (Self::Cosserat(r), MemberState::Framed(o)) => {
                r.displace(framed!(state), &gather(r.n_free(), dx), alpha, o)
            }
            (Self::Se3(r), MemberState::Framed(o)) => {
                r.displace(framed!(state), &gather(r.n_free(), dx), alpha, o)
            }
            _ => unreachable!("member and state of different models"),
        }
    }

    /// [`Self::displace_by`] with the member's own step as a slice (a member whose DOFs are a
    /// contiguous range of the structure's): the framed models take it as it is, without a
    /// gathered copy.
    pub fn displace_slice(
        &self,
        state: &MemberState,
        dx: &[f64],
        alpha: f64,
        out: &mut MemberState,
    ) {
        match (self, out) {
            (Self::Der(r), MemberState::Der(o)) => r.retract_by(der!(state), |i| dx[i], alpha, o),
            (Self::Cosserat(r), MemberState::Framed(o)) => r.displace(framed!(state), dx, alpha, o),
            (Self::Se3(r), MemberState::Framed(o)) => r.displace(framed!(state), dx, alpha, o),
            _ => unreachable!("member and state of different models"),
        }
    }

    /// The chart (see [`EquilibriumProblem::chart`]) with the member's step given by `dx`.
    pub fn chart_by(&self, state: &MemberState, dx: impl Fn(usize) -> f64, out: &mut MemberState) {
        match (self, out) {
            (Self::Der(r), MemberState::Der(o)) => r.displace_linear_by(der!(state), dx, 1.0, o),
            (Self::Cosserat(r), MemberState::Framed(o)) => {
                r.chart(framed!(state), &gather(r.n_free(), dx), o)
            }
            (Self::Se3(r), MemberState::Framed(o)) => {
                r.chart(framed!(state), &gather(r.n_free(), dx), o)
            }
            _ => unreachable!("member and state of different models"),
        }
    }

    /// Calls `f(i, d)` with the difference `a ⊖ b` of every own free DOF `i`.
    pub fn difference(&self, a: &MemberState, b: &MemberState, mut f: impl FnMut(usize, f64)) {
        by_model!(self, r => {
            let (a, b) = (der!(a), der!(b));
            for i in 0..r.n_free() {
                f(i, r.dof_value(a, i) - r.dof_value(b, i));
            }
        }, r => {
            let mut d = vec![0.0; EquilibriumProblem::n_free(r)];
            r.difference(framed!(a), framed!(b), &mut d);
            for (i, v) in d.into_iter().enumerate() {
                f(i, v);
            }
        })
    }

    /// The member's step cap for the step `dx`.
    pub fn max_step_by(&self, state: &MemberState, dx: impl Fn(usize) -> f64 + Copy) -> f64 {
        by_model!(self, r => r.max_step_by(der!(state), dx),
            r => r.max_step(framed!(state), &gather(EquilibriumProblem::n_free(r), dx)))
    }

    /// [`Self::max_step_by`] with the member's own step as a slice (see
    /// [`Self::displace_slice`]).
    pub fn max_step_slice(&self, state: &MemberState, dx: &[f64]) -> f64 {
        by_model!(self, r => r.max_step_by(der!(state), |i| dx[i]),
            r => r.max_step(framed!(state), dx))
    }

    /// See [`EquilibriumProblem::force_length`].
    pub fn force_length(&self, i: usize) -> f64 {
        by_model!(self, r => r.force_length(i), r => EquilibriumProblem::force_length(r, i))
    }

    /// See [`EquilibriumProblem::dof_magnitude`].
    pub fn dof_magnitude(&self, state: &MemberState, i: usize) -> f64 {
        by_model!(self, r => r.dof_magnitude(der!(state), i),
            r => EquilibriumProblem::dof_magnitude(r, framed!(state), i))
    }

    /// Calls `f(i, force_length, dof_magnitude)` for every own free DOF i, in order: one
    /// dispatch on the model for all of them.
    pub fn dof_scales_each(&self, state: &MemberState, mut f: impl FnMut(usize, f64, f64)) {
        by_model!(self, r => r.dof_scales_each(der!(state), f), r => {
            let s = framed!(state);
            for i in 0..r.n_free() {
                f(i, EquilibriumProblem::force_length(r, i), EquilibriumProblem::dof_magnitude(r, s, i));
            }
        })
    }

    /// See [`MassMetric::inertia_metric`].
    pub fn inertia_metric(&self, i: usize) -> f64 {
        by_model!(self, r => r.inertia_metric(i), r => MassMetric::inertia_metric(r, i))
    }

    /// See [`MassMetric::eigenvalue_scale`].
    pub fn eigenvalue_scale(&self) -> f64 {
        by_model!(self, r => r.eigenvalue_scale(), r => MassMetric::eigenvalue_scale(r))
    }

    /// See [`EquilibriumProblem::impose_load`].
    pub fn impose_load(&self, state: &mut MemberState, from: f64, to: f64, guess: bool) {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.impose_load(s, from, to, guess),
            (Self::Cosserat(r), MemberState::Framed(s)) => {
                EquilibriumProblem::impose_load(r, s, from, to, guess)
            }
            (Self::Se3(r), MemberState::Framed(s)) => {
                EquilibriumProblem::impose_load(r, s, from, to, guess)
            }
            _ => unreachable!("member and state of different models"),
        }
    }

    /// Calls `f` with every term's stencil (own free DOFs).
    pub fn for_each_stencil(&self, f: impl FnMut(&[usize])) {
        by_model!(self, r => r.for_each_stencil(f), r => framed_stencils(r, f))
    }

    /// The own free DOF of coordinate `k` of vertex `v`, or FIXED.
    pub fn vertex_dof(&self, v: usize, k: usize) -> usize {
        by_model!(self, r => r.dofs().vertex(v, k), r => r.dofs().vertex(v, k))
    }

    /// Makes the load factor move the support holding `vertices` (the member's own) rigidly
    /// from 0 to 1: rotation vector (rad) about `pivot`, translation (m).
    pub fn set_support_motion(
        &mut self,
        vertices: &[usize],
        pivot: crate::geometry::Vec3,
        rotation: crate::geometry::Vec3,
        translation: crate::geometry::Vec3,
    ) -> Result<(), crate::ModelError> {
        match self {
            Self::Der(r) => r.set_support_motion(vertices, pivot, rotation, translation),
            Self::Cosserat(r) => r
                .core
                .set_support_motion(vertices, pivot, rotation, translation),
            Self::Se3(r) => r
                .core
                .set_support_motion(vertices, pivot, rotation, translation),
        }
    }

    /// Makes the load factor change gravity from `old` to the member's gravity `g` (m/s²),
    /// which is set now.
    pub fn set_gravity_change(
        &mut self,
        old: crate::geometry::Vec3,
        g: crate::geometry::Vec3,
    ) -> Result<(), crate::ModelError> {
        let path = crate::rod::RodLoadPath::gravity_change(old);
        match self {
            Self::Der(r) => {
                r.set_gravity(g);
                r.set_load_path(path)
            }
            Self::Cosserat(r) => {
                r.core.set_gravity(g);
                r.core.set_load_path(path)
            }
            Self::Se3(r) => {
                r.core.set_gravity(g);
                r.core.set_load_path(path)
            }
        }
    }

    /// Changes the dead point force on vertex `v` from `old` to `new` (N): at load factor 1
    /// from now on, and along the load path of the next solve (λ = 0: `old`). Returns the
    /// vertex's nodal force before the change, for [`Self::undo_force_change`]. Errors
    /// (nothing changed) if `v` is not a vertex or a force is not finite.
    pub fn set_force_change(
        &mut self,
        v: usize,
        old: crate::geometry::Vec3,
        new: crate::geometry::Vec3,
    ) -> Result<crate::geometry::Vec3, crate::ModelError> {
        match self {
            Self::Der(r) => r.set_force_change(v, old, new),
            Self::Cosserat(r) => r.core.set_force_change(v, old, new),
            Self::Se3(r) => r.core.set_force_change(v, old, new),
        }
    }

    /// Changes the follower force on vertex `v` from `old` to `new` (N, given at rest): from
    /// now on, and along the load path of the next solve (λ = 0: `old`, turned with the rod).
    /// `state` is this member's state, whose frozen follower loads are refreshed. Returns the
    /// follower's index, for [`Self::undo_follower_force_change`]. Errors (nothing changed):
    /// not a discrete elastic rod (the only model with follower loads), no follower force
    /// `old` on `v`, a force not finite.
    pub fn set_follower_force_change(
        &mut self,
        state: &mut MemberState,
        v: usize,
        old: crate::geometry::Vec3,
        new: crate::geometry::Vec3,
    ) -> Result<usize, crate::ModelError> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.set_follower_force_change(s, v, old, new),
            _ => Err(crate::ModelError::structure(
                "follower_change",
                "follower loads act on discrete elastic rods only",
            )),
        }
    }

    /// As [`Self::set_follower_force_change`], for a follower moment on vertex `v`: from `old`
    /// to `new` (N m, given at rest). Returns the follower's index, for
    /// [`Self::undo_follower_moment_change`].
    pub fn set_follower_moment_change(
        &mut self,
        state: &mut MemberState,
        v: usize,
        old: crate::geometry::Vec3,
        new: crate::geometry::Vec3,
    ) -> Result<usize, crate::ModelError> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.set_follower_moment_change(s, v, old, new),
            _ => Err(crate::ModelError::structure(
                "follower_moment_change",
                "follower loads act on discrete elastic rods only",
            )),
        }
    }

    /// Undoes [`Self::set_follower_moment_change`]: follower `i`'s moment back to `old` (N m),
    /// the load path cleared (the state is the caller's to restore).
    pub fn undo_follower_moment_change(&mut self, i: usize, old: crate::geometry::Vec3) {
        if let Self::Der(r) = self {
            r.undo_follower_moment_change(i, old);
        }
    }

    /// Undoes [`Self::set_follower_force_change`]: follower `i`'s force back to `old` (N),
    /// the load path cleared (the state is the caller's to restore).
    pub fn undo_follower_force_change(&mut self, i: usize, old: crate::geometry::Vec3) {
        if let Self::Der(r) = self {
            r.undo_follower_force_change(i, old);
        }
    }

    /// Changes the dead point moment on vertex `v` from `old` to `new` (N m): along the load
    /// path of the next solve (λ = 0: `old`, λ = 1: `new`; see `rod/moment_change.rs`).
    /// `state` is this member's state, which gets the new moment's angle. After a converged
    /// solve call [`Self::finish_moment_change`]; after one that failed,
    /// [`Self::undo_moment_change`] with the returned index (and restore the state). Errors
    /// (nothing changed): no dead moment `old` on `v`, a value not finite.
    pub fn set_moment_change(
        &mut self,
        state: &mut MemberState,
        v: usize,
        old: crate::geometry::Vec3,
        new: crate::geometry::Vec3,
    ) -> Result<usize, crate::ModelError> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.set_moment_change(s, v, old, new),
            (Self::Cosserat(r), MemberState::Framed(s)) => r.core.set_moment_change(s, v, old, new),
            (Self::Se3(r), MemberState::Framed(s)) => r.core.set_moment_change(s, v, old, new),
            _ => Err(crate::ModelError::structure(
                "moment_change",
                "the state does not belong to this member",
            )),
        }
    }

    /// Ends a converged [`Self::set_moment_change`]: the old moment and its angle in `state`
    /// dropped, the load path cleared.
    pub fn finish_moment_change(&mut self, state: &mut MemberState) {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.finish_moment_change(s),
            (Self::Cosserat(r), MemberState::Framed(s)) => r.core.finish_moment_change(s),
            (Self::Se3(r), MemberState::Framed(s)) => r.core.finish_moment_change(s),
            (m, _) => m.clear_load_path(),
        }
    }

    /// Undoes [`Self::set_moment_change`] of moment `i`: its old value back, the load path
    /// cleared (the state is the caller's to restore).
    pub fn undo_moment_change(&mut self, i: usize) {
        match self {
            Self::Der(r) => r.undo_moment_change(i),
            Self::Cosserat(r) => r.core.undo_moment_change(i),
            Self::Se3(r) => r.core.undo_moment_change(i),
        }
    }

    /// Undoes [`Self::set_force_change`] bit for bit: vertex `v`'s nodal force back to
    /// `before` (N), the load path cleared.
    pub fn undo_force_change(&mut self, v: usize, before: crate::geometry::Vec3) {
        match self {
            Self::Der(r) => r.undo_force_change(v, before),
            Self::Cosserat(r) => r.core.undo_force_change(v, before),
            Self::Se3(r) => r.core.undo_force_change(v, before),
        }
    }

    /// Keeps the dead loads (before a gravity change) for [`Self::restore_loads`].
    pub fn save_loads(&mut self) {
        match self {
            Self::Der(r) => r.save_loads(),
            Self::Cosserat(r) => r.core.save_loads(),
            Self::Se3(r) => r.core.save_loads(),
        }
    }

    /// Puts back the dead loads [`Self::save_loads`] kept, bit for bit (the load path
    /// cleared): the undo of a gravity change that did not converge.
    pub fn restore_loads(&mut self) {
        match self {
            Self::Der(r) => r.restore_loads(),
            Self::Cosserat(r) => r.core.restore_loads(),
            Self::Se3(r) => r.core.restore_loads(),
        }
    }

    /// Sets gravity (m/s²) at load factor 1.
    pub fn set_gravity(&mut self, g: crate::geometry::Vec3) {
        match self {
            Self::Der(r) => r.set_gravity(g),
            Self::Cosserat(r) => r.core.set_gravity(g),
            Self::Se3(r) => r.core.set_gravity(g),
        }
    }

    /// Back to the plain load ramp.
    pub fn clear_load_path(&mut self) {
        match self {
            Self::Der(r) => r.clear_load_path(),
            Self::Cosserat(r) => r.core.clear_load_path(),
            Self::Se3(r) => r.core.clear_load_path(),
        }
    }
}
