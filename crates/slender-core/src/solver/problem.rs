//! What the Newton solver needs from a model.
//!
//! A model is a DOF map, a list of term groups and a retraction: it implements
//! [`EquilibriumProblem`] by running its term groups through an
//! [`Assembler`](crate::assembly::Assembler) ([`EquilibriumProblem::assemble_selected`]), and
//! says how a state moves along a step ([`EquilibriumProblem::displace`]), how two states differ
//! ([`EquilibriumProblem::difference`], a log map on rotation DOFs) and what the load factor
//! drives ([`EquilibriumProblem::impose_load`]). Energy and assembly of all terms come for free.

use crate::assembly::{Assembler, TermGroup, TermSet};
use crate::linalg::SymmetricMatrix;

// The assembler's summary lives with the assembler (no assembly ↔ solver import cycle).
pub use crate::assembly::AssemblyInfo;

/// The inertia a model attaches to its DOFs: the metric of its eigenvalue problems.
///
/// The smallest Hessian eigenvalue is reported in this metric (H v = λ M v), so that it is a
/// squared natural frequency (1/s²) and does not depend on the mesh; the Newton solver's
/// regularization shifts by multiples of M for the same reason.
pub trait MassMetric {
    /// Inertia attached to free DOF `i` (kg, or kg m² for angles).
    fn inertia_metric(&self, i: usize) -> f64;

    /// Reference value of eigenvalues (1/s²) used to normalize λ_min (e.g. EI/(ρA L⁴)).
    fn eigenvalue_scale(&self) -> f64;
}

/// A discretized structure whose equilibria the solver finds: an energy over a state with
/// exact gradient and Hessian in the free DOFs. The Hessian storage (banded for rods, sparse
/// for shells) is the problem's choice; the solver only assembles, factors and solves.
///
/// States may carry more than the DOF vector (a rod carries reference frames, a Cosserat rod
/// rotations). Every state a problem hands out is consistent: [`displace`](Self::displace)
/// produces a new state with its caches adapted, and the derivatives are exact at that state.
pub trait EquilibriumProblem: MassMetric {
    /// Configuration type (positions, angles, rotations and whatever caches derive from them).
    type State: Clone;

    /// Hessian storage and factorization.
    type Hessian: SymmetricMatrix;

    /// Number of free DOFs.
    fn n_free(&self) -> usize;

    /// A zero Hessian with the problem's pattern (n_free × n_free).
    fn new_hessian(&self) -> Self::Hessian;

    /// The model's term groups (each a bit of a [`TermSet`]), in assembly order.
    fn term_groups(&self) -> &[TermGroup];

    /// Runs the term groups selected in `asm` at load factor `load` through the assembler, for
    /// any Hessian storage whose pattern holds the model's.
    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &Self::State,
        load: f64,
        asm: &mut Assembler<'_, M>,
    );

    /// Energy (J) at load factor `load` (internal energy minus the work of the loads).
    fn energy(&self, state: &Self::State, load: f64) -> f64 {
        let mut asm = Assembler::<Self::Hessian>::energy_only(TermSet::ALL);
        self.assemble_selected(state, load, &mut asm);
        asm.finish().energy
    }

    /// The function the line search decreases along a Newton step, at a trial state
    /// `trial` = [`displace`](Self::displace)`(base, dx, α)`; at α = 0 it must equal the
    /// energy at `base`, and its slope there gᵀdx. Default: the energy.
    ///
    /// A model whose Newton step treats its stresses as independent of the positions (the
    /// mixed-integration-point method, see `shell::mixed_update`) measures trial points by
    /// the energy at the linearly updated stresses: the energy minus that of the step's
    /// second-order strain, which a linearized step cannot see and which would otherwise make
    /// the line search cut every large rotation down to about a thickness.
    fn merit(&self, trial: &Self::State, load: f64) -> f64 {
        self.energy(trial, load)
    }

    /// True if [`merit`](Self::merit) is the energy [`assemble`](Self::assemble) reports, so
    /// that an assembly at a trial point can stand in for its merit (see
    /// [`SolverParams::deferred_energy_check`](super::SolverParams::deferred_energy_check)).
    /// Default false: a model says so explicitly.
    fn merit_is_energy(&self) -> bool {
        false
    }

    /// Gradient into `grad` (length [`n_free`](Self::n_free)), Hessian into `hess` (zeroed
    /// here), and Σ over terms of |term gradient| per DOF into `abs_grad` (the round-off scale).
    fn assemble(
        &self,
        state: &Self::State,
        load: f64,
        grad: &mut [f64],
        hess: &mut Self::Hessian,
        abs_grad: &mut [f64],
    ) -> AssemblyInfo {
        let mut asm = Assembler::new(TermSet::ALL, Some(grad), Some(hess), Some(abs_grad));
        self.assemble_selected(state, load, &mut asm);
        asm.finish()
    }

    /// `out` = `a` ⊖ `b`: the step in the free DOFs that carries `b` to `a` (the log map on
    /// rotation DOFs, plain differences on coordinates), so that
    /// `displace(b, difference(a, b), 1)` ≈ `a`. Predictors extrapolate with it; subtracting
    /// raw DOF values would be wrong for rotations.
    fn difference(&self, a: &Self::State, b: &Self::State, out: &mut [f64]);

    /// `out` = `state` moved by `alpha·dx` (free DOFs) by the model's retraction, with caches
    /// adapted. Prescribed DOFs (supports) are left where `state` has them.
    fn displace(&self, state: &Self::State, dx: &[f64], alpha: f64, out: &mut Self::State);

    /// The chart whose derivatives [`assemble`](Self::assemble) returns: the energy's gradient
    /// and Hessian are those of dx ↦ E(chart(state, dx)) at dx = 0. Defaults to
    /// [`displace`](Self::displace); a model whose retraction differs from its chart at second
    /// order overrides it (finite-difference checks use the chart).
    fn chart(&self, state: &Self::State, dx: &[f64], out: &mut Self::State) {
        self.displace(state, dx, 1.0, out);
    }

    /// Moves the prescribed DOFs of `state` (supports driven by the load path) from their
    /// values at load factor `from` to those at `to`. With `guess`, free DOFs may be moved too,
    /// as a first guess of the equilibrium at `to` (used when no secant predictor exists).
    /// Default: the load factor drives no prescribed DOF.
    fn impose_load(&self, state: &mut Self::State, from: f64, to: f64, guess: bool) {
        let _ = (state, from, to, guess);
    }

    /// Turns `v`, a vector over the free DOFs (a step or a gradient), by the rotation that
    /// [`impose_load`](Self::impose_load)'s first guess gives the whole structure from load
    /// factor `from` to `to` (by its inverse if `inverse`), and returns true; returns false,
    /// leaving `v` alone, if that first guess is not one rigid turn of every free DOF, or if
    /// the energy's Hessian does not turn with the structure. Where it does (internal energy
    /// invariant under rigid rotations, loads linear in the positions), the Hessian at the
    /// turned state is P H Pᵀ, P this turn: the factorization of H from before the turn then
    /// solves for the turned state's Newton step (the continuation's chord predictor).
    /// Default: false.
    fn turn_free(&self, from: f64, to: f64, v: &mut [f64], inverse: bool) -> bool {
        let _ = (from, to, v, inverse);
        false
    }

    /// Refreshes loads that depend on the state but are frozen during a Newton solve (follower
    /// loads, applied lagged) and returns their largest relative change; the solver re-solves
    /// until it is below round-off. Default: no such loads (0).
    fn refresh_loads(&self, state: &mut Self::State) -> f64 {
        let _ = state;
        0.0
    }

    /// True if the model has lagged loads (follower loads): loads with no potential, frozen
    /// during each Newton solve. Its Hessian is then that of the frozen loads, whose inertia
    /// says nothing of the stability under the loads that turn (a dynamic question): the
    /// solver reports it but follows none of its modes. Default false.
    fn has_lagged_loads(&self) -> bool {
        false
    }

    /// The lagged loads of `state` (those [`refresh_loads`](Self::refresh_loads) refreshes) as
    /// numbers into `out` (cleared first), in the units of the loads (N, N m). The solver
    /// accelerates their fixed-point iteration with them. Default: none (`out` left empty).
    fn lagged_loads(&self, state: &Self::State, out: &mut Vec<f64>) {
        let _ = state;
        out.clear();
    }

    /// Sets the lagged loads of `state` to `values`, listed as
    /// [`lagged_loads`](Self::lagged_loads) lists them. Default: nothing to set.
    fn set_lagged_loads(&self, state: &mut Self::State, values: &[f64]) {
        let _ = (state, values);
    }

    /// The largest fraction α ∈ [0, 1] of a kick `dx` (a branch switch's push along a mode,
    /// taken whole rather than by Newton's capped steps) that keeps `state` admissible for
    /// constraints the model's own [`max_step`](Self::max_step) does not hold: a contact's
    /// obstacles, which a kick must not push a vertex into or through. 1 by default.
    fn kick_limit(&self, _state: &Self::State, _dx: &[f64]) -> f64 {
        1.0
    }

    /// Largest α ∈ (0, 1] such that `alpha·dx` respects the model's step caps (e.g. no edge
    /// turns by more than π/4 in one step).
    fn max_step(&self, state: &Self::State, dx: &[f64]) -> f64;

    /// True if the continuation's secant predictor must respect [`max_step`](Self::max_step)
    /// too (a contact model: an extrapolated state must not jump through an obstacle).
    /// Default false: the predictor is the plain secant.
    fn caps_predictor(&self) -> bool {
        false
    }

    /// False if the continuation should start every load step from the model's first guess
    /// ([`impose_load`](Self::impose_load) with `guess`) instead of the secant predictor: a
    /// load path that turns the structure, whose linear extrapolation stretches it at second
    /// order (a strip turning with its clamp). Default true.
    fn secant_predictor(&self) -> bool {
        true
    }

    /// The term groups whose Hessian changes slowly along a warm re-solve (a rod's bending and
    /// twisting: the stencil turns with the rod, while the stretching's geometric stiffness
    /// follows the tension, which a support's move changes at once). The first Newton step
    /// after a chord predictor may reuse their Hessian from the previous solve's last
    /// assembly with the other groups' Hessian fresh (see [`SolverParams::lagged_first_step`]).
    /// Default: none (every assembly is complete).
    ///
    /// [`SolverParams::lagged_first_step`]: crate::solver::SolverParams::lagged_first_step
    fn lagged_hessian_groups(&self) -> TermSet {
        TermSet::NONE
    }

    /// Length (m) that turns the generalized force of DOF `i` into a force: 1 for coordinates,
    /// a characteristic length for angles (whose generalized forces are moments).
    fn force_length(&self, i: usize) -> f64;

    /// Typical magnitude of DOF `i` (m or rad), for the round-off floor of the gradient.
    fn dof_magnitude(&self, state: &Self::State, i: usize) -> f64;

    /// [`force_length`](Self::force_length) (m) and [`dof_magnitude`](Self::dof_magnitude)
    /// (m or rad) of every free DOF at once, into `force_length` and `magnitude` (length n):
    /// the solver's round-off floor reads both for every DOF at every iterate, and a model can
    /// produce them in one pass (a structure: one dispatch per member instead of two per DOF).
    /// The default asks DOF by DOF; an override must give the same values.
    fn dof_scales(&self, state: &Self::State, force_length: &mut [f64], magnitude: &mut [f64]) {
        for (i, (l, m)) in force_length
            .iter_mut()
            .zip(magnitude.iter_mut())
            .enumerate()
        {
            *l = self.force_length(i);
            *m = self.dof_magnitude(state, i);
        }
    }
}
