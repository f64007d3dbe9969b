//! `slender cantilever`: runs the sweep and writes results.csv, summary.csv, the Fig. 2
//! counterparts (one per material and mesh family), error plots and deformed shapes.

use std::path::Path;

use anyhow::{Context, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::master_curve::heavy_elastica;
use slender_validation::cantilever::{
    log_space, run_case_with, summarize, CantileverCase, CantileverRecord, CantileverSweep,
    DiscretizationSummary, MeshKind, CABLE_RANGE,
};

use slender_validation::rod_model::RodModel;

use crate::output::write_csv;
use crate::plot::{plot_cantilever_ratio, plot_relative_error, plot_shapes_2d, Curve};
use crate::store::runner::RunStats;
use crate::store::runner::{run_cases, StoreOptions};
use crate::store::BenchmarkStore;

/// What the cantilever benchmark produced.
pub struct CantileverOutput {
    /// One record per case.
    pub records: Vec<CantileverRecord>,
    /// Worst errors per discretization.
    pub summary: Vec<DiscretizationSummary>,
    /// Cases computed, reused and their compute time.
    pub stats: RunStats,
}

/// Everything a cantilever record depends on: the store key.
#[derive(Serialize)]
struct CantileverKey {
    case: CantileverCase,
    /// Absent for the discrete elastic rod, so that its keys are those of before the models.
    #[serde(skip_serializing_if = "is_der")]
    model: RodModel,
    solver: SolverParams,
}

/// Runs `sweep` through the store and writes everything under `out`; `None` if this run
/// computed one shard only (no report).
pub fn run(
    sweep: &CantileverSweep,
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<CantileverOutput>> {
    run_model(sweep, RodModel::Der, out, store)
}

fn is_der(m: &RodModel) -> bool {
    *m == RodModel::Der
}

/// As [`run`] with the rod formulation `model`.
pub fn run_model(
    sweep: &CantileverSweep,
    model: RodModel,
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<CantileverOutput>> {
    let solver = SolverParams::default();
    sweep.validate()?;
    solver.validate()?;
    let keys: Vec<CantileverKey> = sweep
        .cases()
        .into_iter()
        .map(|case| CantileverKey {
            case,
            model,
            solver: solver.clone(),
        })
        .collect();
    let bench = BenchmarkStore::new(&store.root, "cantilever");
    let run = run_cases(&bench, store.shard, &keys, |k| {
        Ok(run_case_with(&k.case, k.model, &k.solver)?)
    })?;
    let stats = RunStats::of(&run);
    let Some(records) = run.complete() else {
        return Ok(None);
    };
    write_csv(&out.join("results.csv"), &records)?;
    let summary = summarize(&records);
    write_csv(&out.join("summary.csv"), &summary)?;
    plot_ratios(sweep, &records, out)?;
    plot_coarse_shapes(sweep, model, out)?;
    Ok(Some(CantileverOutput {
        records,
        summary,
        stats,
    }))
}

/// Prints the worst errors per discretization.
pub fn print_summary(summary: &[DiscretizationSummary]) {
    println!(
        "{:<8} {:<10} {:>4}  {:>22}  {:>16}  {:>9}",
        "material", "mesh", "N", "worst err Γ∈[10,1e3] %", "worst err all %", "unconv."
    );
    for s in summary {
        println!(
            "{:<8} {:<10} {:>4}  {:>22.3}  {:>16.3}  {:>9}",
            s.material,
            s.mesh,
            s.n_elements,
            100.0 * s.worst_in_cable_range,
            100.0 * s.worst_overall,
            s.not_converged
        );
    }
}

fn plot_ratios(sweep: &CantileverSweep, records: &[CantileverRecord], out: &Path) -> Result<()> {
    let lo = sweep.gammas.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = sweep.gammas.iter().cloned().fold(0.0, f64::max);
    // The master curve drawn densely, independent of the sweep's Γ grid.
    let master: Vec<(f64, f64)> = log_space(lo, hi, 200)
        .into_iter()
        .filter_map(|g| heavy_elastica(g).ok().map(|h| (g, h.ratio())))
        .collect();
    for material in &sweep.materials {
        for &mesh in &sweep.meshes {
            let mut ratio_curves = Vec::new();
            let mut error_curves = Vec::new();
            for &n in &sweep.element_counts {
                let rows: Vec<&CantileverRecord> = records
                    .iter()
                    .filter(|r| {
                        r.material == material.name && r.mesh == mesh.name() && r.n_elements == n
                    })
                    .collect();
                ratio_curves.push(Curve {
                    label: format!("{n} elements"),
                    points: rows.iter().map(|r| (r.gamma, r.ratio)).collect(),
                    dashed: false,
                    markers: true,
                });
                error_curves.push(Curve {
                    label: format!("{n} elements"),
                    points: rows
                        .iter()
                        .map(|r| (r.gamma, 100.0 * r.rel_error))
                        .collect(),
                    dashed: false,
                    markers: true,
                });
            }
            let stem = out.join(format!("ratio_{}_{}", material.name, mesh.name()));
            plot_cantilever_ratio(
                &stem,
                &format!("Cantilever, {} — {} mesh", material.label, mesh.name()),
                &master,
                &ratio_curves,
                Some(CABLE_RANGE),
            )
            .with_context(|| format!("plotting {}", stem.display()))?;
            let stem = out.join(format!("error_{}_{}", material.name, mesh.name()));
            plot_relative_error(
                &stem,
                &format!(
                    "Error vs master curve, {} — {} mesh",
                    material.label,
                    mesh.name()
                ),
                &error_curves,
                Some(CABLE_RANGE),
            )
            .with_context(|| format!("plotting {}", stem.display()))?;
        }
    }
    Ok(())
}

/// Deformed shapes at Γ = 10⁴ on the coarsest meshes (the seed's Figs. 3 and 5), with the
/// exact heavy elastica.
fn plot_coarse_shapes(sweep: &CantileverSweep, model: RodModel, out: &Path) -> Result<()> {
    let gamma = 1e4;
    let exact = heavy_elastica(gamma)?;
    let reference = Curve {
        label: "heavy elastica (exact)".into(),
        points: exact.shape(400).iter().map(|p| (p[0], p[1])).collect(),
        dashed: true,
        markers: false,
    };
    let mut counts = sweep.element_counts.clone();
    counts.sort_unstable();
    counts.truncate(2);
    let params = SolverParams::default();
    for material in sweep.materials.iter().take(1) {
        for &n in &counts {
            let mut shapes = Vec::new();
            for mesh in MeshKind::ALL {
                let run = CantileverCase {
                    material: *material,
                    mesh,
                    n_elements: n,
                    gamma,
                }
                .run_with(model, &params)?;
                let l = material.length;
                shapes.push(Curve {
                    label: format!(
                        "{} mesh, Δy/Δx {}",
                        mesh.name(),
                        if run.ratio.is_finite() {
                            format!("{:+.1} %", 100.0 * (run.ratio / exact.ratio() - 1.0))
                        } else {
                            "not converged".into()
                        }
                    ),
                    points: run.positions.iter().map(|p| (p.x / l, p.y / l)).collect(),
                    dashed: false,
                    markers: true,
                });
            }
            let stem = out.join(format!("shape_gamma1e4_{}_n{}", material.name, n));
            plot_shapes_2d(
                &stem,
                &format!("Γ = 10⁴, {n} elements, {}", material.label),
                "x / L",
                "y / L",
                Some(&reference),
                &shapes,
            )
            .with_context(|| format!("plotting {}", stem.display()))?;
            // The boundary layer (width ≈ L/√Γ = 0.01 L) is invisible at full scale: zoom in.
            let zoom = |c: &Curve| Curve {
                points: clip_to_clamp(&c.points, 0.04),
                ..c.clone()
            };
            let stem = out.join(format!("shape_gamma1e4_{}_n{}_clamp", material.name, n));
            plot_shapes_2d(
                &stem,
                &format!(
                    "Γ = 10⁴, {n} elements, {}: the clamp region",
                    material.label
                ),
                "x / L",
                "y / L",
                Some(&zoom(&reference)),
                &shapes.iter().map(zoom).collect::<Vec<_>>(),
            )
            .with_context(|| format!("plotting {}", stem.display()))?;
        }
    }
    Ok(())
}

/// The leading part of a hanging shape down to depth `depth` (units of L); the segment that
/// crosses y = −depth is cut there by linear interpolation.
fn clip_to_clamp(points: &[(f64, f64)], depth: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    for &p in points {
        if p.1 < -depth {
            if let Some(&q) = out.last() {
                let t = (-depth - q.1) / (p.1 - q.1);
                out.push((q.0 + t * (p.0 - q.0), -depth));
            }
            break;
        }
        out.push(p);
    }
    out
}
