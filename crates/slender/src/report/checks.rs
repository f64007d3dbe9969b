//! The acceptance table: written as `checks.csv` and `checks.md`, printed to the terminal.

use std::path::Path;

use anyhow::Result;
use slender_validation::cantilever::Check;

use crate::output::{write_atomic, write_csv};

/// Writes `out/checks.csv` and `out/checks.md`.
pub fn write_checks(out: &Path, checks: &[Check]) -> Result<()> {
    write_csv(&out.join("checks.csv"), checks)?;
    write_atomic(&out.join("checks.md"), markdown(checks).as_bytes())
}

/// A measured value for tables: fixed point, or scientific when small (a 1e-12 force
/// imbalance must not print as 0.00000).
pub fn format_measured(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.3e}")
    } else {
        format!("{v:.5}")
    }
}

/// Prints one line per check.
pub fn print_table(checks: &[Check]) {
    for c in checks {
        println!(
            "{}  {:<11} {:>12}  target {:<8}  {}",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            format_measured(c.measured),
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
            "| {} | {} | {} | {} | {} |\n",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.description,
            format_measured(c.measured),
            c.target
        );
    }
    s
}
