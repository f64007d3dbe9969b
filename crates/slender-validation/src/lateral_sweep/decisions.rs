//! Scoring the 2-D/3-D decisions of the lateral-buckling protocol against the master curve
//! (the in-code buckling load of the clamped Kirchhoff plate, independent of the shell).

use serde::{Deserialize, Serialize};

use super::sweep::LateralBucklingRecord;

/// Relative half-width of the band around the master curve whose points are scored apart:
/// the converged shell's Γ_c itself may differ from the plate master curve by up to 3 %
/// (the acceptance tolerance of the Γ_c convergence check), so inside the band no verdict can
/// be called wrong with confidence. Points inside it are still listed and scored in the
/// "all points" figure.
pub const UNDECIDABLE_BAND: f64 = 0.03;

/// How many decisions were right, overall and per aspect ratio.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DecisionScore {
    /// Points with a master-curve verdict.
    pub points: usize,
    /// Of those, decided correctly (converged, and the protocol's verdict equals the truth).
    pub correct: usize,
    /// Points outside the band |Γ/Γ_c − 1| ≤ [`UNDECIDABLE_BAND`].
    pub points_outside_band: usize,
    /// Of those, decided correctly.
    pub correct_outside_band: usize,
    /// Protocol runs with a stage that did not converge (counted as incorrect).
    pub not_converged: usize,
}

impl DecisionScore {
    /// Percentage correct over all points (NaN if there are none).
    pub fn percent(&self) -> f64 {
        percent(self.correct, self.points)
    }

    /// Percentage correct outside the band around the master curve (NaN if none).
    pub fn percent_outside_band(&self) -> f64 {
        percent(self.correct_outside_band, self.points_outside_band)
    }
}

fn percent(k: usize, n: usize) -> f64 {
    if n == 0 {
        f64::NAN
    } else {
        100.0 * k as f64 / n as f64
    }
}

/// Whether one record's protocol verdict is right: `None` without a master-curve verdict; a
/// run that did not converge is never right (its verdict is not a decision).
pub fn is_correct(r: &LateralBucklingRecord) -> Option<bool> {
    r.truth_3d
        .map(|truth| r.converged && r.tip_deviation.is_finite() && r.protocol_3d == truth)
}

/// Scores `records` (all of them; filter beforehand to score a subset, e.g. one w/L).
pub fn score_decisions<'a>(
    records: impl IntoIterator<Item = &'a LateralBucklingRecord>,
) -> DecisionScore {
    let mut s = DecisionScore::default();
    for r in records {
        s.not_converged += usize::from(!r.converged);
        let Some(ok) = is_correct(r) else { continue };
        s.points += 1;
        s.correct += usize::from(ok);
        if (r.gamma / r.master_gamma_c - 1.0).abs() > UNDECIDABLE_BAND {
            s.points_outside_band += 1;
            s.correct_outside_band += usize::from(ok);
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(gamma: f64, tip: f64, converged: bool) -> LateralBucklingRecord {
        let master = 20.0;
        LateralBucklingRecord {
            width_ratio: 0.5,
            gamma,
            tip_deviation: tip,
            protocol_3d: tip.abs() > 1e-4,
            stability_3d: None,
            master_gamma_c: master,
            truth_3d: Some(gamma > master),
            correct: None,
            converged,
            relative_residual: 0.0,
        }
    }

    #[test]
    fn counts_right_wrong_unconverged_and_the_band() {
        let records = [
            record(10.0, 1e-12, true),  // 2-D, right
            record(30.0, 0.2, true),    // 3-D, right
            record(30.0, 1e-9, true),   // 2-D below a 3-D truth: wrong
            record(20.2, 0.1, true),    // inside the band, right (3-D above Γ_c)
            record(20.3, 1e-9, true),   // inside the band, wrong (2-D above Γ_c)
            record(10.0, 1e-12, false), // not converged: wrong
        ];
        let s = score_decisions(&records);
        assert_eq!(s.points, 6);
        assert_eq!(s.correct, 3);
        assert_eq!(s.points_outside_band, 4);
        assert_eq!(s.correct_outside_band, 2);
        assert_eq!(s.not_converged, 1);
        assert!((s.percent() - 50.0).abs() < 1e-12);
        assert!((s.percent_outside_band() - 50.0).abs() < 1e-12);
    }

    #[test]
    fn no_truth_no_score() {
        let mut r = record(10.0, 0.0, true);
        r.truth_3d = None;
        let s = score_decisions([&r]);
        assert_eq!(s.points, 0);
        assert!(s.percent().is_nan());
    }
}
