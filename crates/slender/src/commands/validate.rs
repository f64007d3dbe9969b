//! `slender validate`: every benchmark of [`crate::benchmarks::suite`] in turn, then the
//! acceptance table (printed, `checks.csv`, `checks.md`) and the report page `index.html`.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;

use super::{print_shard_done, thread_pool, StoreArgs};
use crate::benchmarks::{suite, Context, Layout, Preset};
use crate::report::checks::{print_table, write_checks};
use crate::report::{write_report, Report, Section};

/// The flags of `slender validate`.
#[derive(clap::Args, Debug)]
pub struct ValidateArgs {
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

/// Runs the validation; returns whether every target passed. With a shard, computes that
/// shard of every benchmark into the store and writes no report.
pub fn run(a: &ValidateArgs) -> Result<bool> {
    let pool = thread_pool(a.jobs)?;
    let jobs = pool.current_num_threads();
    pool.install(|| validate(a, jobs))
}

fn validate(a: &ValidateArgs, jobs: usize) -> Result<bool> {
    let clock = Instant::now();
    let out = &a.out;
    let store = a.store.options(out);
    let benchmarks = suite(a.preset);
    let mut cx = Context::new(out, Layout::PerSection, &store, true);
    let mut checks = Vec::new();
    let mut complete = true;
    for b in &benchmarks {
        match b.run(&mut cx)? {
            Some(c) => checks.extend(c),
            None => complete = false,
        }
    }
    if !complete {
        print_shard_done(&store);
        return Ok(true);
    }
    write_checks(out, &checks)?;
    println!();
    print_table(&checks);
    let failed = checks.iter().filter(|c| !c.passed).count();
    let sections: Vec<Section> = benchmarks
        .iter()
        .flat_map(|b| b.sections())
        .map(|spec| Section {
            tally: cx.tally(&spec.dir),
            spec,
        })
        .collect();
    let page = write_report(
        out,
        &Report {
            checks: &checks,
            sections,
            preset: a.preset.name(),
            jobs,
            wall_seconds: clock.elapsed().as_secs_f64(),
        },
    )?;
    println!(
        "\n{} of {} targets passed ({:.1} s); report {}",
        checks.len() - failed,
        checks.len(),
        clock.elapsed().as_secs_f64(),
        page.display()
    );
    Ok(failed == 0)
}
