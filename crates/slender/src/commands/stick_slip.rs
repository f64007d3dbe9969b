//! `slender stick-slip`: the stick–slip sweep (Romero's fourth benchmark) of a preset, with
//! overrides.

use std::path::PathBuf;

use anyhow::Result;
use slender_validation::stick_slip::sweep::{rod_set_by_name, StickSlipSweep, ROD_SETS};

use super::{run_benchmark, StoreArgs};
use crate::benchmarks::stick_slip::StickSlip;
use crate::benchmarks::Preset;

/// Command-line arguments of `slender stick-slip`; explicit lists override the preset.
#[derive(clap::Args, Debug)]
pub struct StickSlipArgs {
    /// Output directory.
    #[arg(long, default_value = "out/stick-slip")]
    pub out: PathBuf,
    /// quick: 3 rods × μ ∈ {0.2, 0.5, 1} × 16 values of tan α/μ in [0.5, 1.5] (down to
    /// ±0.5 % of 1); full: 3 rods × 6 values of μ × 28 values of tan α/μ (down to ±0.1 %).
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    pub preset: Preset,
    /// Rod sets, comma-separated: soft (E = 1 MPa), polymer (1 GPa), steel (200 GPa).
    #[arg(long, value_delimiter = ',')]
    pub rods: Option<Vec<String>>,
    /// Coulomb coefficients μ, comma-separated (> 0).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub mus: Option<Vec<f64>>,
    /// Values of tan α / μ, comma-separated (≥ 0; 1 is the threshold).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub ratios: Option<Vec<f64>>,
    /// Elements along each rod.
    #[arg(long)]
    pub elements: Option<usize>,
    /// Time step (s).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// Time steps per run.
    #[arg(long)]
    pub steps: Option<usize>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    #[command(flatten)]
    pub store: StoreArgs,
}

/// Runs the sweep the flags describe.
pub fn run(a: &StickSlipArgs) -> Result<bool> {
    let benchmark = StickSlip {
        sweep: sweep_from_args(a)?,
    };
    run_benchmark(&benchmark, &a.out, &a.store, a.jobs)
}

/// The sweep the arguments describe, validated; errors name the flag and the valid range.
fn sweep_from_args(a: &StickSlipArgs) -> Result<StickSlipSweep> {
    let mut s = StickSlip::for_preset(a.preset).sweep;
    if let Some(names) = &a.rods {
        s.rods = names
            .iter()
            .map(|n| {
                rod_set_by_name(n.trim()).ok_or_else(|| {
                    anyhow::anyhow!(
                        "--rods: unknown rod set `{n}` (one of {})",
                        ROD_SETS.map(|r| r.name).join(", ")
                    )
                })
            })
            .collect::<Result<_>>()?;
    }
    if let Some(v) = &a.mus {
        s.mus = v.clone();
    }
    if let Some(v) = &a.ratios {
        s.ratios = v.clone();
    }
    if let Some(n) = a.elements {
        s.elements = n;
    }
    if let Some(dt) = a.dt {
        s.dt = dt;
    }
    if let Some(n) = a.steps {
        s.steps = n;
    }
    s.validate().map_err(|e| anyhow::anyhow!("--{e}"))?;
    Ok(s)
}
