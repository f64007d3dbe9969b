//! The acceptance targets of the model comparison, per model, measured.

use serde::{Deserialize, Serialize};

use crate::bend_twist::acceptance::outside_band;
use crate::bend_twist::regime::Regime;
use crate::bend_twist::sweep::BendTwistRecord;
use crate::cantilever::Check;
use crate::materials::RodMaterialSet;

use super::cantilever::{ModelConvergence, ModelSummary};
use super::greenhill::GREENHILL;
use super::shear_limit::{coil_tension, shear_tension_limit};

/// One model's bend–twist decisions on a grid, scored against the master curve.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BendTwistModelScore {
    /// Model name.
    pub model: String,
    /// Points outside the ±5 % band.
    pub scored: usize,
    /// Of those, stability decisions matching the master curve.
    pub correct: usize,
    /// Protocol (both thresholds) decisions matching the master curve.
    pub protocol_correct: usize,
    /// Points not classified (a solve did not converge).
    pub unclassified: usize,
    /// Points outside the band left unscored because they are out of the master curve's
    /// regime or under-resolved (`bend_twist::regime::Regime`, as in the bend–twist section).
    pub flagged: usize,
    /// Scored points whose clamp tension exceeds the shear-tension limit of the shearable
    /// models (see `shear_limit.rs`).
    pub beyond_shear_limit: usize,
    /// Wrong stability decisions among those.
    pub wrong_beyond_shear_limit: usize,
}

/// Scores `records` of one model.
pub fn bend_twist_model_score(
    model: &str,
    records: &[BendTwistRecord],
    material: &RodMaterialSet,
) -> BendTwistModelScore {
    let limit = shear_tension_limit(material);
    let mut s = BendTwistModelScore {
        model: model.into(),
        scored: 0,
        correct: 0,
        protocol_correct: 0,
        unclassified: 0,
        flagged: 0,
        beyond_shear_limit: 0,
        wrong_beyond_shear_limit: 0,
    };
    for r in records {
        let Some(d) = r.stability_3d else {
            s.unclassified += 1;
            continue;
        };
        if !outside_band(r) {
            continue;
        }
        if !Regime::of(r, material).trusted() {
            s.flagged += 1;
            continue;
        }
        s.scored += 1;
        let beyond = coil_tension(material, r.gamma) > limit;
        s.beyond_shear_limit += usize::from(beyond);
        if d == r.truth_3d {
            s.correct += 1;
        } else if beyond {
            s.wrong_beyond_shear_limit += 1;
        }
        if r.protocol_3d == Some(r.truth_3d) {
            s.protocol_correct += 1;
        }
    }
    s
}

fn check(description: String, measured: f64, target: &str, passed: bool) -> Check {
    Check {
        benchmark: "models".into(),
        description,
        measured,
        target: target.into(),
        passed: passed && measured.is_finite(),
    }
}

/// The targets for model `model` (its `label` in the descriptions): cantilever accuracy on
/// the graded mesh, order of convergence, Greenhill's threshold, bend–twist decisions.
pub fn model_checks(
    model: &str,
    label: &str,
    summaries: &[ModelSummary],
    orders: &[ModelConvergence],
    greenhill: f64,
    bend_twist: Option<&BendTwistModelScore>,
) -> Vec<Check> {
    let mut out = Vec::new();
    let find = |n: usize| {
        summaries
            .iter()
            .find(|s| s.model == model && s.mesh == "graded" && s.n_elements == n)
    };
    let worst = |s: Option<&ModelSummary>, cable: bool| match s {
        Some(s) if s.not_converged == 0 => {
            if cable {
                s.worst_cable_percent
            } else {
                s.worst_percent
            }
        }
        _ => f64::NAN,
    };
    let w20 = worst(find(20), false);
    out.push(check(
        format!("{label}: cantilever Ω_rod, graded, N = 20, worst |Δy/Δx error| (%) over Γ ∈ [0.1, 10⁴]"),
        w20,
        "≤ 0.5 %",
        w20 <= 0.5,
    ));
    let w5 = worst(find(5), true);
    out.push(check(
        format!("{label}: cantilever Ω_rod, graded, N = 5, worst error (%) over Γ ∈ [10, 10³]"),
        w5,
        "≤ 3 %",
        w5 <= 3.0,
    ));
    for o in orders.iter().filter(|o| o.model == model) {
        out.push(check(
            format!(
                "{label}: order of convergence at Γ = {}, slope of log|error| vs log N (graded, N = 10…80; {:.2} over N = 40…80)",
                o.gamma, o.finest_slope
            ),
            o.slope,
            "≤ −1.8",
            o.slope <= -1.8,
        ));
    }
    let g = 100.0 * (greenhill / GREENHILL - 1.0);
    out.push(check(
        format!("{label}: Greenhill's heavy column by inertia, 40 elements: Γ_c = {greenhill:.4}, error (%) vs 7.8373"),
        g.abs(),
        "≤ 0.5 %",
        g.abs() <= 0.5,
    ));
    if let Some(b) = bend_twist {
        let p = 100.0 * b.correct as f64 / b.scored as f64;
        let note = if b.beyond_shear_limit > 0 {
            format!(
                "; {} of the {} wrong lie beyond the shear-tension limit (clamp tension > κGA/(1 − κGA/EA), {} such points), where the shearable rod is unstable in shear",
                b.wrong_beyond_shear_limit,
                b.scored - b.correct,
                b.beyond_shear_limit
            )
        } else {
            String::new()
        };
        out.push(check(
            format!(
                "{label}: bend–twist grid, stability decisions correct (%) of {} points outside ±5 % and in the master curve's regime ({} flagged){note}",
                b.scored, b.flagged
            ),
            p,
            "= 100 %",
            b.correct == b.scored && b.unclassified == 0,
        ));
    }
    out
}
