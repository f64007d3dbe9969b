//! The subcommands of `slender`, one file each: their flags, how the flags become a benchmark
//! (or a scene run, a merge…), and what they print. The benchmarks themselves are in
//! [`crate::benchmarks`].

pub mod bend_twist;
pub mod cantilever;
pub mod lateral_buckling;
pub mod master_curve;
pub mod merge;
pub mod models;
pub mod scene_schema;
pub mod sensitivity;
pub mod solve;
pub mod stick_slip;
pub mod validate;
pub mod view;

use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};
use slender_validation::rod_model::RodModel;

use crate::benchmarks::{AnyBenchmark, Context, Layout};
use crate::store::runner::StoreOptions;
use crate::store::shard::Shard;

/// Where a sweep keeps its finished cases, and which shard of it this run computes.
#[derive(clap::Args, Debug)]
pub struct StoreArgs {
    /// Result store (default: OUT/store). Finished cases found there are not recomputed.
    #[arg(long)]
    pub(crate) store: Option<PathBuf>,
    /// Compute only shard i of n (e.g. 0/4) into the store and write no report; combine the
    /// shards with `slender merge`, then rerun without --shard to write the report.
    #[arg(long)]
    pub(crate) shard: Option<Shard>,
}

impl StoreArgs {
    /// Store root and shard of a run writing to `out`.
    pub fn options(&self, out: &Path) -> StoreOptions {
        StoreOptions {
            root: self.store.clone().unwrap_or_else(|| out.join("store")),
            shard: self.shard,
        }
    }
}

/// The rod formulations of `--model`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelArg {
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
    /// The model of the flag.
    pub fn model(self) -> RodModel {
        match self {
            Self::Der => RodModel::Der,
            Self::Cosserat => RodModel::Cosserat,
            Self::CosseratTan => RodModel::CosseratTangent,
            Self::Se3 => RodModel::Se3,
        }
    }
}

/// The worker threads of `--jobs` (all cores if `None`).
pub fn thread_pool(jobs: Option<usize>) -> Result<rayon::ThreadPool> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(j) = jobs {
        if j == 0 {
            anyhow::bail!("--jobs = 0: must be >= 1");
        }
        b = b.num_threads(j);
    }
    b.build().context("starting the worker threads")
}

/// Tells a shard run where its records are and what to do next.
pub fn print_shard_done(store: &StoreOptions) {
    if let Some(s) = store.shard {
        println!(
            "shard {s}: records in {}; merge the shards with `slender merge`, then rerun without --shard for the report",
            store.root.display()
        );
    }
}

/// Runs one benchmark the way a single-benchmark command does: every section's files
/// straight in `out`, no acceptance checks; prints where the files went.
pub fn run_benchmark(
    benchmark: &dyn AnyBenchmark,
    out: &Path,
    store: &StoreArgs,
    jobs: Option<usize>,
) -> Result<bool> {
    let pool = thread_pool(jobs)?;
    let store = store.options(out);
    let mut cx = Context::new(out, Layout::Flat, &store, false);
    match pool.install(|| benchmark.run(&mut cx))? {
        Some(_) => println!("wrote {}", out.display()),
        None => print_shard_done(&store),
    }
    Ok(true)
}

/// The shell models named in `--shell-model` (comma-separated, no duplicates).
pub fn shell_models(names: &[String]) -> Result<Vec<slender_validation::shell_model::ShellModel>> {
    let mut models = Vec::new();
    for n in names {
        let m = n
            .trim()
            .parse()
            .map_err(|e: String| anyhow::anyhow!("--shell-model: {e}"))?;
        if models.contains(&m) {
            anyhow::bail!("--shell-model: `{m}` given twice");
        }
        models.push(m);
    }
    if models.is_empty() {
        anyhow::bail!("--shell-model: give at least one of midedge, bspline");
    }
    Ok(models)
}
