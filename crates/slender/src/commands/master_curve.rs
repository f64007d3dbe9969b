//! `slender master-curve`: the bend–twist master curve on its own, at chosen Y and GJ/EI —
//! the critical X_c1 (the coil loses stability) and X_c2 (the hanging curl is stable again)
//! from the linearized stability ODE, without a rod discretization or a grid sweep.

use std::path::PathBuf;

use anyhow::{bail, Context as _, Result};
use rayon::prelude::*;
use serde::Serialize;
use slender_validation::bend_twist::master_curve::critical_boundaries;
use slender_validation::cantilever::log_space;

use super::thread_pool;
use crate::output::write_csv;
use crate::plot::{plot_lines, Curve, LineAxes, Scale};

/// The flags of `slender master-curve`.
#[derive(clap::Args, Debug)]
pub struct MasterCurveArgs {
    /// Output directory.
    #[arg(long, default_value = "out/master-curve")]
    out: PathBuf,
    /// The Y = L/(2πR) values, comma-separated (e.g. `--y 0.5,1,2`); default: `--points`
    /// values log-spaced over `--y-range`.
    #[arg(long, value_delimiter = ',')]
    y: Vec<f64>,
    /// The Y range of the default log-spaced values.
    #[arg(long, value_delimiter = ',', num_args = 2, default_values_t = [0.1, 10.0])]
    y_range: Vec<f64>,
    /// Number of log-spaced Y values (without `--y`).
    #[arg(long, default_value_t = 40)]
    points: usize,
    /// Torsion-to-bending stiffness ratio c = GJ/EI (Ω_rod: 0.77; 1/(1 + ν) for a solid
    /// circle).
    #[arg(long, default_value_t = 0.77)]
    gj_over_ei: f64,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    jobs: Option<usize>,
}

/// One row of `master_curve.csv`.
#[derive(Clone, Debug, Serialize)]
struct Row {
    y: f64,
    gj_over_ei: f64,
    /// Lower critical X (empty: the coil is stable at every X).
    x_c1: Option<f64>,
    /// Upper critical X.
    x_c2: Option<f64>,
    /// Γ = (2πX_c1·Y)³.
    gamma_c1: Option<f64>,
    /// Γ = (2πX_c2·Y)³.
    gamma_c2: Option<f64>,
}

/// The Y values the flags ask for.
fn y_values(a: &MasterCurveArgs) -> Result<Vec<f64>> {
    let ys = if a.y.is_empty() {
        let (lo, hi) = (a.y_range[0], a.y_range[1]);
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && hi >= lo) {
            bail!("--y-range = {lo},{hi}: must be two finite values with 0 < lo <= hi");
        }
        if a.points == 0 {
            bail!("--points = 0: must be >= 1");
        }
        log_space(lo, hi, a.points)
    } else {
        a.y.clone()
    };
    for &y in &ys {
        if !(y.is_finite() && y > 0.0) {
            bail!("--y = {y}: every Y must be finite and > 0");
        }
    }
    Ok(ys)
}

/// Computes and writes the master curve.
pub fn run(a: &MasterCurveArgs) -> Result<bool> {
    let c = a.gj_over_ei;
    if !(c.is_finite() && c > 0.0) {
        bail!("--gj-over-ei = {c}: must be finite and > 0");
    }
    let ys = y_values(a)?;
    let pool = thread_pool(a.jobs)?;
    let boundaries = pool.install(|| {
        ys.par_iter()
            .map(|&y| critical_boundaries(y, c).with_context(|| format!("master curve at Y = {y}")))
            .collect::<Result<Vec<_>>>()
    })?;
    let gamma = |x: Option<f64>, y: f64| x.map(|x| (2.0 * std::f64::consts::PI * x * y).powi(3));
    let rows: Vec<Row> = boundaries
        .iter()
        .map(|b| Row {
            y: b.y,
            gj_over_ei: c,
            x_c1: b.lower,
            x_c2: b.upper,
            gamma_c1: gamma(b.lower, b.y),
            gamma_c2: gamma(b.upper, b.y),
        })
        .collect();
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    write_csv(&a.out.join("master_curve.csv"), &rows)?;
    println!("bend–twist master curve, GJ/EI = {c}: planar state unstable for X_c1 < X < X_c2");
    println!("  {:>10} {:>12} {:>12}", "Y", "X_c1", "X_c2");
    let show = |x: Option<f64>| x.map_or("—".to_string(), |x| format!("{x:.6}"));
    for r in &rows {
        println!("  {:>10.5} {:>12} {:>12}", r.y, show(r.x_c1), show(r.x_c2));
    }
    // The boundary in the seed's (X, Y) plane: lines through the rows that have it.
    let line = |label: &str, pick: fn(&Row) -> Option<f64>| Curve {
        label: label.into(),
        points: rows
            .iter()
            .filter_map(|r| pick(r).map(|x| (x, r.y)))
            .collect(),
        dashed: false,
        markers: rows.len() < 20,
    };
    plot_lines(
        &a.out.join("master_curve"),
        &format!("Bend–twist master curve, GJ/EI = {c}"),
        LineAxes {
            x_desc: "X = (R/L) Γ^(1/3)",
            y_desc: "Y = L / (2πR)",
            x_scale: Scale::Log,
            y_scale: Scale::Log,
        },
        &[
            line("X_c1: the coil loses stability", |r| r.x_c1),
            line("X_c2: the hanging curl is stable again", |r| r.x_c2),
        ],
    )?;
    println!("wrote {}", a.out.display());
    Ok(true)
}
