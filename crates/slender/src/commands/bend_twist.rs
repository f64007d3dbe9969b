//! `slender bend-twist`: the bend–twist benchmark on the grid of a preset, with overrides.

use std::path::PathBuf;

use anyhow::{bail, Result};
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::log_space;

use super::{run_benchmark, StoreArgs};
use crate::benchmarks::bend_twist::BendTwist;
use crate::benchmarks::Preset;

/// The flags of `slender bend-twist`.
#[derive(clap::Args, Debug)]
pub struct BendTwistArgs {
    /// Output directory.
    #[arg(long, default_value = "out/bend-twist")]
    out: PathBuf,
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

/// Runs the benchmark the flags describe.
pub fn run(a: &BendTwistArgs) -> Result<bool> {
    let benchmark = BendTwist {
        sweep: bend_twist_sweep(a)?,
    };
    run_benchmark(&benchmark, &a.out, &a.store, a.jobs)
}

/// The grid of the preset with the flags' overrides.
fn bend_twist_sweep(a: &BendTwistArgs) -> Result<BendTwistSweep> {
    let mut s = BendTwist::for_preset(a.preset).sweep;
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
