//! `slender cantilever`: the cantilever benchmark (rods, and the shell strips unless
//! `--shell-materials none`) on the grid given by the flags.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use slender_validation::cantilever::{log_space, CantileverSweep, MeshKind, ShellCantileverSweep};
use slender_validation::materials::{ROD_SETS, SHELL_SETS};

use super::{run_benchmark, ModelArg, StoreArgs};
use crate::benchmarks::cantilever::Cantilever;

/// The flags of `slender cantilever`.
#[derive(clap::Args, Debug)]
pub struct CantileverArgs {
    /// Output directory.
    #[arg(long, default_value = "out/cantilever")]
    out: PathBuf,
    /// Rod formulation: der (discrete elastic rod), cosserat (discrete Cosserat rod, CRod-type),
    /// cosserat-tan (the same with the tangent Darboux vector), se3 (SE(3) beam, Odin-type).
    #[arg(long, value_enum, default_value_t = ModelArg::Der)]
    model: ModelArg,
    /// Smallest Γ of the log-spaced sweep (> 0).
    #[arg(long, default_value_t = 0.1)]
    gamma_min: f64,
    /// Largest Γ.
    #[arg(long, default_value_t = 1e4)]
    gamma_max: f64,
    /// Number of Γ values.
    #[arg(long, default_value_t = 40)]
    gamma_count: usize,
    /// Element counts, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![5usize, 10, 20, 50])]
    elements: Vec<usize>,
    /// Mesh families, comma-separated: uniform, quadratic, graded.
    #[arg(long, value_delimiter = ',', default_values_t = vec!["uniform".to_string(), "quadratic".to_string(), "graded".to_string()])]
    meshes: Vec<String>,
    /// Material sets, comma-separated: rod, bundle.
    #[arg(long, value_delimiter = ',', default_values_t = vec!["rod".to_string(), "bundle".to_string()])]
    materials: Vec<String>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
    /// Shell sets (seed Table 2), comma-separated: shell, ips, combined; `none` skips shells.
    #[arg(long, value_delimiter = ',', default_values_t = vec!["shell".to_string(), "ips".to_string(), "combined".to_string()])]
    shell_materials: Vec<String>,
    /// Shell elements along the length n_L, comma-separated (n_W follows from w/L).
    #[arg(long, value_delimiter = ',', default_values_t = vec![8usize, 15, 30])]
    shell_elements: Vec<usize>,
    /// Shell aspect ratio w/L (> 0).
    #[arg(long, default_value_t = 0.1)]
    shell_width_ratio: f64,
    /// Shell models, comma-separated: midedge (triangles, mid-edge directors), bspline (C¹
    /// cubic B-spline patch).
    #[arg(long, value_delimiter = ',', default_values_t = vec!["midedge".to_string(), "bspline".to_string()])]
    shell_model: Vec<String>,
}

/// Runs the benchmark the flags describe.
pub fn run(a: &CantileverArgs) -> Result<bool> {
    let benchmark = Cantilever {
        rods: sweep_from_args(a)?,
        model: a.model.model(),
        shells: shell_sweep_from_args(a)?,
    };
    run_benchmark(&benchmark, &a.out, &a.store, a.jobs)
}

/// The rod sweep of the flags.
fn sweep_from_args(a: &CantileverArgs) -> Result<CantileverSweep> {
    if !(a.gamma_min.is_finite() && a.gamma_min > 0.0) {
        bail!("--gamma-min = {}: must be finite and > 0", a.gamma_min);
    }
    if !(a.gamma_max.is_finite() && a.gamma_max >= a.gamma_min) {
        bail!(
            "--gamma-max = {}: must be finite and >= --gamma-min ({})",
            a.gamma_max,
            a.gamma_min
        );
    }
    if a.gamma_count == 0 {
        bail!("--gamma-count = 0: must be >= 1");
    }
    if let Some(n) = a.elements.iter().find(|&&n| n == 0) {
        bail!("--elements contains {n}: element counts must be >= 1");
    }
    let meshes = a
        .meshes
        .iter()
        .map(|m| {
            MeshKind::from_name(m).with_context(|| {
                format!("--meshes: unknown mesh `{m}`; valid: uniform, quadratic, graded")
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let materials = a
        .materials
        .iter()
        .map(|m| {
            ROD_SETS
                .iter()
                .copied()
                .find(|s| s.name == m)
                .with_context(|| format!("--materials: unknown set `{m}`; valid: rod, bundle"))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(CantileverSweep {
        gammas: log_space(a.gamma_min, a.gamma_max, a.gamma_count),
        element_counts: a.elements.clone(),
        meshes,
        materials,
    })
}

/// The shell sweep of `slender cantilever`, or `None` if shells are skipped.
fn shell_sweep_from_args(a: &CantileverArgs) -> Result<Option<ShellCantileverSweep>> {
    if a.shell_materials.iter().any(|m| m == "none") {
        return Ok(None);
    }
    if !(a.shell_width_ratio.is_finite() && a.shell_width_ratio > 0.0) {
        bail!(
            "--shell-width-ratio = {}: must be finite and > 0",
            a.shell_width_ratio
        );
    }
    if let Some(n) = a.shell_elements.iter().find(|&&n| n == 0) {
        bail!("--shell-elements contains {n}: element counts must be >= 1");
    }
    let materials =
        a.shell_materials
            .iter()
            .map(|m| {
                SHELL_SETS.iter().copied().find(|s| s.name == m).with_context(|| {
                format!("--shell-materials: unknown set `{m}`; valid: shell, ips, combined, none")
            })
            })
            .collect::<Result<Vec<_>>>()?;
    Ok(Some(ShellCantileverSweep {
        models: super::shell_models(&a.shell_model)?,
        gammas: log_space(a.gamma_min, a.gamma_max, a.gamma_count),
        element_counts: a.shell_elements.clone(),
        width_ratio: a.shell_width_ratio,
        materials,
    }))
}
