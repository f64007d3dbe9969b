//! `slender`: physically validated equilibria of slender elastic structures.
//!
//! Subcommands run the seed's benchmarks and write data files, plots and a pass/fail summary.

mod bend_twist_report;
mod cantilever_report;
mod lateral_buckling_curves_report;
mod lateral_sweep_report;
mod model_comparison_report;
mod output;
#[allow(dead_code)]
mod plot;
mod progress;
mod report_html;
mod sensitivity_report;
mod shell_cantilever_report;
mod solve;
mod store;
mod validate;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand, ValueEnum};
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::ShellCantileverSweep;
use slender_validation::cantilever::{log_space, CantileverSweep, MeshKind};
use slender_validation::materials::{ROD_SETS, SHELL_SETS};
use slender_validation::rod_model::RodModel;
use store::runner::StoreOptions;
use store::shard::Shard;

/// Large deformations of cables, hoses and flat cables, with the validation to prove them.
#[derive(Parser, Debug)]
#[command(name = "slender", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// The cantilever benchmark (seed §3, Fig. 2): Δy/Δx against Γ, every discretization
    /// against the heavy-elastica master curve.
    Cantilever(CantileverArgs),
    /// The bend–twist bifurcation benchmark (seed §4, Figs. 6–8): 2-D or 3-D over a grid in
    /// (X, Y), decided by the seed's protocol and by stability, against the master curve.
    BendTwist(BendTwistArgs),
    /// The rod models side by side (seed §2, Fig. 5): the cantilever, its order of convergence,
    /// Greenhill's column and the bend–twist quick grid on the discrete elastic rod, the
    /// discrete Cosserat rod and the SE(3) beam (the `models` section of `slender validate`).
    Models(ModelsArgs),
    /// Run every benchmark and write the validation report OUT/index.html with a pass/fail
    /// table of the acceptance targets (exit code 1 if a target fails).
    Validate(ValidateArgs),
    /// Combine result stores (e.g. of `--shard` runs) into one.
    Merge(MergeArgs),
    /// Equilibria of a scene file (TOML or JSON): shapes (VTK, glTF, PNG), frames, strains,
    /// reactions and solver reports (JSON, CSV); prescribed support motion in steps.
    Solve(solve::SolveArgs),
    /// Print (or write with --out) the JSON Schema of the scene format.
    SceneSchema(SceneSchemaArgs),
    /// The lateral-buckling benchmark (seed §5): a heavy strip with its width along gravity,
    /// 2-D or 3-D over (w/L, Γ_shell) by the seed's protocol and by stability.
    LateralBuckling(LateralBucklingArgs),
    /// The sensitivity study of the lateral-buckling protocol (seed §5.3, Fig. 12): the
    /// percentage of correct 2-D/3-D decisions against the plate master curve, for every
    /// combination of Ω, n_L, m_ls and σ, as box plots.
    Sensitivity(sensitivity_report::SensitivityArgs),
}

#[derive(clap::Args, Debug)]
struct MergeArgs {
    /// Destination store (created if missing).
    #[arg(long)]
    into: PathBuf,
    /// Source stores.
    #[arg(required = true)]
    sources: Vec<PathBuf>,
}

/// Where a sweep keeps its finished cases, and which shard of it this run computes.
#[derive(clap::Args, Debug)]
struct StoreArgs {
    /// Result store (default: OUT/store). Finished cases found there are not recomputed.
    #[arg(long)]
    store: Option<PathBuf>,
    /// Compute only shard i of n (e.g. 0/4) into the store and write no report; combine the
    /// shards with `slender merge`, then rerun without --shard to write the report.
    #[arg(long)]
    shard: Option<Shard>,
}

/// Store root and shard of a run writing to `out`.
fn store_options(out: &std::path::Path, args: &StoreArgs) -> StoreOptions {
    StoreOptions {
        root: args.store.clone().unwrap_or_else(|| out.join("store")),
        shard: args.shard,
    }
}

#[derive(clap::Args, Debug)]
struct SceneSchemaArgs {
    /// Write the schema to this file instead of printing it.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// The rod formulations on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum ModelArg {
    /// Discrete elastic rod (Kirchhoff).
    Der,
    /// Discrete Cosserat rod (CRod-type, sine Darboux vector).
    Cosserat,
    /// Discrete Cosserat rod with the tangent Darboux vector.
    CosseratTan,
    /// SE(3) beam (Odin-type).
    Se3,
}

impl ModelArg {
    fn model(self) -> RodModel {
        match self {
            Self::Der => RodModel::Der,
            Self::Cosserat => RodModel::Cosserat,
            Self::CosseratTan => RodModel::CosseratTangent,
            Self::Se3 => RodModel::Se3,
        }
    }
}

#[derive(clap::Args, Debug)]
struct ModelsArgs {
    /// Output directory.
    #[arg(long, default_value = "out/models")]
    out: PathBuf,
    /// Worker threads (default: all cores). Results other than times do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
}

#[derive(clap::Args, Debug)]
struct BendTwistArgs {
    /// Output directory.
    #[arg(long, default_value = "out/bend-twist")]
    out: PathBuf,
    /// Rod formulation: der (discrete elastic rod), cosserat (discrete Cosserat rod, CRod-type),
    /// cosserat-tan (the same with the tangent Darboux vector), se3 (SE(3) beam, Odin-type).
    #[arg(long, value_enum, default_value_t = ModelArg::Der)]
    model: ModelArg,
    /// Grid and resolution: quick (12 × 12, 20·Y elements) or full (25 × 25, 100·Y, the seed's).
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    preset: Preset,
    /// Number of X values (overrides the preset), log-spaced in [0.1, 10].
    #[arg(long)]
    points_x: Option<usize>,
    /// Number of Y values (overrides the preset), log-spaced in [0.1, 10].
    #[arg(long)]
    points_y: Option<usize>,
    /// Elements per unit Y (overrides the preset).
    #[arg(long)]
    elements_per_turn: Option<f64>,
    /// Protocol threshold on Ξ₁[ξ_y]/L².
    #[arg(long)]
    threshold_y: Option<f64>,
    /// Protocol threshold on Ξ₁[ξ_τ] (rad).
    #[arg(long)]
    threshold_tau: Option<f64>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
}

fn bend_twist_sweep(a: &BendTwistArgs) -> Result<BendTwistSweep> {
    let mut s = match a.preset {
        Preset::Quick => BendTwistSweep::quick(),
        Preset::Full => BendTwistSweep::full(),
    };
    if let Some(n) = a.points_x {
        if n == 0 {
            bail!("--points-x = 0: must be >= 1");
        }
        s.xs = log_space(0.1, 10.0, n);
    }
    if let Some(n) = a.points_y {
        if n == 0 {
            bail!("--points-y = 0: must be >= 1");
        }
        s.ys = log_space(0.1, 10.0, n);
    }
    if let Some(k) = a.elements_per_turn {
        if !(k.is_finite() && k > 0.0) {
            bail!("--elements-per-turn = {k}: must be finite and > 0");
        }
        s.elements_per_turn = k;
    }
    if let Some(t) = a.threshold_y {
        if !(t.is_finite() && t >= 0.0) {
            bail!("--threshold-y = {t}: must be finite and >= 0");
        }
        s.protocol.threshold_y = t;
    }
    if let Some(t) = a.threshold_tau {
        if !(t.is_finite() && t >= 0.0) {
            bail!("--threshold-tau = {t}: must be finite and >= 0");
        }
        s.protocol.threshold_tau = t;
    }
    Ok(s)
}

#[derive(clap::Args, Debug)]
struct CantileverArgs {
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
        gammas: log_space(a.gamma_min, a.gamma_max, a.gamma_count),
        element_counts: a.shell_elements.clone(),
        width_ratio: a.shell_width_ratio,
        materials,
    }))
}

#[derive(clap::Args, Debug)]
struct LateralBucklingArgs {
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
    /// Meshes n_L of the Γ_c convergence study (three or more give an extrapolation);
    /// `--convergence-meshes 0` skips it.
    #[arg(long, value_delimiter = ',', default_values_t = vec![8, 15, 30])]
    convergence_meshes: Vec<usize>,
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
}

fn lateral_sweep_from_args(
    a: &LateralBucklingArgs,
) -> Result<slender_validation::lateral_sweep::LateralBucklingSweep> {
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
    Ok(slender_validation::lateral_sweep::LateralBucklingSweep {
        material,
        n_length: a.elements,
        width_ratios: a.width_ratios.clone(),
        gammas: log_space(a.gamma_min, a.gamma_max, a.gamma_count),
        sigma: a.sigma,
        load_steps: a.load_steps,
        threshold: a.threshold,
    })
}

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
enum Preset {
    /// What CI runs.
    Quick,
    /// The paper-size sweeps.
    Full,
}

#[derive(clap::Args, Debug)]
struct ValidateArgs {
    /// Output directory.
    #[arg(long, default_value = "out/validate")]
    out: PathBuf,
    /// Sweep size.
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    preset: Preset,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
}

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

fn thread_pool(jobs: Option<usize>) -> Result<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(j) = jobs {
        if j == 0 {
            bail!("--jobs = 0: must be >= 1");
        }
        b = b.num_threads(j);
    }
    b.build().context("starting the worker threads")
}

fn run(cli: Cli) -> Result<bool> {
    match cli.command {
        Command::Cantilever(a) => {
            let sweep = sweep_from_args(&a)?;
            let shells = shell_sweep_from_args(&a)?;
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            let model = a.model.model();
            match pool.install(|| cantilever_report::run_model(&sweep, model, &a.out, &store))? {
                Some(out) => {
                    cantilever_report::print_summary(&out.summary);
                    if let Some(shells) = shells {
                        // Fig. 2 of the seed pairs the measured bundle with the Ω_combined shells.
                        let rod = ["bundle", "rod"]
                            .into_iter()
                            .find(|m| sweep.materials.iter().any(|s| s.name == *m));
                        let records = pool.install(|| {
                            shell_cantilever_report::run(&shells, &out.records, rod, &a.out)
                        })?;
                        shell_cantilever_report::print_summary(&records);
                    }
                    println!("wrote {}", a.out.display());
                }
                None => print_shard_done(&store),
            }
            Ok(true)
        }
        Command::BendTwist(a) => {
            let sweep = bend_twist_sweep(&a)?;
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            let model = a.model.model();
            match pool.install(|| bend_twist_report::run_model(&sweep, model, &a.out, &store))? {
                Some(out) => {
                    bend_twist_report::print_summary(&out.summary);
                    println!("wrote {}", a.out.display());
                }
                None => print_shard_done(&store),
            }
            Ok(true)
        }
        Command::Solve(a) => {
            let ok = solve::run(&a)?;
            solve::print_summary(&a.out)?;
            println!("wrote {}", a.out.display());
            if !ok {
                eprintln!("error: some step did not converge; see solver.csv and report.json");
            }
            Ok(ok)
        }
        Command::SceneSchema(a) => {
            solve::write_schema(a.out.as_deref())?;
            Ok(true)
        }
        Command::LateralBuckling(a) => {
            let sweep = lateral_sweep_from_args(&a)?;
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            let meshes: Vec<usize> = a
                .convergence_meshes
                .iter()
                .copied()
                .filter(|&n| n > 0)
                .collect();
            let out = pool.install(|| lateral_sweep_report::run(&sweep, &a.out, &store))?;
            let conv = if meshes.is_empty() {
                Some(Vec::new())
            } else {
                pool.install(|| {
                    lateral_sweep_report::run_convergence(
                        sweep.material,
                        &a.convergence_widths,
                        &meshes,
                        &a.out,
                        &store,
                    )
                })?
            };
            match (out, conv) {
                (Some(out), Some(conv)) => {
                    lateral_sweep_report::print_summary(&out);
                    lateral_sweep_report::print_convergence(&conv);
                    println!("wrote {}", a.out.display());
                }
                _ => print_shard_done(&store),
            }
            Ok(true)
        }
        Command::Models(a) => {
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            match pool.install(|| model_comparison_report::run(&a.out, &store))? {
                Some(c) => {
                    model_comparison_report::print_summary(&c);
                    for ch in &c.checks {
                        println!(
                            "{}  {:>10.4}  target {:<8}  {}",
                            if ch.passed { "PASS" } else { "FAIL" },
                            ch.measured,
                            ch.target,
                            ch.description
                        );
                    }
                    write_csv_checks(&a.out, &c.checks)?;
                    println!("wrote {}", a.out.display());
                }
                None => print_shard_done(&store),
            }
            Ok(true)
        }
        Command::Sensitivity(a) => {
            let study = sensitivity_report::study_from_args(&a)?;
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            match pool.install(|| sensitivity_report::run(&study, &a.out, &store))? {
                Some(out) => {
                    sensitivity_report::print_summary(&out);
                    println!("wrote {}", a.out.display());
                }
                None => print_shard_done(&store),
            }
            Ok(true)
        }
        Command::Validate(a) => {
            let pool = thread_pool(a.jobs)?;
            let store = store_options(&a.out, &a.store);
            let jobs = pool.current_num_threads();
            pool.install(|| validate::run(&a.out, a.preset == Preset::Full, &store, jobs))
        }
        Command::Merge(a) => {
            let s = store::merge::merge_stores(&a.into, &a.sources)?;
            println!(
                "merged into {}: {} records copied, {} already there, {} unreadable left out",
                a.into.display(),
                s.copied,
                s.identical,
                s.skipped
            );
            Ok(true)
        }
    }
}

pub(crate) fn print_shard_done(store: &StoreOptions) {
    if let Some(s) = store.shard {
        println!(
            "shard {s}: records in {}; merge the shards with `slender merge`, then rerun without --shard for the report",
            store.root.display()
        );
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// Writes `checks.csv` of a standalone command.
fn write_csv_checks(
    out: &std::path::Path,
    checks: &[slender_validation::cantilever::Check],
) -> Result<()> {
    output::write_csv(&out.join("checks.csv"), checks)
}
