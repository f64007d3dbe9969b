//! What one time step reports.

/// The outcome of [`TimeStepper::step`](super::TimeStepper::step).
#[derive(Clone, Debug, PartialEq)]
pub struct StepReport {
    /// True if the step's Newton solve converged; otherwise the stepper did not advance.
    pub converged: bool,
    /// Newton iterations of the step.
    pub iterations: usize,
    /// Largest residual force (N) of the step's last iterate (moments count as force × length).
    pub residual: f64,
    /// The time (s) after the step (unchanged when the step failed).
    pub time: f64,
    /// Why the step failed, if it did.
    pub failure: Option<String>,
}
