//! The lateral-buckling grid (seed §5): Γ_shell × w/L decided 2-D or 3-D by the seed's
//! protocol, scored against the master curve and compared with the shell's own stability
//! (Γ_c per aspect ratio from the Hessian inertia). Written as CSV and drawn as a decision
//! diagram (Figs. 9b–11b) and a height map of the end point's y-deviation (Figs. 9a–11a).

use std::path::Path;

use anyhow::{Context as _, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::log_space;
use slender_validation::lateral_buckling::{sample_master_curve, MasterCurve};
use slender_validation::lateral_sweep::sweep::{GAMMA_C_BRACKET, SWEEP_TOLERANCE};
use slender_validation::lateral_sweep::vlasov_band;
use slender_validation::lateral_sweep::{
    score_decisions, CriticalRecord, DecisionScore, LateralBucklingRecord, LateralBucklingSweep,
};
use slender_validation::materials::ShellMaterialSet;
use slender_validation::shell_model::ShellModel;

use crate::benchmarks::Context;
use crate::output::write_csv;
use crate::plot::{plot_height_map, plot_phase_diagram, Overlay, Phase, PhasePoint};

/// The store of protocol points (shared with the sensitivity study).
pub(crate) const PROTOCOL_STORE: &str = "lateral-buckling";
/// The store of Γ_c records (shared with the convergence study).
pub(super) const CRITICAL_STORE: &str = "lateral-buckling-critical";

/// What the grid produced.
pub struct GridRecords {
    /// Γ_c per aspect ratio.
    pub critical: Vec<CriticalRecord>,
    /// Protocol points.
    pub records: Vec<LateralBucklingRecord>,
    /// Decisions scored against the master curve, over the whole grid.
    pub score: DecisionScore,
    /// (w/L, Γ_c of the plate master curve) per aspect ratio.
    master: Vec<(f64, f64)>,
}

/// One row of `decisions.csv`: the score of one aspect ratio (w/L = NaN: the whole grid).
#[derive(Serialize)]
struct DecisionRow {
    width_ratio: f64,
    master_gamma_c: f64,
    points: usize,
    correct: usize,
    percent: f64,
    points_outside_band: usize,
    correct_outside_band: usize,
    percent_outside_band: f64,
    not_converged: usize,
}

impl DecisionRow {
    fn new(width_ratio: f64, master_gamma_c: f64, s: &DecisionScore) -> Self {
        Self {
            width_ratio,
            master_gamma_c,
            points: s.points,
            correct: s.correct,
            percent: s.percent(),
            points_outside_band: s.points_outside_band,
            correct_outside_band: s.correct_outside_band,
            percent_outside_band: s.percent_outside_band(),
            not_converged: s.not_converged,
        }
    }
}

/// Everything a Γ_c record depends on: its store key.
#[derive(Serialize)]
pub(super) struct CriticalKey {
    pub(super) material: ShellMaterialSet,
    pub(super) model: ShellModel,
    pub(super) n_length: usize,
    pub(super) width_ratio: f64,
    bracket: (f64, f64),
    /// Relative width of the bisection.
    pub(super) tolerance: f64,
    pub(super) solver: SolverParams,
}

/// Everything a protocol point depends on (not the threshold: it is applied afterwards).
/// Shared with `slender sensitivity`, so the two commands reuse each other's stored points.
#[derive(Serialize)]
pub(crate) struct ProtocolKey {
    pub(crate) material: ShellMaterialSet,
    pub(crate) model: ShellModel,
    pub(crate) n_length: usize,
    pub(crate) width_ratio: f64,
    pub(crate) gamma: f64,
    pub(crate) sigma: f64,
    pub(crate) load_steps: usize,
    pub(crate) solver: SolverParams,
}

/// The grid's Γ_c records and protocol points through the store; `None` if this run
/// computes one shard only.
pub(super) fn records(
    sweep: &LateralBucklingSweep,
    cx: &mut Context,
) -> Result<Option<GridRecords>> {
    let params = slender_validation::lateral_sweep::solver_params();
    params.validate()?;
    let critical_keys: Vec<CriticalKey> = sweep
        .width_ratios
        .iter()
        .map(|&width_ratio| {
            critical_key(
                sweep.material,
                sweep.model,
                sweep.n_length,
                width_ratio,
                SWEEP_TOLERANCE,
            )
        })
        .collect();
    let critical = cx.cases(CRITICAL_STORE, &critical_keys, |k| {
        Ok(sweep.critical_at(k.width_ratio, &k.solver)?)
    })?;
    let points = sweep.points();
    let protocol_keys: Vec<ProtocolKey> = points
        .iter()
        .map(|&(width_ratio, gamma)| ProtocolKey {
            material: sweep.material,
            model: sweep.model,
            n_length: sweep.n_length,
            width_ratio,
            gamma,
            sigma: sweep.sigma,
            load_steps: sweep.load_steps,
            solver: params,
        })
        .collect();
    let protocol = cx.cases(PROTOCOL_STORE, &protocol_keys, |k| {
        Ok(sweep.protocol_at(k.width_ratio, k.gamma, &k.solver)?)
    })?;
    let (Some(critical), Some(protocol)) = (critical, protocol) else {
        return Ok(None);
    };
    let master = sweep.master_critical();
    let records: Vec<LateralBucklingRecord> = points
        .iter()
        .zip(&protocol)
        .map(|(&wg, p)| sweep.record(wg, p, &critical, &master))
        .collect();
    let score = score_decisions(&records);
    Ok(Some(GridRecords {
        critical,
        records,
        score,
        master,
    }))
}

/// Writes `critical.csv`, `results.csv`, `decisions.csv`, `phase_diagram.{png,svg}` and
/// `height_map.{png,svg}` under `out`.
pub(super) fn write(sweep: &LateralBucklingSweep, g: &GridRecords, out: &Path) -> Result<()> {
    let (critical, records, score) = (&g.critical, &g.records, &g.score);
    write_csv(&out.join("critical.csv"), critical)?;
    write_csv(&out.join("results.csv"), records)?;
    let mut rows: Vec<DecisionRow> = g
        .master
        .iter()
        .map(|&(w, gc)| {
            DecisionRow::new(
                w,
                gc,
                &score_decisions(records.iter().filter(|r| r.width_ratio == w)),
            )
        })
        .collect();
    rows.push(DecisionRow::new(f64::NAN, f64::NAN, score));
    write_csv(&out.join("decisions.csv"), &rows)?;
    let curve: Vec<(f64, f64)> = critical
        .iter()
        .filter(|c| c.gamma_c.is_finite())
        .map(|c| (c.width_ratio, c.gamma_c))
        .collect();
    let points: Vec<PhasePoint> = records
        .iter()
        .map(|r| PhasePoint {
            x: r.width_ratio,
            y: r.gamma,
            phase: if !r.tip_deviation.is_finite() {
                Phase::NotConverged
            } else if r.protocol_3d {
                Phase::ThreeD
            } else {
                Phase::TwoD
            },
            disagrees: r.stability_3d.is_some_and(|s| s != r.protocol_3d),
        })
        .collect();
    // The master curves (slender_validation::lateral_buckling, independent of the shell): the
    // Kirchhoff plate's linear buckling load, and the Vlasov beam with the beam and the plate
    // lateral stiffness.
    let nu = sweep.material.poisson;
    let grid = log_space(0.01, 1.0, 40);
    let band: Vec<(f64, (f64, f64))> = grid
        .iter()
        .filter_map(|&w| vlasov_band(nu, w).map(|b| (w, b)))
        .collect();
    let plate = sample_master_curve(MasterCurve::KirchhoffPlate, nu, &grid)?;
    // Ground truth of the background: Γ above the plate master curve, interpolated in log–log
    // between its samples.
    let plate_at = |w: f64| -> Option<f64> { log_interpolate(&plate, w) };
    let truth = |w: f64, g: f64| plate_at(w).map(|gc| g > gc);
    let overlays = vec![
        Overlay {
            label: format!("master curve: Kirchhoff plate (ν = {nu})"),
            points: plate.clone(),
            dashed: false,
            color: Some(plotters::style::RGBColor(200, 30, 30)),
        },
        Overlay {
            label: format!(
                "Γ_c from the Hessian inertia ({}, n_L = {})",
                sweep.model, sweep.n_length
            ),
            points: curve.clone(),
            dashed: false,
            color: None,
        },
        Overlay {
            label: "Vlasov beam, B = E w h³/12".into(),
            points: band.iter().map(|(w, b)| (*w, b.0)).collect(),
            dashed: true,
            color: None,
        },
        Overlay {
            label: "Vlasov beam, B = D w".into(),
            points: band.iter().map(|(w, b)| (*w, b.1)).collect(),
            dashed: true,
            color: None,
        },
    ];
    let lo = |v: &[f64]| v.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = |v: &[f64]| v.iter().cloned().fold(0.0, f64::max);
    let stem = out.join("phase_diagram");
    plot_phase_diagram(
        &stem,
        &format!(
            "Lateral buckling, {}, {} (ν = {}), n_L = {}: protocol σ = {}, m_ls = {}, ε = {}",
            sweep.model.label(),
            sweep.material.label,
            sweep.material.poisson,
            sweep.n_length,
            sweep.sigma,
            sweep.load_steps,
            sweep.threshold
        ),
        "w / L",
        "Γ_shell",
        (lo(&sweep.width_ratios) / 1.2, hi(&sweep.width_ratios) * 1.2),
        (lo(&sweep.gammas) / 1.2, hi(&sweep.gammas) * 1.2),
        &truth,
        &points,
        &overlays,
    )
    .with_context(|| format!("plotting {}", stem.display()))?;
    // Height map of |y_tip|/L (Figs. 9a–11a): the steep descent should follow the master curve.
    let heights: Vec<Vec<f64>> = sweep
        .gammas
        .iter()
        .map(|&g| {
            sweep
                .width_ratios
                .iter()
                .map(|&w| {
                    records
                        .iter()
                        .find(|r| r.width_ratio == w && r.gamma == g)
                        .filter(|r| r.converged)
                        .map_or(f64::NAN, |r| r.tip_deviation.abs())
                })
                .collect()
        })
        .collect();
    let stem = out.join("height_map");
    plot_height_map(
        &stem,
        &format!(
            "{}, {}, n_L = {}: free-end y-deviation after the protocol (σ = {}, m_ls = {})",
            sweep.model.label(),
            sweep.material.label,
            sweep.n_length,
            sweep.sigma,
            sweep.load_steps
        ),
        "w / L",
        "Γ_shell",
        &sweep.width_ratios,
        &sweep.gammas,
        &heights,
        "|y_tip| / L",
        true,
        &overlays[..2],
    )
    .with_context(|| format!("plotting {}", stem.display()))?;
    Ok(())
}

/// Linear interpolation of log y against log x through `curve` (x ascending); None outside.
fn log_interpolate(curve: &[(f64, f64)], x: f64) -> Option<f64> {
    let i = curve.iter().position(|p| p.0 >= x)?;
    if i == 0 {
        return (curve[0].0 == x).then_some(curve[0].1);
    }
    let (a, b) = (curve[i - 1], curve[i]);
    let t = (x.ln() - a.0.ln()) / (b.0.ln() - a.0.ln());
    Some((a.1.ln() + t * (b.1.ln() - a.1.ln())).exp())
}

/// Everything a Γ_c record depends on, as in [`CriticalKey`] (shared store).
pub(super) fn critical_key(
    material: ShellMaterialSet,
    model: ShellModel,
    n_length: usize,
    width_ratio: f64,
    tolerance: f64,
) -> CriticalKey {
    CriticalKey {
        material,
        model,
        n_length,
        width_ratio,
        bracket: GAMMA_C_BRACKET,
        tolerance,
        solver: slender_validation::lateral_sweep::solver_params(),
    }
}

/// Prints Γ_c per aspect ratio and the protocol's agreement with stability.
pub(super) fn print_summary(out: &GridRecords) {
    println!("{:>6} {:>4} {:>4} {:>10}", "w/L", "n_L", "n_W", "Γ_c");
    for c in &out.critical {
        println!(
            "{:>6.3} {:>4} {:>4} {:>10.3}",
            c.width_ratio, c.n_length, c.n_width, c.gamma_c
        );
    }
    let decided: Vec<&LateralBucklingRecord> = out
        .records
        .iter()
        .filter(|r| r.stability_3d.is_some())
        .collect();
    let agree = decided
        .iter()
        .filter(|r| r.stability_3d == Some(r.protocol_3d))
        .count();
    println!(
        "protocol agrees with stability at {agree} of {} points ({:.0} %); {} protocol runs with a stage not converged",
        decided.len(),
        100.0 * agree as f64 / decided.len().max(1) as f64,
        out.records.iter().filter(|r| !r.converged).count()
    );
    let s = &out.score;
    println!(
        "protocol correct vs the plate master curve: {} of {} points ({:.1} %); outside ±{:.0} % of Γ_c: {} of {} ({:.1} %)",
        s.correct,
        s.points,
        s.percent(),
        100.0 * slender_validation::lateral_sweep::UNDECIDABLE_BAND,
        s.correct_outside_band,
        s.points_outside_band,
        s.percent_outside_band()
    );
}
