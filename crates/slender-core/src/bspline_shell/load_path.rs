//! What the load factor λ drives on a B-spline shell: the loads' scale and the rigid motion of
//! its clamps (the shell counterpart of the rod's `RodLoadPath`).
//!
//! A clamp moving with λ is a change of the state that the solver asks for before each step
//! ([`EquilibriumProblem::impose_load`](crate::solver::EquilibriumProblem::impose_load)): its
//! two control rows move exactly and, as a first guess when no secant predictor exists yet,
//! the free control points move with the same rigid motion when the other end is free (the
//! strip turns rigidly with its clamp) and by the length-preserving guess of
//! `shell::strip_guess` when it is clamped. A linearized guess would stretch the membrane at
//! second order (see `shell::mixed_update`).

use nalgebra::Rotation3;
use serde::{Deserialize, Serialize};

use crate::geometry::Vec3;
use crate::shell::Clamp;

use super::clamp::StripEnd;

/// A rigid motion of one clamp over the load path: at load factor λ ∈ [0, 1] a point x₀ of
/// the clamp is at `pivot + λ·translation + exp(λ·rotation)·(x₀ − pivot)`, x₀ being its
/// position at λ = 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ClampMotion {
    /// The clamped end that moves.
    pub end: StripEnd,
    /// Centre of the rotation at λ = 0 (m).
    pub pivot: [f64; 3],
    /// Rotation vector (rad) at λ = 1: axis × angle.
    pub rotation: [f64; 3],
    /// Translation (m) at λ = 1.
    pub translation: [f64; 3],
}

impl ClampMotion {
    /// A turn of `end` by `angle` (rad) about the x axis through the origin (the
    /// lateral-buckling protocol's clamp rotation).
    pub fn about_x(end: StripEnd, angle: f64) -> Self {
        Self {
            end,
            pivot: [0.0; 3],
            rotation: [angle, 0.0, 0.0],
            translation: [0.0; 3],
        }
    }

    /// The increment from load factor `from` to `to`, scaled by `w` ∈ [0, 1], as
    /// (rotation, centre, translation): x ↦ centre + translation + R (x − centre).
    fn increment(&self, from: f64, to: f64, w: f64) -> (Rotation3<f64>, Vec3, Vec3) {
        let (pivot, rotation, translation) = (
            Vec3::from(self.pivot),
            Vec3::from(self.rotation),
            Vec3::from(self.translation),
        );
        let d = (to - from) * w;
        (
            Rotation3::new(rotation * d),
            pivot + translation * from,
            translation * d,
        )
    }

    /// Where a point at `x` at load factor `from` is at `to`, for a fraction `w` of the motion.
    pub(crate) fn carry(&self, x: &Vec3, from: f64, to: f64, w: f64) -> Vec3 {
        let (r, centre, t) = self.increment(from, to, w);
        centre + t + r * (x - centre)
    }

    /// The rotation of the motion from load factor `from` to `to`.
    pub(crate) fn turn(&self, from: f64, to: f64) -> Rotation3<f64> {
        self.increment(from, to, 1.0).0
    }

    /// The clamp pose `clamp` (at `from`) moved to load factor `to`.
    pub(crate) fn move_clamp(&self, clamp: &Clamp, from: f64, to: f64) -> Clamp {
        let (r, centre, t) = self.increment(from, to, 1.0);
        Clamp {
            rotation: r * clamp.rotation,
            translation: r * (clamp.translation - centre) + centre + t,
        }
    }

    pub(crate) fn is_finite(&self) -> bool {
        self.pivot
            .iter()
            .chain(&self.rotation)
            .chain(&self.translation)
            .all(|c| c.is_finite())
    }
}

/// What the load factor λ of a [`BsplineShell`](super::BsplineShell) drives.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BsplineLoadPath {
    /// Factor on the loads (gravity and point forces) at λ = 0 and at λ = 1, linear in
    /// between. Default [0, 1]: λ ramps the loads.
    pub loads: [f64; 2],
    /// Clamps moved rigidly as λ goes from 0 to 1. Default none.
    pub motions: Vec<ClampMotion>,
}

impl Default for BsplineLoadPath {
    fn default() -> Self {
        Self {
            loads: [0.0, 1.0],
            motions: Vec::new(),
        }
    }
}

impl BsplineLoadPath {
    /// Full loads, the clamps moved by `motions` as λ goes from 0 to 1.
    pub fn clamp_motion(motions: Vec<ClampMotion>) -> Self {
        Self {
            loads: [1.0, 1.0],
            motions,
        }
    }

    /// Factor on the loads at load factor `load`.
    pub fn load_factor(&self, load: f64) -> f64 {
        self.loads[0] + load * (self.loads[1] - self.loads[0])
    }
}
