//! `slender lateral-buckling`: the seed's §5 — Γ_shell × w/L decided 2-D or 3-D by the
//! protocol and by stability, written as CSV and drawn as a phase diagram.

use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::log_space;
use slender_validation::lateral_buckling::{sample_master_curve, MasterCurve};
use slender_validation::lateral_sweep::sweep::GAMMA_C_BRACKET;
use slender_validation::lateral_sweep::vlasov_band;
use slender_validation::lateral_sweep::{
    CriticalRecord, LateralBucklingRecord, LateralBucklingSweep,
};
use slender_validation::materials::ShellMaterialSet;

use crate::output::write_csv;
use crate::plot::{plot_phase_diagram, Overlay, Phase, PhasePoint};
use crate::store::runner::{run_cases, StoreOptions};
use crate::store::BenchmarkStore;

/// What the benchmark produced.
pub struct LateralBucklingOutput {
    /// Γ_c per aspect ratio.
    pub critical: Vec<CriticalRecord>,
    /// Protocol points.
    pub records: Vec<LateralBucklingRecord>,
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
#[derive(Serialize)]
struct ProtocolKey {
    material: ShellMaterialSet,
    n_length: usize,
    width_ratio: f64,
    gamma: f64,
    sigma: f64,
    load_steps: usize,
    solver: SolverParams,
}

/// Runs `sweep` through the store, writes `critical.csv`, `results.csv` and
/// `phase_diagram.{png,svg}` under `out`; `None` if this run computed one shard only.
pub fn run(
    sweep: &LateralBucklingSweep,
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<LateralBucklingOutput>> {
    let params = SolverParams::default();
    params.validate()?;
    let critical_keys: Vec<CriticalKey> = sweep
        .width_ratios
        .iter()
        .map(|&width_ratio| CriticalKey {
            material: sweep.material,
            n_length: sweep.n_length,
            width_ratio,
            bracket: GAMMA_C_BRACKET,
            solver: params.clone(),
        })
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
    let records: Vec<LateralBucklingRecord> = points
        .iter()
        .zip(&protocol)
        .map(|(&wg, p)| sweep.record(wg, p, &critical))
        .collect();
    write_csv(&out.join("results.csv"), &records)?;

    let curve: Vec<(f64, f64)> = critical
        .iter()
        .filter(|c| c.gamma_c.is_finite())
        .map(|c| (c.width_ratio, c.gamma_c))
        .collect();
    // Stability truth between the computed aspect ratios: Γ_c interpolated in log–log.
    let gamma_c_at = |w: f64| -> Option<f64> {
        let i = curve.iter().position(|p| p.0 >= w)?;
        if i == 0 {
            return (curve[0].0 == w).then_some(curve[0].1);
        }
        let (a, b) = (curve[i - 1], curve[i]);
        let t = (w.ln() - a.0.ln()) / (b.0.ln() - a.0.ln());
        Some((a.1.ln() + t * (b.1.ln() - a.1.ln())).exp())
    };
    let truth = |w: f64, g: f64| gamma_c_at(w).map(|gc| g > gc);
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
    let overlays = vec![
        Overlay {
            label: format!("master curve: Kirchhoff plate (ν = {nu})"),
            points: plate,
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
    Ok(Some(LateralBucklingOutput { critical, records }))
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
}
