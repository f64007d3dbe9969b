//! Adaptive load stepping with a secant predictor (design.md §4.4), and the solver facade.
//!
//! The user never chooses load steps: the solver first tries the whole load change in one
//! step, halves the increment when Newton fails, doubles it after fast steps, and predicts
//! each step's start by extrapolating the last two converged states.

use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};

use super::newton::{newton, IterateMeasures, NewtonWorkspace};
use super::params::SolverParams;
use super::problem::EquilibriumProblem;
use super::report::{SolveReport, SolveStatus};
use super::stability::{lowest_mode, LowestMode};

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

/// Relative accuracy of the reported smallest eigenvalue.
const EIGEN_TOLERANCE: f64 = 1e-6;

/// An equilibrium solver with reusable buffers for one problem size.
#[derive(Clone, Debug)]
pub struct EquilibriumSolver<S, M: SymmetricMatrix = SymmetricBandMatrix> {
    /// Parameters.
    pub params: SolverParams,
    ws: NewtonWorkspace<S, M>,
    predictor: Vec<f64>,
    values: [Vec<f64>; 2],
    scaled: M,
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
            values: [vec![0.0; n], vec![0.0; n]],
            scaled: problem.new_hessian(),
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
        let params = self.params.clone();
        let span = to - from;
        let mut current = start.clone();
        let mut load = from;
        let mut step = params.initial_load_step * span;
        let mut previous_step: Option<f64> = None;
        let mut iterations = 0;
        let mut load_steps = 0;
        let mut rejected = 0;
        let mut last: IterateMeasures;
        let mut failure: Option<String> = None;
        let mut candidate = start.clone();
        let mut snapped_at: Option<f64> = None;
        let mut snaps = 0;

        // Span 0 (e.g. a warm re-solve at the same load): a single Newton solve.
        if span == 0.0 {
            let out = newton(problem, &mut current, to, &params, &mut self.ws);
            iterations += out.iterations;
            last = out.last;
            if !out.converged {
                failure = out.failure;
            } else {
                load_steps = 1;
            }
        } else {
            loop {
                let remaining = to - load;
                if step.abs() > remaining.abs() {
                    step = remaining;
                }
                let target = load + step;
                // Secant predictor: extrapolate along the last converged increment.
                candidate.clone_from(&current);
                if let Some(prev) = previous_step {
                    let ratio = step / prev;
                    for i in 0..self.predictor.len() {
                        self.predictor[i] = (self.values[1][i] - self.values[0][i]) * ratio;
                    }
                    problem.displace(&current, &self.predictor, 1.0, &mut candidate);
                }
                let mut out = newton(problem, &mut candidate, target, &params, &mut self.ws);
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
                    candidate.clone_from(&current);
                    let long = SolverParams {
                        max_iterations: params.snap_iterations,
                        ..params.clone()
                    };
                    out = newton(problem, &mut candidate, target, &long, &mut self.ws);
                    iterations += out.iterations;
                    if out.converged {
                        snaps += 1;
                    }
                }
                last = out.last;
                if out.converged {
                    load_steps += 1;
                    problem.dof_values(&current, &mut self.values[0]);
                    problem.dof_values(&candidate, &mut self.values[1]);
                    std::mem::swap(&mut current, &mut candidate);
                    load = target;
                    previous_step = Some(step);
                    if load == to {
                        break;
                    }
                    if out.iterations <= params.fast_iterations {
                        step *= 2.0;
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
            // After a failure, measure the returned state at the *requested* load, so the
            // residual shows that it is not an equilibrium of the problem that was asked.
            if failure.is_some() {
                let mut probe = current.clone();
                let p = SolverParams {
                    max_iterations: 0,
                    ..params.clone()
                };
                last = newton(problem, &mut probe, to, &p, &mut self.ws).last;
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
        let lowest = if failure.is_none() && params.compute_lambda_min {
            // On convergence the workspace still holds the unshifted factorization of the
            // final Hessian; if it is positive definite, inverse iteration can reuse it.
            let positive_definite =
                matches!(last.inertia, Some(i) if i.negative == 0 && i.zero == 0);
            lowest_mode(
                problem,
                &self.ws.hess,
                positive_definite,
                &mut self.scaled,
                &mut self.ws.ldlt,
                EIGEN_TOLERANCE,
            )
            .ok()
        } else {
            None
        };
        let report = SolveReport {
            status,
            load_reached: load,
            iterations,
            load_steps,
            rejected_steps: rejected,
            snaps,
            residual: last.residual,
            relative_residual: if last.external_force > 0.0 {
                last.residual / last.external_force
            } else {
                0.0
            },
            residual_floor: last.floor,
            energy_decrement: last.decrement,
            energy: last.energy,
            inertia: last.inertia,
            lambda_min: lowest.as_ref().map(|m| m.value),
            lambda_min_normalized: lowest.as_ref().map(|m| m.normalized),
        };
        Solution {
            state: current,
            report,
            lowest_mode: lowest,
        }
    }
}
