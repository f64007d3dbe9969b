//! What the solver's load factor λ drives on a shell: the gravity ramp, or the clamp's rotation
//! at full gravity (design.md §4.4: the continuation is parameter-agnostic, λ and the clamp
//! angle σ are both parameters).
//!
//! Why the clamp angle is a continuation parameter rather than a prescribed jump: turning the
//! clamp of a heavy, deflected strip changes its shape non-rigidly, and a Newton start that
//! is off by more than about a thickness crawls (linear updates stretch the membrane at second
//! order). As a parameter, the clamp rotation gets the solver's adaptive steps and secant
//! predictor, like the gravity ramp.

use super::clamp::Clamp;
use crate::bspline_shell::ClampMotion;

/// The meaning of the load factor λ ∈ [0, 1] of a [`Shell`](super::Shell).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum LoadPath {
    /// Gravity scaled by λ; the clamp stays where the state has it.
    #[default]
    Gravity,
    /// Full gravity; the clamp turned about x to σ = `from` + λ·(`to` − `from`) (rad): the solver
    /// moves the state's clamp there before each step (`EquilibriumProblem::impose_load`).
    ClampRotation {
        /// σ at λ = 0 (rad).
        from: f64,
        /// σ at λ = 1 (rad).
        to: f64,
    },
    /// Full gravity; the clamps of the start and the end (indexed by
    /// [`StripEnd::index`](crate::bspline_shell::StripEnd::index)) moved rigidly as λ goes
    /// from 0 to 1 (a support drag or a prescribed motion stage).
    ClampMotion([Option<ClampMotion>; 2]),
}

impl LoadPath {
    /// Factor on gravity at load factor `load`.
    pub fn gravity_factor(&self, load: f64) -> f64 {
        match *self {
            LoadPath::Gravity => load,
            LoadPath::ClampRotation { .. } | LoadPath::ClampMotion(_) => 1.0,
        }
    }

    /// The start clamp at load factor `load` on the lateral-buckling protocol's path, or
    /// `None` if the path does not turn it about x.
    pub fn clamp_at(&self, load: f64) -> Option<Clamp> {
        match *self {
            LoadPath::Gravity | LoadPath::ClampMotion(_) => None,
            LoadPath::ClampRotation { from, to } => Some(Clamp::about_x(from + load * (to - from))),
        }
    }
}
