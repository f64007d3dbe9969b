//! Solving a model in contact within a scene: the load path, with friction, taken in pieces
//! with the stick/slide set of the contacts settled after each — the same for the rod
//! structures and the shell strips of a [`Session`](super::Session).

use crate::contact::{ContactProblem, ContactSites, Friction};
use crate::linalg::AdaptiveMatrix;
use crate::solver::{EquilibriumSolver, SolveReport, SolveStatus};

use super::session::unsolved;

/// Pieces of a load path solved with friction (the stick/slide set updated after each).
pub const FRICTION_PIECES: usize = 10;

/// Relative change of the sliding force magnitudes below which their refresh needs no
/// re-solve.
const SLIDE_DRIFT: f64 = 1e-12;
/// Re-solves allowed for refreshed sliding forces. The refresh is a fixed-point iteration
/// on the magnitudes μ f_n; on cable_over_bracket its free end, sliding on the floor, changes
/// its normal force through its own friction and contracts by about 0.06 per refresh (from a
/// drift of 0.7): 12 refreshes bring it below [`SLIDE_DRIFT`], 5 left it at 1e-7.
const MAX_REFRESHES: usize = 12;

/// Largest change of a sliding force magnitude (μ f_n) between two friction states,
/// relative to it.
fn slide_drift(a: &[Friction], b: &[Friction]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| match (x, y) {
            (Friction::Slide { magnitude: f, .. }, Friction::Slide { magnitude: g, .. }) => {
                (f - g).abs() / g.max(f64::MIN_POSITIVE)
            }
            _ => 0.0,
        })
        .fold(0.0, f64::max)
}

/// Re-solves allowed for the stick/slide set of the contacts to settle after a solve.
pub const MAX_FRICTION_SOLVES: usize = 20;

/// Solves `problem` in `state` with `solver` from load `from` to `to`: with friction in
/// [`FRICTION_PIECES`] pieces of the load path, after each the stick/slide set of the
/// contacts updated and the equilibrium re-solved (at the piece's end, warm) until the set
/// settles (at most [`MAX_FRICTION_SOLVES`] times; not settling is reported as not
/// converged). The problem keeps the friction state the returned equilibrium was solved with.
/// One function for every model a scene holds in contact (rod structures, shell strips).
pub(crate) fn solve_with_contact<P: ContactSites>(
    problem: &ContactProblem<'_, P>,
    solver: &mut EquilibriumSolver<P::State, AdaptiveMatrix>,
    state: &mut P::State,
    from: f64,
    to: f64,
) -> SolveReport {
    // With friction, the load path is taken in pieces with the stick/slide set updated after
    // each: a sticking contact's anchor is unlimited within a solve, so one solve over a long
    // path would drag (or lift) what should slide.
    let rough = problem.obstacles().iter().any(|o| o.friction() > 0.0);
    let pieces = if rough && from != to {
        FRICTION_PIECES
    } else {
        1
    };
    let mut report = unsolved(String::new());
    let (mut iterations, mut load_steps) = (0, 0);
    // A barrier's Hessian changes too much between iterates for chord steps to polish the
    // residual down to round-off (the reactions would balance the loads less well).
    let params = solver.params;
    solver.params.chord_final_check = false;
    for piece in 0..pieces {
        let a = from + (to - from) * piece as f64 / pieces as f64;
        let b = if piece + 1 == pieces {
            to
        } else {
            from + (to - from) * (piece + 1) as f64 / pieces as f64
        };
        report = settle_friction(problem, solver, state, a, b);
        iterations += report.iterations;
        load_steps += report.load_steps;
        if !report.converged() {
            if report.iterations >= params.max_total_iterations {
                if let SolveStatus::NotConverged { reason } = &mut report.status {
                    // What the budget usually means in contact (the scene fuzz test's crawling
                    // case, a barrier 10⁴ times too soft): say what to change.
                    reason.push_str(&format!(
                        "; in contact this usually means a barrier too soft for the loads (gaps squeezed far below the activation distance make every load step slow): try a larger `[contact] stiffness` than the {:e} used",
                        problem.params().stiffness
                    ));
                }
            }
            break;
        }
    }
    solver.params = params;
    report.iterations = iterations;
    report.load_steps = load_steps;
    report
}

/// Solves `problem` in `state` from load `from` to `to`, then updates the stick/slide set and
/// re-solves warm at `to` until it settles (see [`solve_with_contact`]).
fn settle_friction<P: ContactSites>(
    problem: &ContactProblem<'_, P>,
    solver: &mut EquilibriumSolver<P::State, AdaptiveMatrix>,
    state: &mut P::State,
    from: f64,
    to: f64,
) -> SolveReport {
    // The slides oppose the slip of this piece (their force at its start kept).
    problem.restart_slides(state);
    let mut previous = state.clone();
    let mut report = solver.solve_in_place(problem, state, from, to);
    let (mut resolves, mut refreshes) = (0, 0);
    // Within one piece of the load path the stick/slide set only moves forward, as within a
    // time step (`contact::step_with_friction`): a contact that slipped keeps sliding for the
    // rest of the piece. Otherwise a contact can cycle (stuck, slipping, stuck again where the
    // slide ended) and the set never settles (measured on cable_over_bracket, 1 cm drags of
    // the clamp along +x, +y, ±z: 1 of 24 converged before, 16 of 24 with this rule; with
    // the sliding force a convex dissipation potential instead of a dead force, the 20 drags
    // of tests/scene_contact.rs all converge); the next piece may stick it again.
    let mut slipped: Vec<bool> = Vec::new();
    while report.converged() {
        let before = problem.friction_state();
        let update = problem.update_friction_keeping(state, Some(&previous), &slipped);
        slipped.resize(before.len(), false);
        for ((old, new), slipped) in before
            .iter()
            .zip(problem.friction_state())
            .zip(&mut slipped)
        {
            if matches!((old, new), (Friction::Stick { .. }, Friction::Slide { .. })) {
                *slipped = true;
            }
        }
        // A released contact's anchor acted in the solve: solve again without it.
        if !update.changed() && update.released == 0 {
            // The update refreshed the sliding magnitudes to μ f_n of this state: while that
            // moves them, solve again (a few times at most); then keep the forces this state
            // was solved with, so that the reported forces balance exactly.
            let drift = slide_drift(&before, &problem.friction_state());
            if drift <= SLIDE_DRIFT || refreshes == MAX_REFRESHES {
                problem.set_friction_state(&before);
                break;
            }
            refreshes += 1;
        } else if resolves == MAX_FRICTION_SOLVES {
            report.status = SolveStatus::NotConverged {
                reason: format!(
                    "the stick/slide set of the contacts did not settle in {MAX_FRICTION_SOLVES} re-solves"
                ),
            };
            break;
        } else {
            resolves += 1;
        }
        previous.clone_from(state);
        let user = solver.params;
        solver.params.max_iterations = user.max_iterations.max(user.snap_iterations);
        let again = solver.solve_in_place(problem, state, to, to);
        solver.params = user;
        report.iterations += again.iterations;
        let total = report.iterations;
        report = SolveReport {
            iterations: total,
            load_steps: report.load_steps,
            ..again
        };
        if let SolveStatus::NotConverged { reason } = &report.status {
            // Keep the equilibrium of the previous stick/slide set, and say why.
            report.status = SolveStatus::NotConverged {
                reason: format!(
                    "no equilibrium with the contacts' friction: re-solve {resolves} after contacts began to slip did not converge ({reason}); the friction may not hold the structure"
                ),
            };
            state.clone_from(&previous);
        }
    }
    report
}
