//! The rods of the cantilever benchmark: the sweep's cases through the store, results.csv,
//! summary.csv, the Fig. 2 counterparts (one per material and mesh family), error plots and
//! deformed shapes.

use std::path::Path;

use anyhow::{Context as _, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::master_curve::heavy_elastica;
use slender_validation::cantilever::{
    log_space, run_case, summarize, CantileverCase, CantileverRecord, CantileverSweep,
    DiscretizationSummary, MeshKind, CABLE_RANGE,
};

use crate::benchmarks::{words, Context};
use crate::output::write_csv;
use crate::plot::{plot_cantilever_ratio, plot_relative_error, plot_shapes_2d, Curve};

/// The store of rod cantilever records.
const STORE: &str = "cantilever";

/// Everything a cantilever record depends on: the store key.
#[derive(Serialize)]
struct CantileverKey {
    case: CantileverCase,
    solver: SolverParams,
}

/// The records of `cases` (in order) through the store; `None` if this run computes one shard.
pub(super) fn records(
    cases: &[CantileverCase],
    cx: &mut Context,
) -> Result<Option<Vec<CantileverRecord>>> {
    let solver = SolverParams::default();
    solver.validate()?;
    let keys: Vec<CantileverKey> = cases
        .iter()
        .map(|&case| CantileverKey {
            case,
            solver: solver.clone(),
        })
        .collect();
    cx.cases(STORE, &keys, |k| Ok(run_case(&k.case, &k.solver)?))
}

/// Writes results.csv, summary.csv and the figures of the sweep's `records` under `out`, and
/// prints the summary.
pub(super) fn write(
    sweep: &CantileverSweep,
    records: &[CantileverRecord],
    out: &Path,
    cx: &mut Context,
) -> Result<()> {
    write_csv(&out.join("results.csv"), records)?;
    let summary = summarize(records);
    write_csv(&out.join("summary.csv"), &summary)?;
    plot_ratios(sweep, records, out)?;
    plot_coarse_shapes(sweep, out, cx)?;
    print_summary(&summary);
    Ok(())
}

/// Caption of a figure of the rods' section.
pub(super) fn caption(stem: &str) -> String {
    if let Some(rest) = stem.strip_prefix("ratio_") {
        format!(
            "Counterpart of the seed's Fig. 2: Δy/Δx against Γ ({}), every element count, \
             with the heavy-elastica master curve computed in code.",
            words(rest)
        )
    } else if let Some(rest) = stem.strip_prefix("error_") {
        format!(
            "Relative error of Δy/Δx against the master curve ({}); the band marks Γ ∈ [10, 10³].",
            words(rest)
        )
    } else if stem.starts_with("shape_") {
        format!(
            "Counterpart of the seed's Figs. 3 and 5: equilibrium shapes on coarse meshes ({}).",
            words(stem)
        )
    } else {
        words(stem)
    }
}

/// Prints the worst errors per discretization.
fn print_summary(summary: &[DiscretizationSummary]) {
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
fn plot_coarse_shapes(sweep: &CantileverSweep, out: &Path, cx: &mut Context) -> Result<()> {
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
                let case = CantileverCase {
                    material: *material,
                    mesh,
                    n_elements: n,
                    gamma,
                };
                let run = cx.compute(1, || Ok(case.run(&params)?))?;
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
