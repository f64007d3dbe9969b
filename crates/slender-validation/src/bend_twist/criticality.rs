//! Sub- or supercritical? Following the buckled branch toward the boundary.
//!
//! Deep inside the unstable window the branch switch lands on the 3-D equilibrium. That branch
//! is then continued toward the boundary X_c in small steps of X, each solve warm-started from
//! the previous 3-D state. At a supercritical pitchfork the out-of-plane amplitude A vanishes
//! continuously, A ∝ √δ at a relative distance δ from X_c; at a subcritical one the 3-D branch
//! turns back (a fold) at finite amplitude before reaching X_c, so the continuation loses it.
//! (Switching branches right next to the boundary does not work: the unstable eigenvalue is
//! tiny there and Newton slows down critically.)

use serde::{Deserialize, Serialize};
use slender_core::geometry::Vec3;
use slender_core::solver::{EquilibriumSolver, SolverParams};

use super::case::BendTwistCase;
use super::master_curve::critical_boundaries;
use super::stability::decide_with_state;
use super::sweep::BendTwistSweepError;

/// Relative distances into the window visited by the continuation, from deep to close.
const DELTAS: [f64; 8] = [0.2, 0.12, 0.07, 0.04, 0.02, 0.01, 0.005, 0.0025];

/// Largest relative disagreement of the two A² slopes for a supercritical verdict.
const MAX_NONLINEARITY: f64 = 0.3;
/// Largest discretization offset δ₀ of the boundary accepted (relative in X).
const MAX_OFFSET: f64 = 0.005;

/// The criticality of one boundary at one Y.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Criticality {
    /// Y.
    pub y: f64,
    /// "lower" (X_c1) or "upper" (X_c2).
    pub boundary: String,
    /// X_c from the master curve.
    pub x_c: f64,
    /// (δ, max|y|/L) along the continued 3-D branch.
    pub amplitudes: Vec<(f64, f64)>,
    /// Exponent p of A ∝ δ^p fitted on the two points closest to the boundary.
    pub exponent: f64,
    /// Where the fitted A² = k (δ − δ₀) vanishes: the discrete boundary's offset from X_c
    /// (relative), from the three points closest to the boundary.
    pub delta_0: f64,
    /// Relative disagreement of the two slopes of A² over those points (0: exactly linear).
    pub nonlinearity: f64,
    /// "supercritical" (p ≈ ½), "subcritical" (branch lost at finite amplitude) or
    /// "undetermined".
    pub kind: String,
}

/// Measures both boundaries at `y` with `elements_per_turn` elements per unit Y.
pub fn criticality(
    y: f64,
    elements_per_turn: f64,
    params: &SolverParams,
) -> Result<Vec<Criticality>, BendTwistSweepError> {
    let probe = BendTwistCase::new(1.0, y, elements_per_turn);
    let stiffness = probe.material.properties.stiffness;
    let b = critical_boundaries(y, stiffness.gj / stiffness.ei_min())?;
    let mut out = Vec::new();
    for (name, x_c, inward) in [("lower", b.lower, 1.0), ("upper", b.upper, -1.0)] {
        let Some(x_c) = x_c else { continue };
        let at = |d: f64| BendTwistCase::new(x_c * (1.0 + inward * d), y, elements_per_turn);
        let (first, mut state) = decide_with_state(&at(DELTAS[0]), params)?;
        let mut amplitudes = Vec::new();
        let mut lost_at_finite = false;
        if let Some(m) = first.buckled {
            amplitudes.push((DELTAS[0], m.max_y));
            for &d in &DELTAS[1..] {
                let case = at(d);
                let rod = case.build(Vec3::new(0.0, 0.0, -case.gravity()), Vec3::zeros())?;
                let sol =
                    EquilibriumSolver::new(&rod, &state, *params).solve(&rod, &state, 1.0, 1.0);
                if !sol.report.converged() {
                    break;
                }
                let a = sol
                    .state
                    .positions()
                    .iter()
                    .map(|p| p.y.abs())
                    .fold(0.0, f64::max)
                    / rod.length();
                // Falling back onto the planar state before the boundary while the previous
                // amplitude was still large is the signature of a fold (subcritical).
                if a < 1e-6 && amplitudes.last().is_some_and(|&(_, prev)| prev > 1e-2) {
                    lost_at_finite = true;
                    break;
                }
                amplitudes.push((d, a));
                state = sol.state;
            }
        }
        let n = amplitudes.len();
        let exponent = if n >= 2 {
            let (d1, a1) = amplitudes[n - 2];
            let (d2, a2) = amplitudes[n - 1];
            (a2 / a1).ln() / (d2 / d1).ln()
        } else {
            f64::NAN
        };
        // Normal form of a supercritical pitchfork: A² = k (δ − δ₀), δ₀ the discretization
        // offset of the boundary.
        let (delta_0, nonlinearity) = if n >= 3 {
            let p: Vec<(f64, f64)> = amplitudes[n - 3..]
                .iter()
                .map(|&(d, a)| (d, a * a))
                .collect();
            let k1 = (p[0].1 - p[1].1) / (p[0].0 - p[1].0);
            let k2 = (p[1].1 - p[2].1) / (p[1].0 - p[2].0);
            (p[2].0 - p[2].1 / k2, ((k1 - k2) / k2).abs())
        } else {
            (f64::NAN, f64::NAN)
        };
        let kind = if lost_at_finite {
            "subcritical"
        } else if n == DELTAS.len() && nonlinearity < MAX_NONLINEARITY && delta_0.abs() < MAX_OFFSET
        {
            "supercritical"
        } else {
            "undetermined"
        };
        out.push(Criticality {
            y,
            boundary: name.into(),
            x_c,
            amplitudes,
            exponent,
            delta_0,
            nonlinearity,
            kind: kind.into(),
        });
    }
    Ok(out)
}
