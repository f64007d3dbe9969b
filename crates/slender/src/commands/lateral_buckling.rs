//! `slender lateral-buckling`: the lateral-buckling grid and the Γ_c convergence on the flags'
//! grid and meshes, for each shell model of `--shell-model` (several models: each in
//! `OUT/<model>`, one store).

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use slender_validation::cantilever::log_space;
use slender_validation::lateral_sweep::LateralBucklingSweep;
use slender_validation::materials::SHELL_SETS;

use super::{run_benchmark, shell_models, StoreArgs};
use crate::benchmarks::lateral_buckling::{convergence_meshes, ConvergenceStudy, LateralBuckling};
use crate::benchmarks::Preset;

/// The flags of `slender lateral-buckling`.
#[derive(clap::Args, Debug)]
pub struct LateralBucklingArgs {
    /// Output directory.
    #[arg(long, default_value = "out/lateral-buckling")]
    out: PathBuf,
    /// Shell set (seed Table 2): shell, ips, combined.
    #[arg(long, default_value = "shell")]
    material: String,
    /// Elements along the length n_L (square elements across).
    #[arg(long, default_value_t = 8)]
    elements: usize,
    /// Aspect ratios w/L, comma-separated (each in (0, 1]).
    #[arg(long, value_delimiter = ',', default_values_t = vec![0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0])]
    width_ratios: Vec<f64>,
    /// Smallest Γ_shell of the log-spaced sweep.
    #[arg(long, default_value_t = 8.0)]
    gamma_min: f64,
    /// Largest Γ_shell.
    #[arg(long, default_value_t = 45.0)]
    gamma_max: f64,
    /// Number of Γ_shell values.
    #[arg(long, default_value_t = 15)]
    gamma_count: usize,
    /// Meshes n_L of the Γ_c convergence study (three or more give an extrapolation; default
    /// 8, 15, 30 for the mid-edge shell, 8, 16, 32 for the B-spline shell);
    /// `--convergence-meshes 0` skips it.
    #[arg(long, value_delimiter = ',')]
    convergence_meshes: Option<Vec<usize>>,
    /// Aspect ratios of the Γ_c convergence study.
    #[arg(long, value_delimiter = ',', default_values_t = vec![0.1, 0.5, 1.0])]
    convergence_widths: Vec<f64>,
    /// Clamp rotation σ of the protocol (rad).
    #[arg(long, default_value_t = 0.2)]
    sigma: f64,
    /// Load steps m_ls of the protocol.
    #[arg(long, default_value_t = 5)]
    load_steps: usize,
    /// Decision threshold ε on |y_tip|/L.
    #[arg(long, default_value_t = 1e-4)]
    threshold: f64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
    /// Shell models, comma-separated: midedge (triangles, mid-edge directors), bspline (C¹
    /// cubic B-spline patch).
    #[arg(long, value_delimiter = ',', default_values_t = vec!["midedge".to_string()])]
    shell_model: Vec<String>,
}

/// Runs the benchmark the flags describe, once per shell model.
pub fn run(a: &LateralBucklingArgs) -> Result<bool> {
    let models = shell_models(&a.shell_model)?;
    let grid = lateral_sweep_from_args(a)?;
    // One store for all models, so that a rerun with one of them reuses its cases.
    let store = StoreArgs {
        store: Some(a.store.options(&a.out).root),
        shard: a.store.shard,
    };
    for &model in &models {
        let meshes: Vec<usize> = a
            .convergence_meshes
            .clone()
            .unwrap_or_else(|| convergence_meshes(model, Preset::Quick))
            .into_iter()
            .filter(|&n| n > 0)
            .collect();
        let benchmark = LateralBuckling {
            grid: LateralBucklingSweep {
                model,
                ..grid.clone()
            },
            fine: None,
            convergence: (!meshes.is_empty()).then(|| ConvergenceStudy {
                widths: a.convergence_widths.clone(),
                meshes,
            }),
        };
        let out = if models.len() > 1 {
            a.out.join(model.name())
        } else {
            a.out.clone()
        };
        println!("{}:", model.label());
        run_benchmark(&benchmark, &out, &store, a.jobs)?;
    }
    Ok(true)
}

/// The protocol grid of the flags.
fn lateral_sweep_from_args(a: &LateralBucklingArgs) -> Result<LateralBucklingSweep> {
    let material = SHELL_SETS
        .iter()
        .copied()
        .find(|s| s.name == a.material)
        .with_context(|| {
            format!(
                "--material: unknown set `{}`; valid: shell, ips, combined",
                a.material
            )
        })?;
    if a.elements == 0 {
        bail!("--elements = 0: must be >= 1");
    }
    if let Some(w) = a
        .width_ratios
        .iter()
        .find(|w| !(w.is_finite() && **w > 0.0 && **w <= 1.0))
    {
        bail!("--width-ratios contains {w}: each must be in (0, 1]");
    }
    if let Some(w) = a
        .convergence_widths
        .iter()
        .find(|w| !(w.is_finite() && **w > 0.0 && **w <= 1.0))
    {
        bail!("--convergence-widths contains {w}: each must be in (0, 1]");
    }
    if !(a.gamma_min.is_finite()
        && a.gamma_min > 0.0
        && a.gamma_max.is_finite()
        && a.gamma_max >= a.gamma_min)
    {
        bail!(
            "--gamma-min/--gamma-max = {}/{}: need 0 < min <= max, finite",
            a.gamma_min,
            a.gamma_max
        );
    }
    if a.gamma_count == 0 || a.load_steps == 0 {
        bail!("--gamma-count and --load-steps must be >= 1");
    }
    if !(a.sigma.is_finite() && a.threshold.is_finite() && a.threshold > 0.0) {
        bail!("--sigma must be finite and --threshold finite and > 0");
    }
    Ok(LateralBucklingSweep {
        material,
        model: slender_validation::shell_model::ShellModel::Midedge,
        n_length: a.elements,
        width_ratios: a.width_ratios.clone(),
        gammas: log_space(a.gamma_min, a.gamma_max, a.gamma_count),
        sigma: a.sigma,
        load_steps: a.load_steps,
        threshold: a.threshold,
    })
}
