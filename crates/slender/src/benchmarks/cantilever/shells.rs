//! The shells of the cantilever benchmark: the strip sets of seed Table 2 through the store,
//! against the master curve, drawn on the same Fig. 2 plot as the rods, plus shape pictures
//! (seed Fig. 4).

use std::path::Path;

use anyhow::{Context as _, Result};
use serde::Serialize;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::master_curve::heavy_elastica;
use slender_validation::cantilever::shell_acceptance::cantilever_grading;
use slender_validation::cantilever::{
    log_space, run_shell_case, CantileverRecord, ShellCantileverCase, ShellCantileverRecord,
    ShellCantileverSweep, CABLE_RANGE,
};
use slender_validation::materials::{ShellMaterialSet, OMEGA_COMBINED, OMEGA_IPS};
use slender_validation::shell_model::ShellModel;

use crate::benchmarks::{words, Context};
use crate::output::write_csv;
use crate::plot::{plot_cantilever_ratio, plot_relative_error, plot_shape_views, Curve, Polyline3};

/// The store of shell cantilever records.
const STORE: &str = "cantilever-shell";

/// Everything a shell cantilever record depends on: the store key.
#[derive(Serialize)]
struct ShellCantileverKey {
    case: ShellCantileverCase,
    solver: SolverParams,
}

/// The records of `cases` (in order) through the store; `None` if this run computes one shard.
pub(super) fn records(
    cases: &[ShellCantileverCase],
    cx: &mut Context,
) -> Result<Option<Vec<ShellCantileverRecord>>> {
    let solver = SolverParams::default();
    solver.validate()?;
    let keys: Vec<ShellCantileverKey> = cases
        .iter()
        .map(|&case| ShellCantileverKey { case, solver })
        .collect();
    cx.cases(STORE, &keys, |k| Ok(run_shell_case(&k.case, &k.solver)?))
}

/// Writes `shell_results.csv`, the per-set ratio and error plots, the combined Fig. 2
/// (`fig2_rod_and_shell`, with the rod `rod_records` of `rod_material` on the graded mesh)
/// and the shape pictures under `out`, and prints the summary.
pub(super) fn write(
    sweep: &ShellCantileverSweep,
    records: &[ShellCantileverRecord],
    rod_records: &[CantileverRecord],
    rod_material: Option<&str>,
    out: &Path,
    cx: &mut Context,
) -> Result<()> {
    write_csv(&out.join("shell_results.csv"), records)?;
    let lo = sweep.gammas.iter().cloned().fold(f64::INFINITY, f64::min);
    let hi = sweep.gammas.iter().cloned().fold(0.0, f64::max);
    let master: Vec<(f64, f64)> = log_space(lo, hi, 200)
        .into_iter()
        .filter_map(|g| heavy_elastica(g).ok().map(|h| (g, h.ratio())))
        .collect();
    let shell_curves = |set: &ShellMaterialSet, error: bool| -> Vec<Curve> {
        sweep
            .models
            .iter()
            .flat_map(|&m| sweep.element_counts.iter().map(move |&n| (m, n)))
            .map(|(model, n)| {
                let rows = records
                    .iter()
                    .filter(|r| r.model == model && r.material == set.name && r.n_length == n);
                Curve {
                    label: format!("{model} shell {}, n_L = {n}", set.label),
                    points: rows
                        .map(|r| (r.gamma, if error { 100.0 * r.rel_error } else { r.ratio }))
                        .collect(),
                    dashed: true,
                    markers: true,
                }
            })
            .collect()
    };
    for set in &sweep.materials {
        // The narrow-strip limit: lateral stiffness E·w·h³/12 = D·w·(1 − ν²), i.e. the master
        // curve at Γ/(1 − ν²) (anticlastic curvature free, design.md §1.1).
        let nu2 = 1.0 - set.poisson * set.poisson;
        let mut curves = vec![Curve {
            label: format!(
                "heavy elastica with E·w·h³/12 (narrow strip, ν = {})",
                set.poisson
            ),
            points: log_space(lo, hi, 100)
                .into_iter()
                .filter_map(|g| heavy_elastica(g / nu2).ok().map(|h| (g, h.ratio())))
                .collect(),
            dashed: true,
            markers: false,
        }];
        curves.extend(shell_curves(set, false));
        let stem = out.join(format!("ratio_shell_{}", set.name));
        plot_cantilever_ratio(
            &stem,
            &format!(
                "Shell cantilever, {} (ν = {}), w/L = {}",
                set.label, set.poisson, sweep.width_ratio
            ),
            &master,
            &curves,
            Some(CABLE_RANGE),
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
        let stem = out.join(format!("error_shell_{}", set.name));
        plot_relative_error(
            &stem,
            &format!(
                "Shell error vs master curve (D·w), {} (ν = {})",
                set.label, set.poisson
            ),
            &shell_curves(set, true),
            Some(CABLE_RANGE),
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
    }
    // The seed's Fig. 2: rods (graded mesh) and the Ω_combined shells on one plot.
    let mut curves = Vec::new();
    if let Some(rod) = rod_material {
        let mut counts: Vec<usize> = rod_records
            .iter()
            .filter(|r| r.material == rod && r.mesh == "graded")
            .map(|r| r.n_elements)
            .collect();
        counts.sort_unstable();
        counts.dedup();
        for n in counts {
            curves.push(Curve {
                label: format!("rod Ω_{rod}, graded, N = {n}"),
                points: rod_records
                    .iter()
                    .filter(|r| r.material == rod && r.mesh == "graded" && r.n_elements == n)
                    .map(|r| (r.gamma, r.ratio))
                    .collect(),
                dashed: false,
                markers: true,
            });
        }
    }
    if let Some(set) = sweep
        .materials
        .iter()
        .find(|s| s.name == OMEGA_COMBINED.name)
        .or(sweep.materials.first())
    {
        curves.extend(shell_curves(set, false));
    }
    let stem = out.join("fig2_rod_and_shell");
    plot_cantilever_ratio(
        &stem,
        "Cantilever under self-weight: rods and shells (seed Fig. 2)",
        &master,
        &curves,
        Some(CABLE_RANGE),
    )
    .with_context(|| format!("plotting {}", stem.display()))?;
    plot_shapes(sweep, out, cx)?;
    print_summary(records);
    Ok(())
}

/// Caption of a figure of the shells' section.
pub(super) fn caption(stem: &str) -> String {
    if stem == "fig2_rod_and_shell" {
        "Counterpart of the seed's Fig. 2: rods (Ω_bundle) and shells of Table 2 along the \
         master curve."
            .into()
    } else if let Some(rest) = stem.strip_prefix("ratio_") {
        format!(
            "Shell Δy/Δx against Γ_shell ({}), with the heavy elastica.",
            words(rest)
        )
    } else if let Some(rest) = stem.strip_prefix("error_") {
        format!("Relative error of the shell's Δy/Δx ({}).", words(rest))
    } else if stem.starts_with("shell_shape") {
        format!(
            "Counterpart of the seed's Fig. 4: shell equilibrium ({}).",
            words(stem)
        )
    } else {
        words(stem)
    }
}

/// The deformed strip as a wire frame (lines along the length and across the width) through
/// the surface points of a run: the mid-edge shell's vertices, the B-spline shell's
/// tessellation (4 × 4 points per element).
fn wire_frame(
    case: &ShellCantileverCase,
    positions: &[slender_core::geometry::Vec3],
) -> Vec<Polyline3> {
    let k = match case.model {
        ShellModel::Midedge => 1,
        ShellModel::Bspline => 4,
    };
    let (nl, nw) = (k * case.n_length, k * case.n_width);
    let at = |i: usize, j: usize| {
        let p = positions[i * (nw + 1) + j];
        [p.x, p.y, p.z]
    };
    let mut lines = Vec::new();
    for j in 0..=nw {
        lines.push(Polyline3 {
            label: if j == 0 {
                format!(
                    "{}, {} × {} elements",
                    case.model, case.n_length, case.n_width
                )
            } else {
                String::new()
            },
            points: (0..=nl).map(|i| at(i, j)).collect(),
            markers: true,
        });
    }
    for i in 0..=nl {
        lines.push(Polyline3 {
            label: String::new(),
            points: (0..=nw).map(|j| at(i, j)).collect(),
            markers: false,
        });
    }
    lines
}

/// Shapes as in the seed's Fig. 4 (an IPS-default strip with fifteen elements; eight for the
/// B-spline shell), at a large Γ where coarse meshes struggle, and the Ω_combined strip, each
/// with the exact centre line.
fn plot_shapes(sweep: &ShellCantileverSweep, out: &Path, cx: &mut Context) -> Result<()> {
    let params = SolverParams::default();
    let shapes = sweep.models.iter().flat_map(|&m| {
        [(OMEGA_IPS, 1e3), (OMEGA_IPS, 1e4), (OMEGA_COMBINED, 61.3)]
            .into_iter()
            .map(move |(set, gamma)| (m, set, gamma))
    });
    for (model, set, gamma) in shapes {
        let n_length = match model {
            ShellModel::Midedge => 15,
            ShellModel::Bspline => 8,
        };
        let case = ShellCantileverCase {
            model,
            material: set,
            width_ratio: sweep.width_ratio,
            n_length,
            n_width: ShellCantileverCase::default_width_elements(
                model,
                sweep.width_ratio,
                n_length,
            ),
            grading: cantilever_grading(model, gamma),
            gamma,
        };
        let run = cx.compute(1, || Ok(case.run(&params)?))?;
        let l = set.length;
        let mut lines = wire_frame(&case, &run.positions);
        if let Ok(exact) = heavy_elastica(gamma) {
            lines.push(Polyline3 {
                label: "heavy elastica centre line (exact)".into(),
                points: exact
                    .shape(200)
                    .iter()
                    .map(|p| [p[0] * l, p[1] * l, 0.0])
                    .collect(),
                markers: false,
            });
        }
        let status = if run.ratio.is_finite() {
            format!("Δy/Δx = {:.4}", run.ratio)
        } else {
            "not converged".into()
        };
        // The mid-edge shell keeps its file names of before the B-spline shell.
        let prefix = match model {
            ShellModel::Midedge => "shell_shape".to_string(),
            ShellModel::Bspline => format!("shell_shape_{model}"),
        };
        let stem = out.join(format!(
            "{prefix}_{}_n{}_gamma{}",
            set.name, n_length, gamma
        ));
        plot_shape_views(
            &stem,
            &format!(
                "Shell cantilever ({}), {}, w/L = {}, Γ = {gamma}: {status}",
                model.label(),
                set.label,
                sweep.width_ratio
            ),
            &lines,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
    }
    Ok(())
}

/// Prints the worst errors per shell discretization against the D·w master curve.
fn print_summary(records: &[ShellCantileverRecord]) {
    println!(
        "{:<8} {:<8} {:>5} {:>4} {:>4}  {:>22}  {:>16}  {:>9}",
        "model", "shell", "ν", "n_L", "n_W", "worst err Γ∈[10,1e3] %", "worst err all %", "unconv."
    );
    let mut keys: Vec<(ShellModel, String, usize)> = records
        .iter()
        .map(|r| (r.model, r.material.clone(), r.n_length))
        .collect();
    keys.dedup();
    for (model, material, n) in keys {
        let rows: Vec<&ShellCantileverRecord> = records
            .iter()
            .filter(|r| r.model == model && r.material == material && r.n_length == n)
            .collect();
        let worst = |lo: f64, hi: f64| {
            rows.iter()
                .filter(|r| r.converged && r.gamma >= lo && r.gamma <= hi)
                .map(|r| 100.0 * r.rel_error.abs())
                .fold(0.0, f64::max)
        };
        println!(
            "{:<8} {:<8} {:>5} {:>4} {:>4}  {:>22.3}  {:>16.3}  {:>9}",
            model.name(),
            material,
            rows[0].poisson,
            n,
            rows[0].n_width,
            worst(CABLE_RANGE.0, CABLE_RANGE.1),
            worst(0.0, f64::INFINITY),
            rows.iter().filter(|r| !r.converged).count()
        );
    }
}
