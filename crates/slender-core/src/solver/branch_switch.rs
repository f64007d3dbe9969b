//! Branch switching: from a converged *unstable* equilibrium, follow its lowest mode to a stable
//! one (design.md §4.5). The state is kicked along ± the mode and minimized from both kicks; the
//! stable result of lower energy wins (in symmetric problems the two are mirror images). Where
//! the result is still unstable (several unstable modes), the switch is repeated along the new
//! lowest mode.

use super::continuation::EquilibriumSolver;
use super::problem::EquilibriumProblem;
use super::report::SolveReport;

/// Largest number of successive switches (each along the lowest mode of the last result).
const MAX_SWITCHES: usize = 6;

/// Largest residual, relative to the force scale, of an equilibrium a switch may land on. A
/// solve may report convergence at its round-off floor, and near a singular point of a load's
/// potential (a dead moment's twist angle at a half turn, `framed/moment.rs`) that floor is
/// huge: a kick that ran there found no equilibrium, whatever the test said.
pub(crate) const SWITCH_RELATIVE_RESIDUAL: f64 = 1e-6;

/// What a branch switch did.
#[derive(Clone, Debug, PartialEq)]
pub struct BranchSwitch {
    /// Energy of the new equilibrium minus that of the unstable one (J; negative).
    pub energy_drop: f64,
    /// Number of switches made (successive unstable modes followed).
    pub switches: usize,
    /// The solve report of the new equilibrium.
    pub report: SolveReport,
}

/// The kick scale that moves the largest coordinate DOF of `mode` (DOFs with force length 1)
/// by `amplitude` (m).
pub fn kick_scale<P: EquilibriumProblem>(problem: &P, mode: &[f64], amplitude: f64) -> f64 {
    let largest = (0..mode.len())
        .filter(|&i| problem.force_length(i) == 1.0)
        .map(|i| mode[i].abs())
        .fold(0.0, f64::max);
    if largest > 0.0 {
        amplitude / largest
    } else {
        0.0
    }
}

/// Puts into `out` the state `from` kicked by `scale` × `mode`, or by the part of that kick the
/// problem allows ([`EquilibriumProblem::kick_limit`]: a kick must not push a cable into or
/// through an obstacle).
pub(crate) fn kick<P: EquilibriumProblem>(
    problem: &P,
    from: &P::State,
    mode: &[f64],
    scale: f64,
    out: &mut P::State,
) {
    let dx: Vec<f64> = mode.iter().map(|m| m * scale).collect();
    let limit = problem.kick_limit(from, &dx);
    if limit >= 1.0 {
        problem.displace(from, mode, scale, out);
    } else {
        problem.displace(from, &dx, limit.max(0.0), out);
    }
}

/// From the converged unstable equilibrium `state` at load factor `load` (the solver's last
/// solve, with its lowest mode computed), follows the lowest mode to a stable equilibrium with
/// minimizations of at most `max_iterations` Newton iterations, kicking by `amplitude` (m, the
/// largest coordinate change). On success `state` is the new equilibrium; on failure it is left
/// unchanged, the solver re-measured there, and `None` returned. A model with lagged (follower) loads is left as it is
/// (`None`): its Hessian's modes are the frozen loads' (see
/// [`EquilibriumProblem::has_lagged_loads`]).
pub fn follow_unstable_mode<P: EquilibriumProblem>(
    problem: &P,
    solver: &mut EquilibriumSolver<P::State, P::Hessian>,
    state: &mut P::State,
    load: f64,
    amplitude: f64,
    max_iterations: usize,
) -> Option<BranchSwitch> {
    if problem.has_lagged_loads() {
        return None;
    }
    let e0 = problem.energy(state, load);
    let saved = solver.params;
    solver.params.max_iterations = saved.max_iterations.max(max_iterations);
    solver.params.compute_lambda_min = true;
    let mut current = state.clone();
    let mut result = None;
    for switch in 1..=MAX_SWITCHES {
        let Some(mode) = solver.lowest_mode().map(|m| m.shape.clone()) else {
            break;
        };
        let scale = kick_scale(problem, &mode, amplitude);
        if !(scale > 0.0) {
            break;
        }
        let mut best: Option<(f64, P::State, SolveReport)> = None;
        let mut kicked = current.clone();
        for sign in [1.0, -1.0] {
            kick(problem, &current, &mode, sign * scale, &mut kicked);
            let report = solver.solve_in_place(problem, &mut kicked, load, load);
            if !report.converged() || !(report.relative_residual <= SWITCH_RELATIVE_RESIDUAL) {
                continue;
            }
            let e = problem.energy(&kicked, load);
            let better = match &best {
                None => true,
                Some((eb, _, rb)) => {
                    let (s_new, s_old) = (report.stable() == Some(true), rb.stable() == Some(true));
                    (s_new && !s_old) || (s_new == s_old && e < *eb)
                }
            };
            if better {
                best = Some((e, kicked.clone(), report));
            }
        }
        let Some((e, s, report)) = best else { break };
        current = s;
        let stable = report.stable() == Some(true);
        result = Some(BranchSwitch {
            energy_drop: e - e0,
            switches: switch,
            report,
        });
        if stable {
            break;
        }
        // Re-solve at the new state so that the solver holds its lowest mode for the next switch.
        let r = solver.solve_in_place(problem, &mut current, load, load);
        if !r.converged() {
            break;
        }
    }
    solver.params = saved;
    // A kick that relaxed back to the unstable state itself (an energy change of round-off)
    // is no switch: reporting one would say the mode was followed when nothing moved.
    let round_off = 64.0 * f64::EPSILON * e0.abs();
    match result {
        Some(r)
            if r.energy_drop < -round_off
                || (r.energy_drop <= 0.0 && r.report.stable() == Some(true)) =>
        {
            *state = current;
            Some(r)
        }
        _ => {
            // Leave the solver at the kept state, as the continuation's switch does: its
            // workspace holds the last kick's factorization and lowest mode, which a later
            // warm re-solve or switch would otherwise start from. (A copy is re-solved: the
            // state itself stays as it was, bit for bit.)
            let mut kept = state.clone();
            solver.solve_in_place(problem, &mut kept, load, load);
            None
        }
    }
}
