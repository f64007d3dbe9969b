//! The bend–twist bifurcation (seed §4, Figs. 6–8): the grid's cases through the store,
//! results.csv, height maps of both measures with the master curve, phase diagrams of the
//! stability and protocol decisions, a 3-D picture of a buckled coil, the criticality of the
//! boundaries, and the score against the master curve.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::Path;

use rayon::prelude::*;

use anyhow::{Context as _, Result};
use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;
use slender_validation::bend_twist::acceptance::{bend_twist_checks, summarize, BendTwistSummary};
use slender_validation::bend_twist::case::BendTwistCase;
use slender_validation::bend_twist::criticality::{criticality, Criticality};
use slender_validation::bend_twist::master_curve::{critical_boundaries, StabilityBoundary};
use slender_validation::bend_twist::protocol::ProtocolSettings;
use slender_validation::bend_twist::stability::decide_by_stability_with;
use slender_validation::bend_twist::sweep::{run_point_with, BendTwistRecord, BendTwistSweep};
use slender_validation::cantilever::{log_space, Check};
use slender_validation::rod_model::RodModel;

use super::{is_der, model_suffix, words, Benchmark, Context, Preset, SectionSpec};
use crate::output::{write_atomic, write_csv};
use crate::plot::{
    plot_height_map, plot_phase_diagram, plot_shape_views, Overlay, Phase, PhasePoint, Polyline3,
};

/// Section (and output directory).
const SECTION: &str = "bend-twist";
/// The store of grid points.
const STORE: &str = "bend-twist";
/// The store of criticality rows.
const CRITICALITY_STORE: &str = "bend-twist-criticality";

/// The bend–twist benchmark.
pub struct BendTwist {
    /// The grid.
    pub sweep: BendTwistSweep,
    /// The rod formulation (part of the store keys). The criticality of the boundaries is
    /// measured on the discrete elastic rod only.
    pub model: RodModel,
}

/// What the cases produced.
pub struct BendTwistRecords {
    /// One per grid point, in sweep order.
    records: Vec<BendTwistRecord>,
    /// Scores and disagreements.
    summary: BendTwistSummary,
    /// Both boundaries at each of [`CRITICALITY_ROWS`] (discrete elastic rod only, else
    /// empty).
    criticality: Vec<Criticality>,
}

impl BendTwist {
    /// The grid of `preset`: 12 × 12 at 20·Y elements, or the seed's 25 × 25 at 100·Y.
    pub fn for_preset(preset: Preset) -> Self {
        Self {
            sweep: match preset {
                Preset::Quick => BendTwistSweep::quick(),
                Preset::Full => BendTwistSweep::full(),
            },
            model: RodModel::Der,
        }
    }
}

/// GJ/EI of the benchmark's material (Ω_rod).
fn torsion_ratio(sweep: &BendTwistSweep) -> f64 {
    let case = sweep.cases()[0];
    case.material.properties.stiffness.gj / case.material.properties.stiffness.ei_min()
}

/// Everything a bend–twist record depends on: the store key.
#[derive(Serialize)]
struct BendTwistKey {
    case: BendTwistCase,
    /// Absent for the discrete elastic rod, so that its keys (and stored records) are those
    /// of before the rod models.
    #[serde(skip_serializing_if = "is_der")]
    model: RodModel,
    protocol: ProtocolSettings,
    solver: SolverParams,
}

/// Everything a criticality row depends on: its store key.
#[derive(Serialize)]
struct CriticalityKey {
    y: f64,
    elements_per_turn: f64,
    solver: SolverParams,
}

/// The stored criticality of both boundaries of one row.
#[derive(Serialize, Deserialize)]
struct CriticalityRecord {
    boundaries: Vec<Criticality>,
}

impl Benchmark for BendTwist {
    type Records = BendTwistRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let s = &self.sweep;
        vec![SectionSpec {
            dir: SECTION.into(),
            title: "Bend–twist bifurcation of a naturally curved rod".into(),
            about: format!(
                "A coil clamped at the top, hanging under gravity: 2-D or 3-D over a {}×{} grid \
                 in (X, Y) with {}·Y elements, decided by the seed's protocol and by stability, \
                 against the master curve from the linearized stability ODE.",
                s.xs.len(),
                s.ys.len(),
                s.elements_per_turn
            ),
            caption,
        }]
    }

    fn records(&self, cx: &mut Context) -> Result<Option<BendTwistRecords>> {
        cx.enter(SECTION);
        let sweep = &self.sweep;
        let params = SolverParams::default();
        let records = grid_records(sweep, self.model, cx)?;
        if !is_der(&self.model) {
            return Ok(records.map(|records| BendTwistRecords {
                summary: summarize(&records, sweep.elements_per_turn),
                records,
                criticality: Vec::new(),
            }));
        }
        // Sub- or supercritical: the buckled branch followed toward both boundaries.
        let keys: Vec<CriticalityKey> = CRITICALITY_ROWS
            .iter()
            .map(|&y| CriticalityKey {
                y,
                elements_per_turn: CRITICALITY_ELEMENTS_PER_TURN,
                solver: params,
            })
            .collect();
        let rows = cx.cases(CRITICALITY_STORE, &keys, |k| {
            Ok(CriticalityRecord {
                boundaries: criticality(k.y, k.elements_per_turn, &k.solver)?,
            })
        })?;
        let (Some(records), Some(rows)) = (records, rows) else {
            return Ok(None);
        };
        let summary = summarize(&records, sweep.elements_per_turn);
        Ok(Some(BendTwistRecords {
            records,
            summary,
            criticality: rows.into_iter().flat_map(|r| r.boundaries).collect(),
        }))
    }

    fn write(&self, r: &BendTwistRecords, cx: &mut Context) -> Result<()> {
        cx.enter(SECTION);
        let out = cx.dir(SECTION);
        write_grid(&self.sweep, self.model, &r.records, &r.summary, &out, cx)?;
        if is_der(&self.model) {
            let rows: Vec<CriticalityRow> =
                r.criticality.iter().map(CriticalityRow::from).collect();
            write_csv(&out.join("criticality.csv"), &rows)?;
            print_criticality(&r.criticality);
        }
        print_summary(&r.summary);
        Ok(())
    }

    fn checks(&self, r: &BendTwistRecords, cx: &mut Context) -> Result<Vec<Check>> {
        cx.enter(SECTION);
        Ok(bend_twist_checks(&r.summary))
    }
}

/// The records of the grid `sweep` on the rod `model` (in sweep order) through the store;
/// `None` if this run computes one shard. Shared with the rod-model comparison, which asks for
/// the same keys.
pub(super) fn grid_records(
    sweep: &BendTwistSweep,
    model: RodModel,
    cx: &mut Context,
) -> Result<Option<Vec<BendTwistRecord>>> {
    let params = SolverParams::default();
    params.validate()?;
    let keys: Vec<BendTwistKey> = sweep
        .cases()
        .into_iter()
        .map(|case| BendTwistKey {
            case,
            model,
            protocol: sweep.protocol,
            solver: params,
        })
        .collect();
    // The master curve once per row of the grid; each record carries its row's boundaries.
    let c = torsion_ratio(sweep);
    let boundaries: Vec<StabilityBoundary> = sweep
        .ys
        .par_iter()
        .map(|&y| critical_boundaries(y, c))
        .collect::<Result<_, _>>()?;
    cx.cases(STORE, &keys, |k| {
        let row = sweep
            .ys
            .iter()
            .position(|&y| y == k.case.y)
            .context("grid row of a case")?;
        Ok(run_point_with(
            &k.case,
            k.model,
            &boundaries[row],
            &k.protocol,
            &k.solver,
        )?)
    })
}

/// Writes results.csv, disagreements.csv, summary.json and the figures of the grid's
/// `records` on `model` under `out`.
pub(super) fn write_grid(
    sweep: &BendTwistSweep,
    model: RodModel,
    records: &[BendTwistRecord],
    summary: &BendTwistSummary,
    out: &Path,
    cx: &mut Context,
) -> Result<()> {
    std::fs::create_dir_all(out)?;
    write_csv(&out.join("results.csv"), records)?;
    write_csv(&out.join("disagreements.csv"), &summary.disagreements)?;
    write_csv(&out.join("flagged.csv"), &summary.flagged)?;
    write_atomic(
        &out.join("summary.json"),
        serde_json::to_string_pretty(summary)?.as_bytes(),
    )?;
    plots(sweep, model, records, torsion_ratio(sweep), out, cx)
}

/// Caption of a figure of the section.
pub(super) fn caption(stem: &str) -> String {
    match stem {
        "height_xi_y" => "Counterpart of the seed's Fig. 7: height map of Ξ₁[ξ_y] over (X, Y) \
                          with the master curve."
            .into(),
        "height_xi_tau" => "Counterpart of the seed's Fig. 8a: height map of Ξ₁[ξ_τ] with the \
                            master curve."
            .into(),
        "height_lambda_min" => "Smallest out-of-plane eigenvalue of the planar equilibrium \
                                (negative: unstable, 3-D) with the master curve."
            .into(),
        "phase_protocol" => "Counterpart of the seed's Fig. 8b: 2-D/3-D decisions of the \
                             seed's protocol against the master curve."
            .into(),
        "phase_stability" => "2-D/3-D decided by stability (Hessian inertia) against the \
                              master curve."
            .into(),
        "shape_buckled" => "3-D shape of a buckled coil (branch switched from the unstable \
                            planar state)."
            .into(),
        _ => words(stem),
    }
}

/// Rows of Y at which the criticality of both boundaries is measured.
const CRITICALITY_ROWS: [f64; 2] = [1.5, 3.0];
/// Mesh for the criticality measurement (finer than the quick grid: the boundary offset must
/// stay well below the distances probed).
const CRITICALITY_ELEMENTS_PER_TURN: f64 = 50.0;

/// One line of `criticality.csv`.
#[derive(serde::Serialize)]
struct CriticalityRow {
    y: f64,
    boundary: String,
    x_c: f64,
    kind: String,
    exponent: f64,
    delta_0: f64,
    nonlinearity: f64,
    closest_delta: f64,
    closest_amplitude: f64,
}

impl From<&Criticality> for CriticalityRow {
    fn from(c: &Criticality) -> Self {
        let (d, a) = c.amplitudes.last().copied().unwrap_or((f64::NAN, f64::NAN));
        Self {
            y: c.y,
            boundary: c.boundary.clone(),
            x_c: c.x_c,
            kind: c.kind.clone(),
            exponent: c.exponent,
            delta_0: c.delta_0,
            nonlinearity: c.nonlinearity,
            closest_delta: d,
            closest_amplitude: a,
        }
    }
}

fn print_criticality(cs: &[Criticality]) {
    println!("  criticality (buckled branch continued toward the boundary; A² = k(δ − δ₀)):");
    for c in cs {
        println!(
            "    Y {:5.2} {:<5} X_c {:.5}: {:<13} (A² slopes differ {:.0} %, branch vanishes at δ₀ = {:+.2} %)",
            c.y,
            c.boundary,
            c.x_c,
            c.kind,
            100.0 * c.nonlinearity,
            100.0 * c.delta_0
        );
    }
}

/// Prints the scores and the disagreements.
fn print_summary(s: &BendTwistSummary) {
    println!(
        "bend-twist: {} points ({} outside the ±5 % band), {}·Y elements",
        s.points, s.outside_band, s.elements_per_turn
    );
    for (name, score) in [
        ("stability (inertia)", s.stability),
        ("protocol, Ξ[ξ_y] > ε", s.protocol_y),
        ("protocol, Ξ[ξ_τ] > ε", s.protocol_tau),
        ("protocol, both", s.protocol_combined),
    ] {
        println!(
            "  {name:<22} {:>6.2} % correct ({}/{}), {} unclassified",
            score.percent(),
            score.correct,
            score.scored,
            score.unclassified
        );
    }
    if !s.flagged.is_empty() {
        println!(
            "  {} points not scored (out of regime or under-resolved; flagged.csv), e.g. X {:.4} Y {:.4}: {}",
            s.flagged.len(),
            s.flagged[0].x,
            s.flagged[0].y,
            s.flagged[0].reasons
        );
    }
    if !s.disagreements.is_empty() {
        println!(
            "  protocol and stability disagree at {} points:",
            s.disagreements.len()
        );
        for d in &s.disagreements {
            println!(
                "    X {:7.4} Y {:7.4}: stability {} protocol {} truth {}, λ_min {:+.3e}, Ξ_y {:.2e}, Ξ_τ {:.2e}",
                d.x,
                d.y,
                if d.stability_3d { "3D" } else { "2D" },
                if d.protocol_3d { "3D" } else { "2D" },
                if d.truth_3d { "3D" } else { "2D" },
                d.lambda_min,
                d.xi_y,
                d.xi_tau
            );
        }
    }
}

/// The master curve as two polylines in (X, Y) and the cable corridor X·Y ∈ [0.74, 1.6]
/// (Γ ∈ [10², 10³], design.md §B).
fn overlays(c: f64, y_range: (f64, f64), x_range: (f64, f64)) -> Result<Vec<Overlay>> {
    let mut lower = Vec::new();
    let mut upper = Vec::new();
    let rows: Vec<StabilityBoundary> = log_space(y_range.0, y_range.1, 80)
        .into_par_iter()
        .map(|y| critical_boundaries(y, c))
        .collect::<Result<_, _>>()?;
    for b in rows {
        let y = b.y;
        if let Some(x) = b.lower {
            lower.push((x, y));
        }
        if let Some(x) = b.upper {
            upper.push((x, y));
        }
    }
    let red = plotters::style::RGBColor(200, 30, 30);
    let mut v = vec![
        Overlay {
            label: "master curve: X_c1 (coil loses stability)".into(),
            points: lower,
            dashed: false,
            color: Some(red),
        },
        Overlay {
            label: "master curve: X_c2 (hanging curl restabilizes)".into(),
            points: upper,
            dashed: false,
            color: Some(plotters::style::RGBColor(120, 0, 60)),
        },
    ];
    for (k, xy) in [100.0_f64, 1000.0]
        .iter()
        .map(|g| g.cbrt() / (2.0 * std::f64::consts::PI))
        .enumerate()
    {
        v.push(Overlay {
            label: if k == 0 {
                "cable corridor, Γ ∈ [10², 10³]".into()
            } else {
                String::new()
            },
            points: log_space(x_range.0, x_range.1, 30)
                .into_iter()
                .map(|x| (x, xy / x))
                .filter(|p| p.1 >= y_range.0 && p.1 <= y_range.1)
                .collect(),
            dashed: true,
            color: Some(plotters::style::RGBColor(60, 60, 60)),
        });
    }
    Ok(v)
}

fn plots(
    sweep: &BendTwistSweep,
    model: RodModel,
    records: &[BendTwistRecord],
    c: f64,
    out: &Path,
    cx: &mut Context,
) -> Result<()> {
    let xr = (sweep.xs[0], *sweep.xs.last().expect("non-empty"));
    let yr = (sweep.ys[0], *sweep.ys.last().expect("non-empty"));
    let ov = overlays(c, yr, xr)?;
    let grid = |f: &dyn Fn(&BendTwistRecord) -> f64| -> Vec<Vec<f64>> {
        sweep
            .ys
            .iter()
            .enumerate()
            .map(|(iy, _)| {
                (0..sweep.xs.len())
                    .map(|ix| f(&records[iy * sweep.xs.len() + ix]))
                    .collect()
            })
            .collect()
    };
    let xl = "X = (R/L) Γ^(1/3)";
    let yl = "Y = L / (2πR)";
    for (name, title, label, f) in [
        (
            "height_xi_y",
            "Protocol: integrated y-deviation Ξ₁[ξ_y]",
            "Ξ₁[ξ_y] / L²",
            &(|r: &BendTwistRecord| {
                if r.protocol_converged {
                    r.xi_y
                } else {
                    f64::NAN
                }
            }) as &dyn Fn(&BendTwistRecord) -> f64,
        ),
        (
            "height_xi_tau",
            "Protocol: integrated torsion Ξ₁[ξ_τ]",
            "Ξ₁[ξ_τ] (rad)",
            &|r: &BendTwistRecord| {
                if r.protocol_converged {
                    r.xi_tau
                } else {
                    f64::NAN
                }
            },
        ),
        (
            "height_lambda_min",
            "Stability: smallest out-of-plane eigenvalue of the planar state",
            "λ_min ρA L⁴ / EI",
            &|r: &BendTwistRecord| r.lambda_min.unwrap_or(f64::NAN),
        ),
    ] {
        let stem = out.join(name);
        let log = name != "height_lambda_min";
        plot_height_map(
            &stem,
            &format!("{title}{}", model_suffix(model)),
            xl,
            yl,
            &sweep.xs,
            &sweep.ys,
            &grid(f),
            label,
            log,
            &ov,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
    }
    // The background samples the ground truth on a fine grid whose rows share Y: compute the
    // master curve once per row.
    let cache: RefCell<HashMap<u64, Option<StabilityBoundary>>> = RefCell::new(HashMap::new());
    let truth = |x: f64, y: f64| -> Option<bool> {
        let b = *cache
            .borrow_mut()
            .entry(y.to_bits())
            .or_insert_with(|| critical_boundaries(y, c).ok());
        b.map(|b| matches!((b.lower, b.upper), (Some(l), Some(u)) if x > l && x < u))
    };
    for (name, title, decision) in [
        (
            "phase_stability",
            "Bend–twist phase diagram: stability decision",
            &(|r: &BendTwistRecord| r.stability_3d) as &dyn Fn(&BendTwistRecord) -> Option<bool>,
        ),
        (
            "phase_protocol",
            "Bend–twist phase diagram: seed protocol (both measures)",
            &|r: &BendTwistRecord| r.protocol_3d,
        ),
    ] {
        let points: Vec<PhasePoint> = records
            .iter()
            .map(|r| PhasePoint {
                x: r.x,
                y: r.y,
                phase: match decision(r) {
                    Some(true) => Phase::ThreeD,
                    Some(false) => Phase::TwoD,
                    None => Phase::NotConverged,
                },
                disagrees: matches!((r.stability_3d, r.protocol_3d), (Some(a), Some(b)) if a != b),
            })
            .collect();
        let stem = out.join(name);
        let title = format!("{title}{}", model_suffix(model));
        plot_phase_diagram(&stem, &title, xl, yl, xr, yr, &truth, &points, &ov)
            .with_context(|| format!("plotting {}", stem.display()))?;
    }
    // A buckled coil: the 3-D point with the largest out-of-plane deviation.
    if let Some(r) = records
        .iter()
        .filter(|r| r.stability_3d == Some(true) && r.buckled_xi_y.is_some())
        .max_by(|a, b| {
            a.buckled_xi_y
                .unwrap_or(0.0)
                .total_cmp(&b.buckled_xi_y.unwrap_or(0.0))
        })
    {
        let case = BendTwistCase::new(r.x, r.y, sweep.elements_per_turn);
        let (_, positions) = cx.compute(1, || {
            Ok(decide_by_stability_with(
                &case,
                model,
                &SolverParams::default(),
            )?)
        })?;
        let rest = case.build(Default::default(), Default::default())?;
        let stem = out.join("shape_buckled");
        plot_shape_views(
            &stem,
            &format!(
                "Buckled coil at X = {:.3}, Y = {:.3} (Γ = {:.3e}){}",
                r.x,
                r.y,
                r.gamma,
                model_suffix(model)
            ),
            &[
                Polyline3 {
                    label: "rest coil".into(),
                    points: rest
                        .rest_state()
                        .positions()
                        .iter()
                        .map(|p| [p.x, p.y, p.z])
                        .collect(),
                    markers: false,
                },
                Polyline3 {
                    label: "3-D equilibrium (branch switch)".into(),
                    points: positions.iter().map(|p| [p.x, p.y, p.z]).collect(),
                    markers: false,
                },
            ],
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
    }
    Ok(())
}
