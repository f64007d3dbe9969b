//! `slender validate`: runs the benchmarks on their default grids and prints a pass/fail
//! table of the acceptance targets.

use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use slender_core::solver::SolverParams;
use slender_validation::bend_twist::acceptance::bend_twist_checks;
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::{cantilever_checks, CantileverSweep, Check};

use crate::output::{write_atomic, write_csv};

/// Runs the validation; returns whether every target passed.
pub fn run(out: &Path, full: bool) -> Result<bool> {
    let clock = Instant::now();
    let sweep = CantileverSweep::default();
    let cantilever = crate::cantilever_report::run(&sweep, &out.join("cantilever"))?;
    crate::cantilever_report::print_summary(&cantilever.summary);
    let mut checks = cantilever_checks(&cantilever.records, &SolverParams::default())?;
    let bt_sweep = if full {
        BendTwistSweep::full()
    } else {
        BendTwistSweep::quick()
    };
    let bend_twist = crate::bend_twist_report::run(&bt_sweep, &out.join("bend-twist"))?;
    crate::bend_twist_report::print_summary(&bend_twist.summary);
    checks.extend(bend_twist_checks(&bend_twist.summary));
    write_csv(&out.join("checks.csv"), &checks)?;
    write_atomic(&out.join("checks.md"), markdown(&checks).as_bytes())?;
    println!();
    print_table(&checks);
    let failed = checks.iter().filter(|c| !c.passed).count();
    println!(
        "\n{} of {} targets passed ({:.1} s); outputs in {}",
        checks.len() - failed,
        checks.len(),
        clock.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(failed == 0)
}

fn print_table(checks: &[Check]) {
    for c in checks {
        println!(
            "{}  {:<11} {:>12.5}  target {:<8}  {}",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.measured,
            c.target,
            c.description
        );
    }
}

fn markdown(checks: &[Check]) -> String {
    let mut s =
        String::from("| result | benchmark | check | measured | target |\n|---|---|---|---|---|\n");
    for c in checks {
        s += &format!(
            "| {} | {} | {} | {:.5} | {} |\n",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.description,
            c.measured,
            c.target
        );
    }
    s
}
