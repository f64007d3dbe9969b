//! One implicit time step with Coulomb friction: the step is solved with the current
//! stick/slide set, the set is updated from the result ([`ContactProblem::update_friction`]),
//! and while a contact changed between sticking and sliding the step is solved again from
//! its start with the new set — so every accepted step satisfies Coulomb's law at its end.
//!
//! Where the step starts, every sliding contact's origin is dragged to just behind it
//! ([`ContactProblem::restart_slides`]), so that its kinetic force opposes the slip of this
//! step, as lagged friction lags to the step's start.
//!
//! Within one step the set only moves forward: a contact that slipped in one of the step's
//! solves keeps sliding (against μ f_n) for the rest of the step, even if its slip then falls
//! back to its origin. Without this, a contact landing on a rough surface
//! can cycle — stuck at touchdown, slipping, stuck again where the slide ended, slipping
//! again — and never settle; it may stick again at the next step's update. Each contact then
//! changes at most twice per step (free → stick → slide), which bounds the re-solves.

use crate::dynamics::{FlatDofs, StepReport, TimeStepper};

use super::friction::Friction;
use super::problem::ContactProblem;
use super::sites::ContactSites;

/// Times a step may be re-solved with a new stick/slide set before it is reported as failed.
const MAX_SET_CHANGES: usize = 12;

/// Advances `stepper` (stepping `problem`) by one step with friction (see the module docs).
/// A step whose stick/slide set does not settle is reported as not converged, and the
/// stepper is left at the step's start.
pub fn step_with_friction<P: ContactSites + FlatDofs>(
    stepper: &mut TimeStepper<'_, ContactProblem<'_, P>>,
    problem: &ContactProblem<'_, P>,
) -> StepReport {
    problem.restart_slides(stepper.state());
    let start = stepper.clone();
    let mut iterations = 0;
    // Per contact: slipped in an earlier solve of this step.
    let mut slipped: Vec<bool> = Vec::new();
    for _ in 0..=MAX_SET_CHANGES {
        let mut report = stepper.step();
        iterations += report.iterations;
        report.iterations = iterations;
        if !report.converged {
            *stepper = start;
            return report;
        }
        let before = problem.friction_state();
        let update =
            problem.update_friction_keeping(stepper.state(), Some(start.state()), &slipped);
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
        if !update.changed() {
            return report;
        }
        *stepper = start.clone();
    }
    *stepper = start;
    StepReport {
        converged: false,
        iterations,
        residual: f64::NAN,
        time: stepper.time(),
        failure: Some(format!(
            "the stick/slide set of the contacts did not settle in {MAX_SET_CHANGES} re-solves"
        )),
    }
}
