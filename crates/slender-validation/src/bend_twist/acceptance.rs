//! The bend–twist acceptance targets (issue 3), measured on a sweep.

use serde::{Deserialize, Serialize};

use super::regime::Regime;
use super::sweep::BendTwistRecord;
use crate::cantilever::Check;
use crate::materials::OMEGA_ROD;

/// Half-width of the band around the master curve, relative in X, inside which a grid point
/// is too close to the bifurcation to be scored.
pub const BAND: f64 = 0.05;

/// A grid point where the protocol and the stability route disagree.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Disagreement {
    /// X.
    pub x: f64,
    /// Y.
    pub y: f64,
    /// Stability decision (3-D?).
    pub stability_3d: bool,
    /// Protocol decision (3-D?).
    pub protocol_3d: bool,
    /// Ground truth (3-D?).
    pub truth_3d: bool,
    /// Normalized smallest out-of-plane eigenvalue of the planar state.
    pub lambda_min: f64,
    /// Protocol Ξ₁[ξ_y]/L².
    pub xi_y: f64,
    /// Protocol Ξ₁[ξ_τ].
    pub xi_tau: f64,
}

/// Scores of one decision method against the ground truth.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Score {
    /// Points outside the band that the method classified.
    pub scored: usize,
    /// Of those, points where it matches the master curve.
    pub correct: usize,
    /// Points not classified because a solve did not converge.
    pub unclassified: usize,
}

impl Score {
    /// Percentage correct (NaN if nothing scored).
    pub fn percent(&self) -> f64 {
        100.0 * self.correct as f64 / self.scored as f64
    }
}

/// True if the record's X is at least `BAND` away (relative) from every boundary at its Y.
pub fn outside_band(r: &BendTwistRecord) -> bool {
    [r.x_c1, r.x_c2]
        .into_iter()
        .flatten()
        .all(|xc| (r.x / xc - 1.0).abs() > BAND)
}

fn score(
    records: &[BendTwistRecord],
    scored: &[bool],
    decision: impl Fn(&BendTwistRecord) -> Option<bool>,
) -> Score {
    let mut s = Score::default();
    for (r, &keep) in records.iter().zip(scored) {
        match decision(r) {
            None => s.unclassified += 1,
            Some(d) if keep => {
                s.scored += 1;
                if d == r.truth_3d {
                    s.correct += 1;
                }
            }
            Some(_) => {}
        }
    }
    s
}

/// Scores of every method, and the list of protocol/stability disagreements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BendTwistSummary {
    /// Elements per unit Y of the sweep.
    pub elements_per_turn: f64,
    /// Grid points.
    pub points: usize,
    /// Points outside the ±5 % band.
    pub outside_band: usize,
    /// Stability route.
    pub stability: Score,
    /// Protocol, Ξ₁[ξ_y] threshold.
    pub protocol_y: Score,
    /// Protocol, Ξ₁[ξ_τ] threshold.
    pub protocol_tau: Score,
    /// Protocol, both thresholds.
    pub protocol_combined: Score,
    /// Points where the protocol and the stability route disagree.
    pub disagreements: Vec<Disagreement>,
    /// Points left out of every score because they are out of the master curve's regime or
    /// under-resolved ([`Regime`]).
    pub flagged: Vec<FlaggedPoint>,
}

/// Summarizes a sweep.
pub fn summarize(records: &[BendTwistRecord], elements_per_turn: f64) -> BendTwistSummary {
    // The benchmark's rod is Ω_rod (`BendTwistCase::new`).
    let regimes: Vec<Regime> = records.iter().map(|r| Regime::of(r, &OMEGA_ROD)).collect();
    let scored: Vec<bool> = records
        .iter()
        .zip(&regimes)
        .map(|(r, g)| outside_band(r) && g.trusted())
        .collect();
    let flagged = records
        .iter()
        .zip(&regimes)
        .filter(|(_, g)| !g.trusted())
        .map(|(r, g)| FlaggedPoint {
            x: r.x,
            y: r.y,
            gamma: r.gamma,
            n_elements: r.n_elements,
            axial_strain: g.axial_strain,
            curvature_error: g.curvature_error,
            lambda_min: r.lambda_min.unwrap_or(f64::NAN),
            lambda_floor: g.lambda_floor,
            reasons: g.reasons.join("; "),
        })
        .collect();
    let disagreements = records
        .iter()
        .filter_map(|r| match (r.stability_3d, r.protocol_3d) {
            (Some(s), Some(p)) if s != p => Some(Disagreement {
                x: r.x,
                y: r.y,
                stability_3d: s,
                protocol_3d: p,
                truth_3d: r.truth_3d,
                lambda_min: r.lambda_min.unwrap_or(f64::NAN),
                xi_y: r.xi_y,
                xi_tau: r.xi_tau,
            }),
            _ => None,
        })
        .collect();
    BendTwistSummary {
        elements_per_turn,
        points: records.len(),
        outside_band: records.iter().filter(|r| outside_band(r)).count(),
        flagged,
        stability: score(records, &scored, |r| r.stability_3d),
        protocol_y: score(records, &scored, |r| r.protocol_3d_y),
        protocol_tau: score(records, &scored, |r| r.protocol_3d_tau),
        protocol_combined: score(records, &scored, |r| r.protocol_3d),
        disagreements,
    }
}

/// A grid point that is not scored, and why ([`Regime`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlaggedPoint {
    /// X.
    pub x: f64,
    /// Y.
    pub y: f64,
    /// Γ = (2πXY)³.
    pub gamma: f64,
    /// Elements.
    pub n_elements: usize,
    /// Axial strain at the clamp.
    pub axial_strain: f64,
    /// Relative error of the discrete rest curvature.
    pub curvature_error: f64,
    /// λ_min ρAL⁴/EI at the planar state (NaN if none).
    pub lambda_min: f64,
    /// Lower bound of a physical λ_min ρAL⁴/EI.
    pub lambda_floor: f64,
    /// The reasons, separated by "; ".
    pub reasons: String,
}

/// The acceptance checks on a summary: 100 % at ≥ 100·Y elements, ≥ 97 % below.
pub fn bend_twist_checks(s: &BendTwistSummary) -> Vec<Check> {
    let (target, threshold) = if s.elements_per_turn >= 100.0 {
        ("= 100 %", 100.0)
    } else {
        ("≥ 97 %", 97.0)
    };
    let p = s.stability.percent();
    vec![
        Check {
            benchmark: "bend-twist".into(),
            description: format!(
                "stability decision (inertia) vs master curve, {} of {} grid points outside ±5 % in X and in regime ({} flagged: axial strain, resolution, eigenvalue range), {}·Y elements: % correct",
                s.stability.scored, s.points, s.flagged.len(), s.elements_per_turn
            ),
            measured: p,
            target: target.into(),
            passed: p >= threshold,
        },
        Check {
            benchmark: "bend-twist".into(),
            description: format!(
                "grid points left unclassified because a solve did not converge (of {})",
                s.points
            ),
            measured: s.stability.unclassified as f64,
            target: "= 0".into(),
            passed: s.stability.unclassified == 0,
        },
    ]
}
