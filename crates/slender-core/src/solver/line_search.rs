//! Backtracking line search with the Armijo condition on the total energy.

use super::params::SolverParams;
use super::problem::EquilibriumProblem;

/// Outcome of a line search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineSearch {
    /// Step length accepted; `trial` holds the new state.
    Accepted(f64),
    /// No step length gave a sufficient decrease.
    Failed,
}

/// Backtracks from `alpha_max` until φ(x + α dx) ≤ E(x) + c₁ α gᵀdx, φ the problem's
/// [`merit`](EquilibriumProblem::merit) (the energy, unless the model says otherwise).
///
/// `slope` is gᵀdx (< 0 for a descent direction). When the predicted decrease is below the
/// round-off of the energy (`energy_noise`, J) the energy cannot rank the trial points, so
/// the step is accepted when the energy has not risen by more than that noise: this is the
/// quadratic-convergence regime, where the full Newton step is right.
#[allow(clippy::too_many_arguments)]
pub fn armijo_backtracking<P: EquilibriumProblem>(
    problem: &P,
    state: &P::State,
    dx: &[f64],
    energy: f64,
    slope: f64,
    energy_noise: f64,
    alpha_max: f64,
    load: f64,
    params: &SolverParams,
    trial: &mut P::State,
) -> LineSearch {
    if !(slope < 0.0) {
        return LineSearch::Failed;
    }
    let mut alpha = alpha_max;
    for _ in 0..=params.max_backtracks {
        problem.displace(state, dx, alpha, trial);
        let e = problem.merit(trial, load);
        let predicted = params.armijo * alpha * slope;
        if e.is_finite()
            && (e <= energy + predicted
                || (-alpha * slope <= energy_noise && e <= energy + energy_noise))
        {
            return LineSearch::Accepted(alpha);
        }
        alpha *= 0.5;
    }
    LineSearch::Failed
}
