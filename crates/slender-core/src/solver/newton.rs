//! The Newton loop at a fixed load: exact Hessian, inertia from the LDLᵀ pivots, diagonal
//! shift when the Hessian is indefinite, step caps and Armijo backtracking (design.md §4.2).

use crate::assembly::{Assembler, TermSet};
use crate::linalg::{Inertia, SymmetricBandMatrix, SymmetricFactor, SymmetricMatrix};

use super::line_search::{armijo_backtracking, LineSearch};
use super::params::SolverParams;
use super::problem::EquilibriumProblem;
use super::stability::{slice_lowest_mode, EigenWorkspace, LowestMode};

/// Buffers reused across Newton iterations and solves: nothing is allocated per iteration.
#[derive(Clone, Debug)]
pub struct NewtonWorkspace<S, M: SymmetricMatrix = SymmetricBandMatrix> {
    pub(crate) grad: Vec<f64>,
    pub(crate) abs_grad: Vec<f64>,
    pub(crate) dx: Vec<f64>,
    pub(crate) diag: Vec<f64>,
    pub(crate) hess: M,
    pub(crate) ldlt: M::Factor,
    pub(crate) trial: S,
    pub(crate) scaled: M,
    /// Gradient at a polishing trial (the workspace keeps the accepted state's).
    pub(crate) trial_grad: Vec<f64>,
    /// Chord step at a trial (see [`SolverParams::chord_final_check`]).
    pub(crate) trial_dx: Vec<f64>,
    pub(crate) eigen: EigenWorkspace,
    pub(crate) shift_mode: LowestMode,
    /// A step taken before its energy was known, to be judged by the next measure (see
    /// [`SolverParams::deferred_energy_check`]); the state before it is in `trial`.
    pub(crate) deferred: Option<DeferredCheck>,
    /// The per-DOF scales of the last round-off floor.
    pub(crate) scales: FloorScales,
    /// The Hessian of the problem's lagged term groups at the last complete assembly (see
    /// [`SolverParams::lagged_first_step`]); allocated by the first such assembly.
    pub(crate) lagged: Option<M>,
    /// True if `lagged` is that of the last complete assembly of this workspace.
    pub(crate) lagged_fresh: bool,
    /// Set after a chord predictor: the next measure may reuse `lagged`.
    pub(crate) lag_next: bool,
}

/// The per-DOF scales a residual's round-off floor is made of, refilled at every measured
/// point (buffers reused).
#[derive(Clone, Debug, Default)]
pub(crate) struct FloorScales {
    /// [`EquilibriumProblem::force_length`] of each DOF (m).
    force_length: Vec<f64>,
    /// [`EquilibriumProblem::dof_magnitude`] of each DOF (m or rad).
    magnitude: Vec<f64>,
    /// The Hessian's diagonal.
    diagonal: Vec<f64>,
}

/// The sufficient-decrease test still owed by a step taken without evaluating the energy at
/// its end point (see [`SolverParams::deferred_energy_check`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum DeferredCheck {
    /// A chord predictor: kept if the energy fell below `energy` (J), the energy before it.
    Predictor { energy: f64 },
    /// A full Newton step (saved in `trial_dx`): kept under the Armijo test of
    /// [`armijo_backtracking`] at α = 1, else backtracked from α = ½.
    NewtonStep { energy: f64, slope: f64, noise: f64 },
}

impl DeferredCheck {
    /// True if the step ending at energy `e` (J) passes.
    fn passes(&self, e: f64, params: &SolverParams) -> bool {
        match *self {
            Self::Predictor { energy } => e < energy,
            Self::NewtonStep {
                energy,
                slope,
                noise,
            } => {
                e.is_finite()
                    && (e <= energy + params.armijo * slope
                        || (-slope <= noise && e <= energy + noise))
            }
        }
    }
}

impl<S: Clone, M: SymmetricMatrix> NewtonWorkspace<S, M> {
    /// Buffers for `problem`; `template` is any state of it (used as line-search scratch).
    pub fn new<P: EquilibriumProblem<State = S, Hessian = M>>(problem: &P, template: &S) -> Self {
        let n = problem.n_free();
        let hess = problem.new_hessian();
        Self {
            grad: vec![0.0; n],
            abs_grad: vec![0.0; n],
            dx: vec![0.0; n],
            diag: vec![0.0; n],
            scaled: hess.clone(),
            hess,
            ldlt: M::Factor::default(),
            trial: template.clone(),
            trial_grad: vec![0.0; n],
            trial_dx: vec![0.0; n],
            eigen: EigenWorkspace::default(),
            shift_mode: LowestMode {
                value: 0.0,
                normalized: 0.0,
                shape: Vec::with_capacity(n),
            },
            deferred: None,
            scales: FloorScales::default(),
            lagged: None,
            lagged_fresh: false,
            lag_next: false,
        }
    }

    /// The Hessian assembled at the last iterate.
    pub fn hessian(&self) -> &M {
        &self.hess
    }

    /// The factorization workspace (holds the last factorization).
    pub fn factor(&self) -> &M::Factor {
        &self.ldlt
    }
}

/// Measures of the last iterate of a Newton solve.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IterateMeasures {
    /// Largest residual force (N).
    pub residual: f64,
    /// Round-off floor of the residual (N).
    pub floor: f64,
    /// Largest external nodal force (N).
    pub external_force: f64,
    /// The force scale of the residual tests (N): the largest external nodal force, or, for a
    /// structure loaded only by its supports' motion, half the largest Σ|term force| on a DOF
    /// (the internal forces the supports impose).
    pub force_scale: f64,
    /// Newton decrement |gᵀH⁻¹g| (J); infinite if the Hessian could not be factored.
    pub decrement: f64,
    /// Energy (J).
    pub energy: f64,
    /// Inertia of the unshifted Hessian, if its LDLᵀ factorization exists.
    pub inertia: Option<Inertia>,
    /// True if the Hessian, its factorization and inertia are those of the previous iterate,
    /// one below-tolerance Newton step away (a chord final check, see
    /// [`SolverParams::chord_final_check`]); false if they are this iterate's.
    pub hessian_lags: bool,
}

/// Result of [`newton`].
#[derive(Clone, Debug, PartialEq)]
pub struct NewtonOutcome {
    /// True if the convergence tests passed.
    pub converged: bool,
    /// Iterations taken (0 if the start was already an equilibrium).
    pub iterations: usize,
    /// Why it stopped, if it did not converge.
    pub failure: Option<String>,
    /// Measures at the final iterate.
    pub last: IterateMeasures,
}

/// A residual under the round-off floor and below this fraction of the force scale is
/// accepted at once; above it, only once Newton stops improving it.
const FLOOR_ACCEPT: f64 = 1e-6;

/// A residual under the round-off floor that stalls is accepted only up to this multiple of
/// the largest external force (see [`floor_above_loads`]). Loads below the rounding of the
/// term forces (the first steps of a ramp, 1e-8 N against a cable's stiffness) leave a
/// residual of up to about their own size, which is round-off; ten times the loads is not.
const FLOOR_CEILING: f64 = 10.0;

/// Measured iterates without halving the best residual of the solve after which Newton is
/// said to stall (see [`STALL_ACCEPT`]).
const STALL_WINDOW: usize = 5;

/// A Newton solve that stalls at a minimum (positive definite Hessian) with its residual at
/// most this fraction of the force scale has converged as far as double precision lets it.
/// A near-null mode makes it so: a 1 mm copper wire 2 m long, buckled between clamps whose
/// tangents nearly share an axis, can turn its buckle about that axis at a stiffness of
/// about 3e-5 N/m; residual round-off pushes it along that mode by ~1e-5 m per step, whose
/// second-order stretch, EA·(a/L)², is a residual of 1e-7 to 8e-7 N (4e-6 of the forces)
/// that no iteration removes (measured: 300 iterations, then a failed move).
const STALL_ACCEPT: f64 = 1e-5;

/// After a chord final check that lowered the residual by at least this factor without
/// converging, a second chord step is taken before a new Hessian is assembled.
const CHORD_AGAIN: f64 = 1e-2;

/// Largest relative step (per DOF magnitude) still considered a change of the state.
const TINY_STEP: f64 = 1e-13;
/// Relative step (per DOF magnitude) at which a polishing step is rounding noise: 16 ε.
const ROUNDOFF_STEP: f64 = 16.0 * f64::EPSILON;
/// Smallest shift, relative to the largest ratio of Hessian diagonal to mass.
const MIN_SHIFT: f64 = 1e-8;
/// Largest shift before giving up, in the same relative units.
const MAX_SHIFT: f64 = 1e12;
/// Doublings of the indefinite shift tried per iterate before giving up (2¹⁰⁰ ≈ 1e30).
const MAX_SHIFT_DOUBLINGS: usize = 100;
/// A gradient whose cosine with the lowest mode (mass metric, see [`mass_metric_cosine`]) is
/// above this is no symmetric saddle: the precise test asks for 1e-9, and
/// the mode of the shift, converged to 1e-3 in λ, is off a symmetric mode by far less than
/// this unless the lowest two modes nearly coincide.
const SADDLE_SCREEN: f64 = 1e-2;

/// Newton's method at load factor `load`, starting from and updating `state`.
///
/// Convergence (design.md §4.3): the residual force is at most
/// max(force_tolerance·‖f_ext‖, round-off floor) *and* either the Newton decrement is at most
/// energy_tolerance·|work of the loads| or the Newton step is below round-off. Both tests are
/// relative, so small loads (Γ → 0) converge to the right answer instead of stopping early.
pub fn newton<P: EquilibriumProblem>(
    problem: &P,
    state: &mut P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
) -> NewtonOutcome {
    let n = problem.n_free();
    let eps = f64::EPSILON;
    let mut shift = 0.0_f64;
    let mut last = IterateMeasures::default();
    let mut previous_residual: Option<f64> = None;
    // The best residual of this solve and the measured iterates since it was last halved.
    let mut best_residual = f64::INFINITY;
    let mut since_best = 0;
    // Newton decrement of the previous measured iterate (quadratic-convergence forecast).
    let mut previous_decrement: Option<f64> = None;
    // Consecutive iterations with a shifted (indefinite) step.
    let mut shifted_run = 0;
    // Whether `ws.shift_mode` holds the lowest mode of an earlier iterate of this solve.
    let mut mode_known = false;
    // Full Newton steps may leave their energy test to the next measure (see
    // `SolverParams::deferred_energy_check`) until one of them fails it.
    let mut defer = params.deferred_energy_check && problem.merit_is_energy();
    for iteration in 0..=params.max_iterations {
        let lag = std::mem::take(&mut ws.lag_next);
        let (measures, mut info, mut lagged) = measure_with(problem, state, load, params, ws, lag);
        last = measures;
        if let Some(check) = ws.deferred.take() {
            if !check.passes(info.energy, params) {
                // Undo the step (the state before it is in `trial`) and take the line search
                // it skipped; the next iteration measures where that lands.
                std::mem::swap(state, &mut ws.trial);
                defer = false;
                if let DeferredCheck::NewtonStep {
                    energy,
                    slope,
                    noise,
                } = check
                {
                    ws.dx.copy_from_slice(&ws.trial_dx);
                    match armijo_backtracking(
                        problem,
                        state,
                        &ws.dx,
                        energy,
                        slope,
                        noise,
                        0.5,
                        load,
                        params,
                        &mut ws.trial,
                    ) {
                        LineSearch::Accepted(_) => std::mem::swap(state, &mut ws.trial),
                        LineSearch::Failed => {
                            return failed(iteration, "line search found no decrease", last)
                        }
                    }
                }
                continue;
            }
        }
        if lagged
            && (!last.inertia.is_some_and(|i| i.is_positive_definite())
                || last.residual <= last.floor.max(params.force_tolerance * last.force_scale))
        {
            // The lagged Hessian only takes a clear Newton step: an indefinite one, or an
            // iterate that may have converged (whose inertia is the stability verdict), is
            // measured in full.
            let (m, i) = measure(problem, state, load, params, ws);
            (last, info, lagged) = (m, i, false);
        }
        let inertia = last.inertia;
        if last.residual < 0.5 * best_residual {
            best_residual = last.residual;
            since_best = 0;
        } else {
            since_best += 1;
        }
        let stalled = since_best >= STALL_WINDOW;
        if converged(
            &last,
            &info,
            params,
            problem,
            state,
            ws,
            previous_residual,
            stalled,
        ) {
            polish(problem, state, load, params, ws, &mut last);
            return NewtonOutcome {
                converged: true,
                iterations: iteration,
                failure: None,
                last,
            };
        }
        let residual = last.residual;
        if residual <= last.floor
            && floor_above_loads(&last)
            && previous_residual.is_some_and(|p| residual > 0.5 * p)
        {
            // Stalled at a floor above the loads: more iterations only repeat the rounding.
            return failed(
                iteration,
                &format!(
                    "residual {residual:.3e} N stalls at its round-off floor {:.3e} N, above \
                     the loads ({:.3e} N): the term forces are too large for an equilibrium \
                     at this precision",
                    last.floor, last.external_force
                ),
                last,
            );
        }
        previous_residual = Some(residual);
        if iteration == params.max_iterations {
            break;
        }
        let forecast = previous_decrement.take();
        previous_decrement = Some(last.decrement);
        if params.chord_final_check
            && !lagged
            && inertia.is_some_and(|i| i.is_positive_definite())
            && next_decrement_passes(&last, forecast, &info, params)
        {
            let mut check = chord_final_check(problem, state, load, params, ws, &mut last);
            if matches!(check, ChordCheck::Improved) && last.residual <= CHORD_AGAIN * residual {
                // The step converged like Newton but the residual is still above the target:
                // the same factorization gives one more step of the same quality, at the cost
                // of a gradient instead of a Hessian and its factorization.
                check = match chord_final_check(problem, state, load, params, ws, &mut last) {
                    ChordCheck::Rejected => ChordCheck::Improved,
                    other => other,
                };
            }
            match check {
                ChordCheck::Converged => {
                    polish(problem, state, load, params, ws, &mut last);
                    return NewtonOutcome {
                        converged: true,
                        iterations: iteration + 1,
                        failure: None,
                        last,
                    };
                }
                // The full step lowered the residual: measure there next.
                ChordCheck::Improved => continue,
                ChordCheck::Rejected => {}
            }
        }
        if !residual.is_finite() {
            return failed(iteration, "non-finite residual", last);
        }

        let positive_definite = inertia.is_some_and(|i| i.is_positive_definite());
        // At a saddle the unshifted step is kept only if it descends: with several unstable
        // modes the gradient may be orthogonal to the lowest one and not to the others.
        let descends = inertia.is_some() && dot(&ws.grad, &ws.dx) < 0.0;
        // Indefinite or singular: the lowest mode in the mass metric sizes the shift below.
        // It is computed first because it also screens the symmetric-saddle test: a gradient
        // with a clear component along it is no symmetric saddle, and the precise test (a
        // cold eigensolve of its own) is then skipped.
        let mut lambda = 0.0;
        let mut screened = false;
        if !positive_definite {
            for i in 0..n {
                ws.diag[i] = problem.inertia_metric(i);
            }
            // From the second indefinite iterate of a solve on, the last iterate's mode starts
            // the eigensolve: the Hessian changed by one step, and the slicing closes in a few
            // factorizations instead of bisecting from the Gershgorin bound.
            let warm = std::mem::take(&mut mode_known);
            lambda = match slice_lowest_mode(
                problem,
                &ws.hess,
                &mut ws.scaled,
                &mut ws.ldlt,
                1e-3,
                &mut ws.eigen,
                &mut ws.shift_mode,
                warm,
            ) {
                Ok(()) => {
                    mode_known = true;
                    screened = ws.shift_mode.value < 0.0
                        && mass_metric_cosine(&ws.grad, &ws.shift_mode.shape, &ws.diag)
                            > SADDLE_SCREEN;
                    ws.shift_mode.value
                }
                Err(_) => 0.0,
            };
        }
        if positive_definite || (descends && !screened && saddle_is_symmetric(problem, ws)) {
            // Positive definite: the Newton step. At a symmetric saddle (the gradient has no
            // component along the unstable mode, e.g. a planar state under planar loads) the
            // unshifted step still converges quadratically to that equilibrium, whose
            // instability is then reported by the inertia (design.md §4.2, §4.5); shifting
            // would only slow convergence to it. `dx` holds the unshifted step already.
            shift *= 0.5;
            shifted_run = 0;
        } else {
            shifted_run += 1;
            if params.indefinite_patience.is_some_and(|k| shifted_run > k) {
                return failed(
                    iteration,
                    &format!("indefinite Hessian for {} iterations", shifted_run - 1),
                    last,
                );
            }
            // Indefinite or singular: shift by a multiple of the mass matrix M, H + μM. In that
            // metric every mode is measured in the same units (squared frequencies), so the
            // shift does not smother the soft bending directions the way a shift scaled by
            // diag(H) (dominated by the stretching stiffness) would: it acts like a
            // pseudo-time step. μ = 2|λ_min(H, M)| leaves a margin of |λ_min| on every mode.
            // The last shift decays by half per iteration here too (λ_min is measured anew at
            // each indefinite iterate): kept whole, the shift of a far-off first iterate (a
            // poor first guess, |λ_min| at the stretching scale) made every later step a tiny
            // pseudo-time step, and the load step failed after max_iterations.
            shift = (0.5 * shift)
                .max(2.0 * lambda.min(0.0).abs())
                .max(MIN_SHIFT * ws.hess.max_abs_diagonal() / max_entry(&ws.diag));
            // No shift regularizes a Hessian with a NaN or infinite entry: say so at once
            // rather than doubling the shift up to the cap (about a thousand failed
            // factorizations per iterate: minutes for a large structure).
            if let Some(row) = ws.hess.first_non_finite() {
                return failed(
                    iteration,
                    &format!("non-finite Hessian entry in row {row}"),
                    last,
                );
            }
            let cap = MAX_SHIFT * ws.hess.max_abs_diagonal() / min_entry(&ws.diag);
            let mut doublings = 0;
            loop {
                if factor_shifted(ws, n, shift) {
                    break;
                }
                shift *= 2.0;
                doublings += 1;
                // The cap itself can sit a thousand doublings up (a tiny mass entry); no finite
                // matrix needs more than MAX_SHIFT_DOUBLINGS (×1e30) over the starting shift.
                if !shift.is_finite() || shift > cap || doublings > MAX_SHIFT_DOUBLINGS {
                    return failed(
                        iteration,
                        "could not regularize an indefinite Hessian",
                        last,
                    );
                }
            }
            for i in 0..n {
                ws.dx[i] = -ws.grad[i];
            }
            ws.ldlt.solve_in_place(&mut ws.dx);
        }

        let slope = dot(&ws.grad, &ws.dx);
        let alpha_max = problem.max_step(state, &ws.dx);
        let noise = 1e3 * eps * info.energy_magnitude.max(info.energy.abs());
        if defer && positive_definite && alpha_max >= 1.0 && slope < 0.0 {
            ws.trial_dx.copy_from_slice(&ws.dx);
            problem.displace(state, &ws.dx, 1.0, &mut ws.trial);
            std::mem::swap(state, &mut ws.trial);
            ws.deferred = Some(DeferredCheck::NewtonStep {
                energy: info.energy,
                slope,
                noise,
            });
            continue;
        }
        match armijo_backtracking(
            problem,
            state,
            &ws.dx,
            info.energy,
            slope,
            noise,
            alpha_max,
            load,
            params,
            &mut ws.trial,
        ) {
            LineSearch::Accepted(_) => std::mem::swap(state, &mut ws.trial),
            LineSearch::Failed => return failed(iteration, "line search found no decrease", last),
        }
    }
    failed(
        params.max_iterations,
        &format!("no convergence in {} iterations", params.max_iterations),
        last,
    )
}

/// Assembles at `state`, factors the unshifted Hessian (its inertia, and the Newton step in
/// `ws.dx` when it factors) and measures the residual, its round-off floor and the decrement.
fn measure<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
) -> (IterateMeasures, crate::solver::AssemblyInfo) {
    let (m, info, _) = measure_with(problem, state, load, params, ws, false);
    (m, info)
}

/// Energy, gradient and Hessian at `state` into the workspace (see [`measure_with`]): the
/// whole Hessian, with the lagged groups' part kept apart in `ws.lagged` when the problem has
/// such groups and `params.lagged_first_step` is on; or, if `lag` and that part is fresh, the
/// other groups' Hessian plus the kept part (returns true then).
fn assemble_hessian<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
    lag: bool,
) -> (crate::solver::AssemblyInfo, bool) {
    let groups = if params.lagged_first_step {
        problem.lagged_hessian_groups()
    } else {
        TermSet::NONE
    };
    if groups != TermSet::NONE {
        let reuse = lag && ws.lagged_fresh && ws.lagged.is_some();
        let kept = ws.lagged.get_or_insert_with(|| ws.hess.clone());
        let mut asm = Assembler::new(
            TermSet::ALL,
            Some(&mut ws.grad),
            Some(&mut ws.hess),
            Some(&mut ws.abs_grad),
        )
        .lagging(groups, (!reuse).then_some(&mut *kept));
        problem.assemble_selected(state, load, &mut asm);
        let info = asm.finish();
        // Clones of one matrix always add; a storage that cannot assembles whole below.
        if ws.hess.add_same_pattern(kept) {
            ws.lagged_fresh = true;
            return (info, reuse);
        }
    }
    ws.lagged_fresh = false;
    let info = problem.assemble(state, load, &mut ws.grad, &mut ws.hess, &mut ws.abs_grad);
    (info, false)
}

/// [`measure`], with the lagged Hessian of the problem's slow groups if `lag` (see
/// [`SolverParams::lagged_first_step`]); the flag returned says whether it was used.
fn measure_with<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
    lag: bool,
) -> (IterateMeasures, crate::solver::AssemblyInfo, bool) {
    let n = problem.n_free();
    let (info, lagged) = assemble_hessian(problem, state, load, params, ws, lag);
    let (residual, floor) = residual_and_floor(
        problem,
        state,
        params,
        &ws.grad,
        &ws.abs_grad,
        &ws.hess,
        &mut ws.scales,
    );
    let force_scale = if info.external_force > 0.0 {
        info.external_force
    } else {
        0.5 * (0..n)
            .map(|i| ws.abs_grad[i] / ws.scales.force_length[i])
            .fold(0.0, f64::max)
    };
    // The unshifted factorization gives the inertia and, if it exists, the Newton step.
    let inertia = ws.ldlt.factorize(&ws.hess, 0.0).ok();
    let mut decrement = f64::INFINITY;
    if inertia.is_some() {
        for i in 0..n {
            ws.dx[i] = -ws.grad[i];
        }
        ws.ldlt.solve_in_place(&mut ws.dx);
        decrement = dot(&ws.grad, &ws.dx).abs();
    }
    (
        IterateMeasures {
            residual,
            floor,
            external_force: info.external_force,
            force_scale,
            decrement,
            energy: info.energy,
            inertia,
            hessian_lags: false,
        },
        info,
        lagged,
    )
}

/// Takes the full step `ws.dx` from `state` into `ws.trial` and assembles the gradient there
/// (into `ws.trial_grad`, its round-off scale into `ws.abs_grad`; no Hessian). Returns the
/// assembly's measures, the residual and its round-off floor (with the workspace Hessian's
/// diagonal standing in for the trial's).
fn full_step_trial<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
) -> (crate::solver::AssemblyInfo, f64, f64) {
    problem.displace(state, &ws.dx, 1.0, &mut ws.trial);
    let mut asm = Assembler::<P::Hessian>::new(
        TermSet::ALL,
        Some(&mut ws.trial_grad),
        None,
        Some(&mut ws.abs_grad),
    );
    problem.assemble_selected(&ws.trial, load, &mut asm);
    let info = asm.finish();
    let (residual, floor) = residual_and_floor(
        problem,
        &ws.trial,
        params,
        &ws.trial_grad,
        &ws.abs_grad,
        &ws.hess,
        &mut ws.scales,
    );
    (info, residual, floor)
}

/// The outcome of [`chord_final_check`].
enum ChordCheck {
    /// The full Newton step reached an equilibrium; the state is there.
    Converged,
    /// Not converged, but the full step lowered the residual; the state is there.
    Improved,
    /// The step was refused; state and workspace are as before.
    Rejected,
}

/// True if the Newton decrement test of [`converged`] is expected to pass after the full
/// Newton step from the measured iterate: it passes here already, or quadratic convergence
/// from the previous iterate's decrement forecasts it (e ↦ C e² for the error makes the
/// decrement d ∝ e² go as d_{k+1} ≈ d_k³ / d_{k−1}²).
fn next_decrement_passes(
    last: &IterateMeasures,
    previous: Option<f64>,
    info: &crate::solver::AssemblyInfo,
    params: &SolverParams,
) -> bool {
    let scale = if info.external_work != 0.0 {
        info.external_work.abs()
    } else {
        info.energy_magnitude
    };
    let bound = params.energy_tolerance * scale;
    let d = last.decrement;
    d <= bound || previous.is_some_and(|p| p > 0.0 && d < p && d * (d / p) * (d / p) <= bound)
}

/// At an iterate whose decrement passes but whose residual does not, with `ws.dx` its Newton
/// step and `ws.ldlt` its positive definite factorization: takes the full step and tests
/// convergence there from a gradient-only assembly, with the chord step (the new gradient
/// solved with this factorization) standing in for the Newton step (see
/// [`SolverParams::chord_final_check`]). Near an equilibrium the full Newton step converges
/// quadratically, so the new point usually passes, and the Hessian is neither assembled nor
/// factored there.
fn chord_final_check<P: EquilibriumProblem>(
    problem: &P,
    state: &mut P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
    last: &mut IterateMeasures,
) -> ChordCheck {
    let n = problem.n_free();
    if !(problem.max_step(state, &ws.dx) >= 1.0) {
        return ChordCheck::Rejected;
    }
    let (info, residual, floor) = full_step_trial(problem, state, load, params, ws);
    if !(residual < last.residual) {
        return ChordCheck::Rejected;
    }
    let force_scale = if info.external_force > 0.0 {
        info.external_force
    } else {
        0.5 * (0..n)
            .map(|i| ws.abs_grad[i] / ws.scales.force_length[i])
            .fold(0.0, f64::max)
    };
    for i in 0..n {
        ws.trial_dx[i] = -ws.trial_grad[i];
    }
    if ws.ldlt.try_solve_in_place(&mut ws.trial_dx).is_err() {
        return ChordCheck::Rejected;
    }
    let measures = IterateMeasures {
        residual,
        floor,
        external_force: info.external_force,
        force_scale,
        decrement: dot(&ws.trial_grad, &ws.trial_dx).abs(),
        energy: info.energy,
        inertia: last.inertia,
        hessian_lags: true,
    };
    // The state moves to the trial either way (the step lowered the residual).
    std::mem::swap(state, &mut ws.trial);
    std::mem::swap(&mut ws.grad, &mut ws.trial_grad);
    std::mem::swap(&mut ws.dx, &mut ws.trial_dx);
    let previous = last.residual;
    *last = measures;
    if converged(
        last,
        &info,
        params,
        problem,
        state,
        ws,
        Some(previous),
        false,
    ) {
        ChordCheck::Converged
    } else {
        ChordCheck::Improved
    }
}

/// Largest residual force (N) and its round-off floor (N) from a gradient and its Σ|term|,
/// with the DOF scales and `hess`'s diagonal (the floor's stiffness scale) gathered into
/// `scales` first.
#[allow(clippy::too_many_arguments)]
fn residual_and_floor<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    params: &SolverParams,
    grad: &[f64],
    abs_grad: &[f64],
    hess: &P::Hessian,
    scales: &mut FloorScales,
) -> (f64, f64) {
    let eps = f64::EPSILON;
    let n = grad.len();
    // resize() only allocates the first time.
    scales.force_length.resize(n, 0.0);
    scales.magnitude.resize(n, 0.0);
    scales.diagonal.resize(n, 0.0);
    problem.dof_scales(state, &mut scales.force_length, &mut scales.magnitude);
    hess.diagonal_into(&mut scales.diagonal);
    let mut residual: f64 = 0.0;
    let mut floor: f64 = 0.0;
    for i in 0..n {
        let len = scales.force_length[i];
        residual = residual.max(grad[i].abs() / len);
        let noise = abs_grad[i] + scales.diagonal[i].abs() * scales.magnitude[i];
        floor = floor.max(params.roundoff_factor * eps * noise / len);
    }
    (residual, floor)
}

/// The convergence test (design.md §4.3): the residual force is at most
/// max(force_tolerance·‖f_ext‖, round-off floor) *and* either the Newton decrement is at most
/// energy_tolerance·|work of the loads| or the Newton step is below round-off.
#[allow(clippy::too_many_arguments)]
fn converged<P: EquilibriumProblem>(
    last: &IterateMeasures,
    info: &crate::solver::AssemblyInfo,
    params: &SolverParams,
    problem: &P,
    state: &P::State,
    ws: &NewtonWorkspace<P::State, P::Hessian>,
    previous_residual: Option<f64>,
    stalled: bool,
) -> bool {
    if stalled
        && last.inertia.is_some_and(|i| i.is_positive_definite())
        && last.residual <= STALL_ACCEPT * last.force_scale
        && !floor_above_loads(last)
    {
        return true;
    }
    let target = params.force_tolerance * last.force_scale;
    let force_ok = if last.residual <= target {
        true
    } else if last.residual <= last.floor {
        // Below the (conservative) round-off floor but not small against the load: accept
        // once the residual is small anyway, or once Newton no longer improves it — so that
        // "converged" means small relative to the load whenever round-off allows it, whatever
        // the stiffness ratio (the floor of a very stiff term can be a sizeable fraction of a
        // small load).
        last.residual <= FLOOR_ACCEPT * last.force_scale
            || (previous_residual.is_some_and(|p| last.residual > 0.5 * p)
                && !floor_above_loads(last))
    } else {
        false
    };
    if !force_ok {
        return false;
    }
    let tiny_step = last.inertia.is_some()
        && (0..ws.dx.len()).all(|i| ws.dx[i].abs() <= TINY_STEP * problem.dof_magnitude(state, i));
    // The decrement is measured against the work of the loads; a structure moved by its
    // supports alone has none, and then the elastic energy is the scale.
    let scale = if info.external_work != 0.0 {
        info.external_work.abs()
    } else {
        info.energy_magnitude
    };
    last.decrement <= params.energy_tolerance * scale || tiny_step
}

/// True if the residual is under its round-off floor but many times the external loads: the
/// state's term forces are so large (a singular term, a collapsed edge) that their
/// rounding exceeds the loads, and Newton can neither lower the residual nor call it an
/// equilibrium. A structure loaded only by its supports has no such test (its force scale is
/// its term forces).
fn floor_above_loads(last: &IterateMeasures) -> bool {
    last.external_force > 0.0 && last.residual > FLOOR_CEILING * last.external_force
}

/// After convergence: up to `params.polish_iterations` full Newton steps, each kept only if it
/// lowers the residual. The reactions balance the loads up to the sum of the free DOFs'
/// residuals, so a balance at round-off needs a residual at round-off, below what the
/// convergence test (a conservative floor) asks and below what a line search on the energy
/// can see.
fn polish<P: EquilibriumProblem>(
    problem: &P,
    state: &mut P::State,
    load: f64,
    params: &SolverParams,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
    last: &mut IterateMeasures,
) {
    let steps = params.polish_iterations.unwrap_or(0);
    for _ in 0..steps {
        if last.inertia.is_none() {
            return;
        }
        // A step of a few ulps of every DOF only moves the state by its rounding: the residual
        // it reaches is round-off noise, not an improvement worth an assembly.
        if (0..ws.dx.len())
            .all(|i| ws.dx[i].abs() <= ROUNDOFF_STEP * problem.dof_magnitude(state, i))
        {
            return;
        }
        let (info, r, floor) = full_step_trial(problem, state, load, params, ws);
        if !(r < last.residual) {
            if last.hessian_lags {
                // A chord step from a lagging factorization can be worse than the state: the
                // soft modes may still be off by more than the residual shows. Measure the
                // state and polish with its own Newton step.
                let (m, _) = measure(problem, state, load, params, ws);
                *last = m;
                continue;
            }
            // Rejected: the workspace still holds the state's gradient, Hessian and factors.
            return;
        }
        std::mem::swap(state, &mut ws.trial);
        if params.chord_final_check {
            // Keep the factorization: the next polishing step is the chord step.
            std::mem::swap(&mut ws.grad, &mut ws.trial_grad);
            for i in 0..ws.dx.len() {
                ws.dx[i] = -ws.grad[i];
            }
            if ws.ldlt.try_solve_in_place(&mut ws.dx).is_err() {
                let (m, _) = measure(problem, state, load, params, ws);
                *last = m;
                continue;
            }
            let halved = r <= 0.5 * last.residual;
            last.residual = r;
            last.floor = floor;
            last.energy = info.energy;
            last.decrement = dot(&ws.grad, &ws.dx).abs();
            last.hessian_lags = true;
            if r <= floor / params.roundoff_factor {
                // At the rounding of the term forces themselves (the floor without its safety
                // factor): no step can do better.
                return;
            }
            if halved {
                continue;
            }
            if r <= floor {
                // At the round-off floor: nothing left to polish.
                return;
            }
            // The chord steps stall above round-off (the Hessian changed too much since it
            // was factored): polish on with true Newton steps.
            let (m, _) = measure(problem, state, load, params, ws);
            *last = m;
            continue;
        }
        let (m, _) = measure(problem, state, load, params, ws);
        *last = m;
    }
}

fn max_entry(v: &[f64]) -> f64 {
    v.iter().cloned().fold(f64::MIN_POSITIVE, f64::max)
}

fn min_entry(v: &[f64]) -> f64 {
    v.iter()
        .cloned()
        .fold(f64::INFINITY, f64::min)
        .max(f64::MIN_POSITIVE)
}

/// Factors H + shift·M with M = `ws.diag` (in place, H restored afterwards); true if positive
/// definite.
fn factor_shifted<S, M: SymmetricMatrix>(
    ws: &mut NewtonWorkspace<S, M>,
    n: usize,
    shift: f64,
) -> bool {
    for i in 0..n {
        ws.hess.add(i, i, shift * ws.diag[i]);
    }
    let ok = matches!(ws.ldlt.factorize(&ws.hess, 0.0), Ok(i) if i.negative == 0 && i.zero == 0);
    for i in 0..n {
        ws.hess.add(i, i, -shift * ws.diag[i]);
    }
    ok
}

/// |cos| of the angle between the gradient and an M-normalized mode `shape` (vᵀMv = 1), both
/// measured in the mass metric: |gᵀv| / ‖M^{-1/2} g‖ (`mass` holds M's diagonal).
fn mass_metric_cosine(grad: &[f64], shape: &[f64], mass: &[f64]) -> f64 {
    let g_norm = grad
        .iter()
        .zip(mass)
        .map(|(g, m)| g * g / m)
        .sum::<f64>()
        .sqrt();
    let c = dot(grad, shape).abs() / g_norm;
    if c.is_finite() {
        c
    } else {
        0.0
    }
}

/// A gradient whose cosine with the lowest mode (mass metric) is at most this is orthogonal to
/// it to round-off: a symmetric saddle.
const SADDLE_SYMMETRY: f64 = 1e-9;

/// True if the gradient is orthogonal (to round-off) to the lowest mode of `ws.hess` in the
/// mass metric, which is negative: line search cannot leave such a saddle, so Newton should
/// converge to it. The mode of the shift (`ws.shift_mode`, 1e-3 in λ) is refined to 1e-6 by
/// warm slicing: a few factorizations, where a cold eigensolve of H took about twenty (a
/// sixth of a buckled protocol run). `ws.diag` must hold the mass metric.
fn saddle_is_symmetric<P: EquilibriumProblem>(
    problem: &P,
    ws: &mut NewtonWorkspace<P::State, P::Hessian>,
) -> bool {
    let refined = slice_lowest_mode(
        problem,
        &ws.hess,
        &mut ws.scaled,
        &mut ws.ldlt,
        1e-6,
        &mut ws.eigen,
        &mut ws.shift_mode,
        true,
    );
    refined.is_ok()
        && ws.shift_mode.value < 0.0
        && mass_metric_cosine(&ws.grad, &ws.shift_mode.shape, &ws.diag) <= SADDLE_SYMMETRY
}

fn failed(iterations: usize, why: &str, last: IterateMeasures) -> NewtonOutcome {
    NewtonOutcome {
        converged: false,
        iterations,
        failure: Some(why.to_string()),
        last,
    }
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
