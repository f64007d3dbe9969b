//! `slender models`: the rod models side by side, with their acceptance checks (printed and
//! in `checks.csv`, `checks.md`).

use std::path::PathBuf;

use anyhow::Result;

use super::{print_shard_done, thread_pool, StoreArgs};
use crate::benchmarks::rod_models::RodModels;
use crate::benchmarks::{AnyBenchmark, Context, Layout, Preset};
use crate::report::checks::{print_table, write_checks};

/// The flags of `slender models`.
#[derive(clap::Args, Debug)]
pub struct ModelsArgs {
    /// Output directory.
    #[arg(long, default_value = "out/models")]
    out: PathBuf,
    /// Bend–twist grid: quick (the 12 × 12 quick grid's rows Y ≤ 5, 20·Y elements) or full
    /// (the whole 12 × 12 grid).
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    preset: Preset,
    /// Worker threads (default: all cores). Results other than times do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
    #[command(flatten)]
    store: StoreArgs,
}

/// Runs the comparison and its checks; returns whether every target passed.
pub fn run(a: &ModelsArgs) -> Result<bool> {
    let pool = thread_pool(a.jobs)?;
    let store = a.store.options(&a.out);
    let benchmark = RodModels::for_preset(a.preset);
    let mut cx = Context::new(&a.out, Layout::Flat, &store, true);
    let Some(checks) = pool.install(|| benchmark.run(&mut cx))? else {
        print_shard_done(&store);
        return Ok(true);
    };
    write_checks(&a.out, &checks)?;
    println!();
    print_table(&checks);
    let failed = checks.iter().filter(|c| !c.passed).count();
    println!(
        "\n{} of {} targets passed; wrote {}",
        checks.len() - failed,
        checks.len(),
        a.out.display()
    );
    Ok(failed == 0)
}
