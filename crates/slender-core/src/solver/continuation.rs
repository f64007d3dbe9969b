//! The load path: adaptive continuation in the load factor λ with a secant predictor
//! (design.md §4.4), and the solver facade. This is the one step controller of slender.
//!
//! What λ drives is the model's business: a gravity ramp, a clamp rotation, the prescribed
//! motion of supports (see [`EquilibriumProblem::impose_load`]). The user never chooses steps:
//! the solver first tries the whole change in one step (or `initial_load_step` of it), halves
//! the increment when Newton fails, doubles it after fast steps (up to `max_load_step`), and
//! predicts each step's start by extrapolating the last two converged states with the model's
//! [`difference`](EquilibriumProblem::difference) (a log map on rotation DOFs).

use crate::linalg::{SymmetricBandMatrix, SymmetricFactor, SymmetricMatrix};

use super::lagged_loads::settle_loads;
use super::newton::{newton, DeferredCheck, IterateMeasures, NewtonWorkspace};
use super::params::SolverParams;
use super::problem::EquilibriumProblem;
use super::report::{SolveReport, SolveStatus};
use super::stability::{
    classify_modes, is_stable, lowest_mode_with, null_band, EigenWorkspace, LowestMode, ModeCounts,
};

/// A state and the report that says what it is.
#[derive(Clone, Debug)]
pub struct Solution<S> {
    /// The final state: an equilibrium at the full load if `report` says converged,
    /// otherwise the last converged load step (or the start).
    pub state: S,
    /// Status, iterations, residuals, inertia and stability margin.
    pub report: SolveReport,
    /// Lowest mode of the Hessian at the final state, when computed.
    pub lowest_mode: Option<LowestMode>,
}

/// Largest load step (fraction of the span) that may be retried as a snap.
const SNAP_MAX_STEP: f64 = 1.0 / 32.0;

/// Halvings of a load step allowed to bracket a bifurcation crossed inside it.
const MAX_BRACKETING: usize = 24;
/// Bracketing stops once the step is this fraction of the whole load change.
const BRACKET_RESOLUTION: f64 = 1.0 / 256.0;
/// Kick of a branch switch inside the continuation: the largest coordinate change, as a
/// fraction of the structure's size.
const SWITCH_AMPLITUDE: f64 = 1e-2;

/// Relative accuracy of the reported smallest eigenvalue.
const EIGEN_TOLERANCE: f64 = 1e-6;

/// An equilibrium solver with reusable buffers for one problem size: after the first solve,
/// [`solve_in_place`](Self::solve_in_place) allocates nothing on the way to a converged,
/// stable equilibrium.
#[derive(Clone, Debug)]
pub struct EquilibriumSolver<S, M: SymmetricMatrix = SymmetricBandMatrix> {
    /// Parameters.
    pub params: SolverParams,
    ws: NewtonWorkspace<S, M>,
    predictor: Vec<f64>,
    scaled: M,
    previous: S,
    candidate: S,
    eigen: EigenWorkspace,
    mode: LowestMode,
    mode_valid: bool,
    /// True when `ws.ldlt` holds the positive definite factorization of the Hessian at the
    /// last converged solve's final state: the next solve's first predictor is then
    /// corrected by a chord step with it (see [`Self::chord_step`]).
    factor_at_equilibrium: bool,
}

impl<S: Clone, M: SymmetricMatrix> EquilibriumSolver<S, M> {
    /// A solver for `problem`; `template` is any state of it.
    pub fn new<P: EquilibriumProblem<State = S, Hessian = M>>(
        problem: &P,
        template: &S,
        params: SolverParams,
    ) -> Self {
        let n = problem.n_free();
        Self {
            params,
            ws: NewtonWorkspace::new(problem, template),
            predictor: vec![0.0; n],
            scaled: problem.new_hessian(),
            previous: template.clone(),
            candidate: template.clone(),
            eigen: EigenWorkspace::default(),
            mode: LowestMode {
                value: 0.0,
                normalized: 0.0,
                shape: Vec::with_capacity(n),
            },
            mode_valid: false,
            factor_at_equilibrium: false,
        }
    }

    /// Ramps the load factor from `from` (where `start` is assumed to be an equilibrium, or
    /// close to one) to `to`, and returns the final state with its report.
    pub fn solve<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        start: &S,
        from: f64,
        to: f64,
    ) -> Solution<S> {
        let mut state = start.clone();
        let report = self.solve_in_place(problem, &mut state, from, to);
        Solution {
            state,
            report,
            lowest_mode: self.lowest_mode().cloned(),
        }
    }

    /// The lowest mode of the last solve's final Hessian, if it converged and
    /// `compute_lambda_min` is set.
    pub fn lowest_mode(&self) -> Option<&LowestMode> {
        self.mode_valid.then_some(&self.mode)
    }

    /// The Newton workspace (its Hessian and factorization are those of the last iterate).
    pub fn workspace(&self) -> &NewtonWorkspace<S, M> {
        &self.ws
    }

    /// As [`solve`](Self::solve), updating `state` in place: on return it is the equilibrium at
    /// `to` if the report says converged, otherwise the last converged load step (or the start,
    /// with the prescribed DOFs where the model puts them at the load reached).
    pub fn solve_in_place<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        state: &mut S,
        from: f64,
        to: f64,
    ) -> SolveReport {
        let params = self.params;
        // Only the load steps' solves may give up early on an indefinite Hessian (see
        // `SolverParams::indefinite_patience`); whatever cannot halve its step may not.
        let unlimited = SolverParams {
            indefinite_patience: None,
            ..params
        };
        let span = to - from;
        let mut load = from;
        let mut step = params.initial_load_step.min(params.max_load_step) * span;
        let mut previous_step: Option<f64> = None;
        let mut iterations = 0;
        let mut load_steps = 0;
        let mut rejected = 0;
        let mut last = IterateMeasures::default();
        let mut failure: Option<String> = None;
        let mut snapped_at: Option<f64> = None;
        let mut snaps = 0;
        // Following the stable branch (`follow_stable`): whether the last equilibrium was
        // stable, halvings spent bracketing a bifurcation, and branch switches made.
        let mut stable_before = true;
        let mut bracketing = 0;
        let mut switches = 0;
        self.mode_valid = false;
        let mut chord = std::mem::replace(&mut self.factor_at_equilibrium, false);

        // Span 0 (e.g. a warm re-solve at the same load): a single Newton solve.
        if span == 0.0 {
            let out = newton(problem, state, to, &unlimited, &mut self.ws);
            let out = settle_loads(problem, state, to, &unlimited, &mut self.ws, out);
            iterations += out.iterations;
            last = out.last;
            if !out.converged {
                failure = out.failure;
            } else {
                load_steps = 1;
            }
        } else {
            loop {
                if !(step.is_finite() && span.is_finite()) {
                    // A NaN or infinite load factor would never shrink below the smallest
                    // step: refuse it instead of halving forever.
                    failure = Some(format!(
                        "the load factor range [{from}, {to}] or its step {step} is not finite"
                    ));
                    break;
                }
                if iterations >= params.max_total_iterations {
                    // Deterministic, unlike a time limit: the same input gives up at the same
                    // iterate whatever the machine.
                    failure = Some(format!(
                        "the solve's budget of {} Newton iterations (solver.max_total_iterations) ran out at load factor {load:.6}, after {load_steps} load steps and {rejected} rejected ones",
                        params.max_total_iterations
                    ));
                    break;
                }
                let remaining = to - load;
                if step.abs() > remaining.abs() {
                    step = remaining;
                }
                let target = load + step;
                self.predict(
                    problem,
                    state,
                    previous_step.map(|p| step / p),
                    load,
                    target,
                );
                if std::mem::take(&mut chord) && params.chord_predictor {
                    self.chord_step(problem, load, target);
                }
                let mut out = newton(problem, &mut self.candidate, target, &params, &mut self.ws);
                iterations += out.iterations;
                if !out.converged
                    && step.abs() <= SNAP_MAX_STEP * span.abs()
                    && !snapped_at.is_some_and(|l: f64| l == load)
                {
                    // Past a limit point (fold) of the loading path no nearby equilibrium
                    // exists and smaller steps cannot help: let the minimization run longer
                    // from the last equilibrium so that it settles on the branch the structure
                    // snaps to. Tried once per load level, and only once steps are small: a
                    // long minimization over a large load step could settle in a distant,
                    // spurious minimum instead (e.g. a kinked coil).
                    snapped_at = Some(load);
                    self.predict(problem, state, None, load, target);
                    let long = SolverParams {
                        max_iterations: params.snap_iterations,
                        ..unlimited
                    };
                    out = newton(problem, &mut self.candidate, target, &long, &mut self.ws);
                    iterations += out.iterations;
                    if out.converged {
                        snaps += 1;
                    }
                }
                let before = out.iterations;
                let out = settle_loads(
                    problem,
                    &mut self.candidate,
                    target,
                    &unlimited,
                    &mut self.ws,
                    out,
                );
                iterations += out.iterations - before;
                let mut out = out;
                // With lagged (follower) loads the Hessian is the frozen loads': no mode of it
                // is followed (see `EquilibriumProblem::has_lagged_loads`).
                if params.follow_stable && out.converged && !problem.has_lagged_loads() {
                    let unstable = out.last.inertia.is_some_and(|i| i.negative > 0)
                        && classify_modes(
                            problem,
                            &self.ws.hess,
                            &mut self.scaled,
                            &mut self.ws.ldlt,
                        )
                        .is_none_or(|(m, _)| m.unstable > 0);
                    if unstable && stable_before {
                        let negative = out.last.inertia.map_or(0, |i| i.negative);
                        // Several modes at once may be one multiple eigenvalue (a round rod buckles
                        // in any plane), so bracketing stops at a fine enough step anyway.
                        if negative > 1
                            && bracketing < MAX_BRACKETING
                            && step.abs() > BRACKET_RESOLUTION * span.abs()
                        {
                            // A bifurcation was crossed inside this step, and more than one
                            // mode went unstable: halve the step until the crossing is close.
                            bracketing += 1;
                            rejected += 1;
                            step *= 0.5;
                            continue;
                        }
                        // Just past it: follow the unstable mode to the stable branch.
                        let (switched, its) = self.switch_branch(problem, target, &unlimited);
                        iterations += its;
                        if let Some(o) = switched {
                            switches += 1;
                            out = o;
                        }
                    }
                }
                last = out.last;
                if out.converged {
                    if params.follow_stable {
                        stable_before = out.last.inertia.is_some_and(|i| i.negative == 0)
                            || classify_modes(
                                problem,
                                &self.ws.hess,
                                &mut self.scaled,
                                &mut self.ws.ldlt,
                            )
                            .is_some_and(|(m, _)| m.unstable == 0);
                        bracketing = 0;
                    }
                    load_steps += 1;
                    // previous ← state, state ← candidate (buffers rotate, nothing is copied).
                    std::mem::swap(&mut self.previous, state);
                    std::mem::swap(state, &mut self.candidate);
                    load = target;
                    previous_step = Some(step);
                    if load == to {
                        break;
                    }
                    if out.iterations <= params.fast_iterations {
                        step = (step * 2.0).clamp(
                            -params.max_load_step * span.abs(),
                            params.max_load_step * span.abs(),
                        );
                    }
                } else {
                    rejected += 1;
                    step *= 0.5;
                    if step.abs() < params.min_load_step * span.abs() {
                        failure = Some(format!(
                            "load step fell below {} of the load at load factor {load:.6}; last Newton: {}",
                            params.min_load_step,
                            out.failure.unwrap_or_default()
                        ));
                        break;
                    }
                }
            }
            // After a failure, measure the returned state at the *requested* load (with its
            // prescribed DOFs there), so that the residual shows that it is not an
            // equilibrium of the problem that was asked.
            if failure.is_some() {
                self.candidate.clone_from(state);
                problem.impose_load(&mut self.candidate, load, to, false);
                let p = SolverParams {
                    max_iterations: 0,
                    polish_iterations: None,
                    ..params
                };
                last = newton(problem, &mut self.candidate, to, &p, &mut self.ws).last;
            }
        }

        let status = match &failure {
            None => SolveStatus::Converged,
            Some(reason) => SolveStatus::NotConverged {
                reason: reason.clone(),
            },
        };
        // After newton() the workspace holds the Hessian at the last iterate, which is the
        // returned state when converged (the loop returns before stepping).
        if failure.is_none() && params.compute_lambda_min {
            // On convergence the workspace still holds the unshifted factorization of the
            // final Hessian; if it is positive definite, inverse iteration can reuse it.
            self.update_lowest_mode(problem, &last);
        }
        if failure.is_none()
            && params.follow_stable
            && last.hessian_lags
            && !(self.mode_valid && self.mode.value > null_band(problem, &self.ws.hess))
        {
            // A chord final check left the Hessian one step behind, and the stability analysis
            // needs more than the margin λ_min gives: measure the state itself.
            let p = SolverParams {
                max_iterations: 0,
                polish_iterations: None,
                chord_final_check: false,
                ..params
            };
            last = newton(problem, state, to, &p, &mut self.ws).last;
            if params.compute_lambda_min {
                self.update_lowest_mode(problem, &last);
            }
        }
        self.factor_at_equilibrium =
            failure.is_none() && last.inertia.is_some_and(|i| i.is_positive_definite());
        let modes = if failure.is_none() && params.follow_stable {
            if self.mode_valid && self.mode.value > null_band(problem, &self.ws.hess) {
                // The lowest eigenvalue is above the null band: no unstable and no null mode,
                // without the two shifted factorizations.
                Some(ModeCounts::default())
            } else {
                self.factor_at_equilibrium = false;
                classify_modes(problem, &self.ws.hess, &mut self.scaled, &mut self.ws.ldlt)
                    .map(|m| m.0)
            }
        } else {
            None
        };
        let lowest = self.lowest_mode();
        SolveReport {
            status,
            load_reached: load,
            iterations,
            load_steps,
            rejected_steps: rejected,
            snaps,
            branch_switches: switches,
            residual: last.residual,
            relative_residual: if last.force_scale > 0.0 {
                last.residual / last.force_scale
            } else {
                0.0
            },
            force_scale: last.force_scale,
            residual_floor: last.floor,
            energy_decrement: last.decrement,
            energy: last.energy,
            inertia: last.inertia,
            lambda_min: lowest.map(|m| m.value),
            lambda_min_normalized: lowest.map(|m| m.normalized),
            modes,
        }
    }

    /// The lowest mode of the Hessian in the workspace (measured as `last`), to
    /// [`EIGEN_TOLERANCE`]; with a positive definite factorization in the workspace, inverse
    /// iteration reuses it.
    fn update_lowest_mode<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        last: &IterateMeasures,
    ) {
        let positive_definite = last.inertia.is_some_and(|i| is_stable(&i));
        self.mode_valid = lowest_mode_with(
            problem,
            &self.ws.hess,
            positive_definite,
            &mut self.scaled,
            &mut self.ws.ldlt,
            EIGEN_TOLERANCE,
            &mut self.eigen,
            &mut self.mode,
        )
        .is_ok();
    }

    /// At the unstable equilibrium in `self.candidate` (load factor `load`), just past a
    /// bifurcation: kicks along its lowest mode (both signs) and minimizes; puts the stable
    /// result of lower energy into `self.candidate`. Returns its Newton outcome (None if no
    /// kick led to a stable equilibrium) and the iterations spent.
    fn switch_branch<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        load: f64,
        params: &SolverParams,
    ) -> (Option<super::newton::NewtonOutcome>, usize) {
        let mut its = 0;
        if lowest_mode_with(
            problem,
            &self.ws.hess,
            false,
            &mut self.scaled,
            &mut self.ws.ldlt,
            1e-6,
            &mut self.eigen,
            &mut self.mode,
        )
        .is_err()
        {
            return (None, 0);
        }
        let length = (0..problem.n_free())
            .filter(|&i| problem.force_length(i) == 1.0)
            .map(|i| problem.dof_magnitude(&self.candidate, i))
            .fold(0.0, f64::max);
        let scale =
            super::branch_switch::kick_scale(problem, &self.mode.shape, SWITCH_AMPLITUDE * length);
        if !(scale > 0.0) {
            return (None, 0);
        }
        let long = SolverParams {
            max_iterations: params.snap_iterations.max(params.max_iterations),
            ..*params
        };
        let start = self.candidate.clone();
        let e0 = problem.energy(&start, load);
        let mut best: Option<(f64, S, super::newton::NewtonOutcome)> = None;
        let mut kicked = start.clone();
        for sign in [1.0, -1.0] {
            super::branch_switch::kick(
                problem,
                &start,
                &self.mode.shape,
                sign * scale,
                &mut kicked,
            );
            let out = newton(problem, &mut kicked, load, &long, &mut self.ws);
            its += out.iterations;
            let stable = out.last.inertia.is_some_and(|i| i.negative == 0);
            let small = out.last.residual
                <= super::branch_switch::SWITCH_RELATIVE_RESIDUAL * out.last.force_scale;
            if !(out.converged && stable && small) {
                continue;
            }
            let e = problem.energy(&kicked, load);
            if e <= e0 && best.as_ref().is_none_or(|b| e < b.0) {
                best = Some((e, kicked.clone(), out));
            }
        }
        match best {
            Some((_, s, out)) => {
                self.candidate = s;
                // Leave the workspace at the chosen state (its Hessian and factorization).
                let again = newton(problem, &mut self.candidate, load, params, &mut self.ws);
                its += again.iterations;
                (Some(again).filter(|o| o.converged).or(Some(out)), its)
            }
            None => {
                // Measure the unstable state again: the workspace holds the last kick's
                // Hessian, whose inertia and lowest mode the report would otherwise give.
                self.candidate = start;
                let again = newton(problem, &mut self.candidate, load, params, &mut self.ws);
                its += again.iterations;
                (None, its)
            }
        }
    }

    /// Corrects the predictor in `self.candidate` by one chord step: the Newton step with the
    /// factorization of the previous equilibrium's Hessian (no assembly of a new Hessian, no
    /// new factorization), kept only if it lowers the merit the line search uses
    /// ([`EquilibriumProblem::merit`]). After a change of the loads (an interactive drag, a
    /// load step of a ramp) it is the tangent predictor, x + H⁻¹·Δf: the first Newton step
    /// from the last equilibrium, taken without the Hessian assembly and factorization there.
    ///
    /// Why the merit and not the energy: over a large load step a shell's linearized step
    /// stretches its membrane at second order, so its energy rises by orders of magnitude even
    /// where the step is the one Newton itself would take and keep (the mixed-integration-point
    /// merit leaves that stretch out, see `shell::mixed_update`); for every other model the
    /// merit is the energy.
    ///
    /// When the first guess turned the structure rigidly (a strip turned with its clamp,
    /// [`EquilibriumProblem::turn_free`]), the Hessian there is the previous one turned with
    /// it: the gradient is turned back, solved with the previous factorization, and the step
    /// turned forward, which is the turned state's Newton step.
    fn chord_step<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        from: f64,
        load: f64,
    ) {
        let n = problem.n_free();
        let mut asm = crate::assembly::Assembler::<M>::new(
            crate::assembly::TermSet::ALL,
            Some(&mut self.ws.grad),
            None,
            None,
        );
        problem.assemble_selected(&self.candidate, load, &mut asm);
        let info = asm.finish();
        for i in 0..n {
            self.predictor[i] = -self.ws.grad[i];
        }
        let turned = problem.turn_free(from, load, &mut self.predictor, true);
        if self
            .ws
            .ldlt
            .try_solve_in_place(&mut self.predictor)
            .is_err()
        {
            return;
        }
        if turned {
            problem.turn_free(from, load, &mut self.predictor, false);
        }
        let alpha = problem.max_step(&self.candidate, &self.predictor).min(1.0);
        problem.displace(&self.candidate, &self.predictor, alpha, &mut self.ws.trial);
        // The first Newton step after it may keep the slow part of the Hessian.
        self.ws.lag_next = self.params.lagged_first_step;
        // At α = 0 the merit is the energy (`info.energy`).
        if self.params.deferred_energy_check && problem.merit_is_energy() {
            // Newton's first measure computes the energy there anyway, and undoes the
            // predictor if it did not lower it (the state before it stays in `ws.trial`).
            std::mem::swap(&mut self.candidate, &mut self.ws.trial);
            self.ws.deferred = Some(DeferredCheck::Predictor {
                energy: info.energy,
            });
        } else if problem.merit(&self.ws.trial, load) < info.energy {
            std::mem::swap(&mut self.candidate, &mut self.ws.trial);
        }
    }

    /// Puts into `self.candidate` the start of the step from `load` to `target`: the current
    /// state extrapolated along the last converged increment scaled by `ratio` (the secant
    /// predictor, when a previous step exists), with the prescribed DOFs moved to `target`.
    fn predict<P: EquilibriumProblem<State = S, Hessian = M>>(
        &mut self,
        problem: &P,
        state: &S,
        ratio: Option<f64>,
        load: f64,
        target: f64,
    ) {
        let ratio = ratio.filter(|_| problem.secant_predictor());
        match ratio {
            Some(ratio) => {
                problem.difference(state, &self.previous, &mut self.predictor);
                for p in self.predictor.iter_mut() {
                    *p *= ratio;
                }
                let alpha = if problem.caps_predictor() {
                    problem.max_step(state, &self.predictor)
                } else {
                    1.0
                };
                problem.displace(state, &self.predictor, alpha, &mut self.candidate);
            }
            None => self.candidate.clone_from(state),
        }
        problem.impose_load(&mut self.candidate, load, target, ratio.is_none());
    }
}
