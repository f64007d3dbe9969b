//! `slender lateral-buckling`: the seed's §5 — Γ_shell × w/L decided 2-D or 3-D by the
//! protocol, scored against the master curve and compared with the shell's own stability;
//! the mesh convergence of Γ_c. Written as CSV and drawn as a decision diagram (Figs. 9b–11b),
//! a height map of the end point's y-deviation (Figs. 9a–11a) and a convergence plot.

use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::log_space;
use slender_validation::lateral_buckling::{critical_gamma, sample_master_curve, MasterCurve};
use slender_validation::lateral_sweep::sweep::GAMMA_C_BRACKET;
use slender_validation::lateral_sweep::vlasov_band;
use slender_validation::lateral_sweep::{
    critical_record, score_decisions, CriticalConvergence, CriticalRecord, DecisionScore,
    LateralBucklingRecord, LateralBucklingSweep,
};
use slender_validation::materials::ShellMaterialSet;

use crate::output::write_csv;
use crate::plot::{
    plot_height_map, plot_lines, plot_phase_diagram, Curve, LineAxes, Overlay, Phase, PhasePoint,
    Scale,
};
use crate::store::runner::{run_cases, StoreOptions};
use crate::store::BenchmarkStore;

/// What the benchmark produced.
pub struct LateralBucklingOutput {
    /// Γ_c per aspect ratio.
    pub critical: Vec<CriticalRecord>,
    /// Protocol points.
    pub records: Vec<LateralBucklingRecord>,
    /// Decisions scored against the master curve, over the whole grid.
    pub score: DecisionScore,
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
struct CriticalKey {
    material: ShellMaterialSet,
    n_length: usize,
    width_ratio: f64,
    bracket: (f64, f64),
    solver: SolverParams,
}

/// Everything a protocol point depends on (not the threshold: it is applied afterwards).
/// Shared with `slender sensitivity`, so the two commands reuse each other's stored points.
#[derive(Serialize)]
pub(crate) struct ProtocolKey {
    pub(crate) material: ShellMaterialSet,
    pub(crate) n_length: usize,
    pub(crate) width_ratio: f64,
    pub(crate) gamma: f64,
    pub(crate) sigma: f64,
    pub(crate) load_steps: usize,
    pub(crate) solver: SolverParams,
}

/// Runs `sweep` through the store, writes `critical.csv`, `results.csv` and
/// `phase_diagram.{png,svg}` under `out`; `None` if this run computed one shard only.
pub fn run(
    sweep: &LateralBucklingSweep,
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<LateralBucklingOutput>> {
    let params = slender_validation::lateral_sweep::solver_params();
    params.validate()?;
    let critical_keys: Vec<CriticalKey> = sweep
        .width_ratios
        .iter()
        .map(|&width_ratio| critical_key(sweep.material, sweep.n_length, width_ratio))
        .collect();
    let critical_run = run_cases(
        &BenchmarkStore::new(&store.root, "lateral-buckling-critical"),
        store.shard,
        &critical_keys,
        |k| Ok(sweep.critical_at(k.width_ratio, &k.solver)?),
    )?;
    let points = sweep.points();
    let protocol_keys: Vec<ProtocolKey> = points
        .iter()
        .map(|&(width_ratio, gamma)| ProtocolKey {
            material: sweep.material,
            n_length: sweep.n_length,
            width_ratio,
            gamma,
            sigma: sweep.sigma,
            load_steps: sweep.load_steps,
            solver: params.clone(),
        })
        .collect();
    let protocol_run = run_cases(
        &BenchmarkStore::new(&store.root, "lateral-buckling"),
        store.shard,
        &protocol_keys,
        |k| Ok(sweep.protocol_at(k.width_ratio, k.gamma, &k.solver)?),
    )?;
    let (Some(critical), Some(protocol)) = (critical_run.complete(), protocol_run.complete())
    else {
        return Ok(None);
    };
    write_csv(&out.join("critical.csv"), &critical)?;
    let master = sweep.master_critical();
    let records: Vec<LateralBucklingRecord> = points
        .iter()
        .zip(&protocol)
        .map(|(&wg, p)| sweep.record(wg, p, &critical, &master))
        .collect();
    write_csv(&out.join("results.csv"), &records)?;
    let score = score_decisions(&records);
    let mut rows: Vec<DecisionRow> = master
        .iter()
        .map(|&(w, gc)| {
            DecisionRow::new(
                w,
                gc,
                &score_decisions(records.iter().filter(|r| r.width_ratio == w)),
            )
        })
        .collect();
    rows.push(DecisionRow::new(f64::NAN, f64::NAN, &score));
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
            label: format!("Γ_c from the Hessian inertia (n_L = {})", sweep.n_length),
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
            "Lateral buckling, {} (ν = {}), n_L = {}: protocol σ = {}, m_ls = {}, ε = {}",
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
            "{}, n_L = {}: free-end y-deviation after the protocol (σ = {}, m_ls = {})",
            sweep.material.label, sweep.n_length, sweep.sigma, sweep.load_steps
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
    Ok(Some(LateralBucklingOutput {
        critical,
        records,
        score,
    }))
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
fn critical_key(material: ShellMaterialSet, n_length: usize, width_ratio: f64) -> CriticalKey {
    CriticalKey {
        material,
        n_length,
        width_ratio,
        bracket: GAMMA_C_BRACKET,
        solver: slender_validation::lateral_sweep::solver_params(),
    }
}

/// One row of `convergence.csv`.
#[derive(Serialize)]
struct ConvergenceRow {
    width_ratio: f64,
    /// Elements along the length; 0 marks the extrapolated value.
    n_length: usize,
    gamma_c: f64,
    master_gamma_c: f64,
    relative_to_master: f64,
}

/// Γ_c of `material` at each of `widths` on each mesh of `meshes` (through the store, shared
/// with the sweep's Γ_c records), extrapolated; writes `convergence.csv` and
/// `convergence.{png,svg}`. `None` if this run computed one shard only.
pub fn run_convergence(
    material: ShellMaterialSet,
    widths: &[f64],
    meshes: &[usize],
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<Vec<CriticalConvergence>>> {
    let mut meshes = meshes.to_vec();
    meshes.sort_unstable();
    meshes.dedup();
    let cases: Vec<(f64, usize)> = meshes
        .iter()
        .flat_map(|&n| widths.iter().map(move |&w| (w, n)))
        .collect();
    let keys: Vec<CriticalKey> = cases
        .iter()
        .map(|&(w, n)| critical_key(material, n, w))
        .collect();
    let run = run_cases(
        &BenchmarkStore::new(&store.root, "lateral-buckling-critical"),
        store.shard,
        &keys,
        |k| {
            Ok(critical_record(
                k.material,
                k.width_ratio,
                k.n_length,
                &k.solver,
            )?)
        },
    )?;
    let Some(records) = run.complete() else {
        return Ok(None);
    };
    let mut result = Vec::new();
    let mut rows = Vec::new();
    for &w in widths {
        let gamma_c: Vec<f64> = meshes
            .iter()
            .map(|&n| {
                records
                    .iter()
                    .find(|r| r.width_ratio == w && r.n_length == n)
                    .map_or(f64::NAN, |r| r.gamma_c)
            })
            .collect();
        let master =
            critical_gamma(w, material.poisson, MasterCurve::KirchhoffPlate).unwrap_or(f64::NAN);
        let c = CriticalConvergence::new(w, meshes.clone(), gamma_c, master);
        for (&n, &g) in c.n_lengths.iter().zip(&c.gamma_c) {
            rows.push(ConvergenceRow {
                width_ratio: w,
                n_length: n,
                gamma_c: g,
                master_gamma_c: master,
                relative_to_master: g / master,
            });
        }
        if let Some(e) = c.extrapolation {
            rows.push(ConvergenceRow {
                width_ratio: w,
                n_length: 0,
                gamma_c: e.value,
                master_gamma_c: master,
                relative_to_master: e.value / master,
            });
        }
        result.push(c);
    }
    write_csv(&out.join("convergence.csv"), &rows)?;
    let mut curves: Vec<Curve> = result
        .iter()
        .map(|c| Curve {
            label: format!("w/L = {}: Γ_c(n_L) / Γ_c(master)", c.width_ratio),
            points: c
                .n_lengths
                .iter()
                .zip(&c.gamma_c)
                .map(|(&n, &g)| (n as f64, g / c.master))
                .collect(),
            dashed: false,
            markers: true,
        })
        .collect();
    for c in &result {
        if let Some(e) = c.extrapolation {
            let last = *c.n_lengths.last().expect("three meshes") as f64;
            curves.push(Curve {
                label: format!(
                    "w/L = {}: extrapolated Γ_∞ / Γ_c(master) = {:.4}",
                    c.width_ratio,
                    e.value / c.master
                ),
                points: vec![
                    (c.n_lengths[0] as f64, e.value / c.master),
                    (last, e.value / c.master),
                ],
                dashed: true,
                markers: false,
            });
        }
    }
    let stem = out.join("convergence");
    plot_lines(
        &stem,
        &format!(
            "{}: Γ_c from the inertia against the mesh, relative to the master curve",
            material.label
        ),
        LineAxes {
            x_desc: "elements along the length n_L",
            y_desc: "Γ_c / Γ_c(master)",
            x_scale: Scale::Log,
            y_scale: Scale::Linear,
        },
        &curves,
    )
    .with_context(|| format!("plotting {}", stem.display()))?;
    Ok(Some(result))
}

/// Prints Γ_c per mesh, the extrapolated value and the master curve.
pub fn print_convergence(conv: &[CriticalConvergence]) {
    for c in conv {
        let per_mesh: Vec<String> = c
            .n_lengths
            .iter()
            .zip(&c.gamma_c)
            .map(|(n, g)| format!("n_L {n}: {g:.3}"))
            .collect();
        println!(
            "w/L = {}: Γ_c {}; extrapolated {}; master curve {:.3}",
            c.width_ratio,
            per_mesh.join(", "),
            c.extrapolation.map_or("—".into(), |e| format!(
                "{:.3} (p = {:.2}{})",
                e.value,
                e.order,
                if e.assumed_order { ", assumed" } else { "" }
            )),
            c.master
        );
    }
}

/// Prints Γ_c per aspect ratio and the protocol's agreement with stability.
pub fn print_summary(out: &LateralBucklingOutput) {
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
