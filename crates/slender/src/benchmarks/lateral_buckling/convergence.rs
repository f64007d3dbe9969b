//! The mesh convergence of the lateral-buckling Γ_c: Γ_c from the Hessian inertia at a few
//! aspect ratios on a sequence of meshes (through the store, shared with the grid's Γ_c
//! records), Richardson-extrapolated, against the plate master curve.

use std::path::Path;

use anyhow::{Context as _, Result};
use serde::Serialize;
use slender_validation::lateral_buckling::{critical_gamma, MasterCurve};
use slender_validation::lateral_sweep::sweep::CONVERGENCE_STUDY_TOLERANCE;
use slender_validation::lateral_sweep::{critical_record, CriticalConvergence};
use slender_validation::materials::ShellMaterialSet;
use slender_validation::shell_model::ShellModel;

use super::grid::{critical_key, CriticalKey, CRITICAL_STORE};
use crate::benchmarks::Context;
use crate::output::write_csv;
use crate::plot::{plot_lines, Curve, LineAxes, Scale};

/// The study: Γ_c at every aspect ratio of `widths` on every mesh of `meshes`, bisected to
/// [`CONVERGENCE_STUDY_TOLERANCE`] (far below the differences between meshes).
#[derive(Clone, Debug, PartialEq)]
pub struct ConvergenceStudy {
    /// Aspect ratios w/L.
    pub widths: Vec<f64>,
    /// Elements along the length n_L (three or more give an extrapolation).
    pub meshes: Vec<usize>,
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

/// Γ_c of `material` with `model` for every case of `study` through the store, extrapolated
/// per aspect ratio. `None` if this run computes one shard only.
pub(super) fn records(
    material: ShellMaterialSet,
    model: ShellModel,
    study: &ConvergenceStudy,
    cx: &mut Context,
) -> Result<Option<Vec<CriticalConvergence>>> {
    let widths = &study.widths;
    let mut meshes = study.meshes.clone();
    meshes.sort_unstable();
    meshes.dedup();
    let cases: Vec<(f64, usize)> = meshes
        .iter()
        .flat_map(|&n| widths.iter().map(move |&w| (w, n)))
        .collect();
    let keys: Vec<CriticalKey> = cases
        .iter()
        .map(|&(w, n)| critical_key(material, model, n, w, CONVERGENCE_STUDY_TOLERANCE))
        .collect();
    let Some(records) = cx.cases(CRITICAL_STORE, &keys, |k| {
        Ok(critical_record(
            k.material,
            k.model,
            k.width_ratio,
            k.n_length,
            k.tolerance,
            &k.solver,
        )?)
    })?
    else {
        return Ok(None);
    };
    let mut result = Vec::new();
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
        result.push(CriticalConvergence::new(
            model,
            w,
            meshes.clone(),
            gamma_c,
            master,
        ));
    }
    Ok(Some(result))
}

/// Writes `convergence.csv` and `convergence.{png,svg}` of `material`'s study under `out`.
pub(super) fn write(
    material: ShellMaterialSet,
    result: &[CriticalConvergence],
    out: &Path,
) -> Result<()> {
    let mut rows = Vec::new();
    for c in result {
        let (w, master) = (c.width_ratio, c.master);
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
    for c in result {
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
            "{}, {}: Γ_c from the inertia against the mesh, relative to the master curve",
            material.label,
            result.first().map_or("", |c| c.model.label())
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
    Ok(())
}

/// Prints Γ_c per mesh, the extrapolated value and the master curve.
pub(super) fn print(conv: &[CriticalConvergence]) {
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
