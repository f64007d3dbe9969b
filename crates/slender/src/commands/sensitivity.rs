//! `slender sensitivity`: the sensitivity study of the lateral-buckling protocol on the
//! configurations of a preset, with overrides.

use std::path::PathBuf;

use anyhow::Result;
use slender_validation::lateral_sweep::sensitivity::{
    shell_set_by_name, SensitivityStudy, StudyError,
};

use super::{run_benchmark, StoreArgs};
use crate::benchmarks::sensitivity::Sensitivity;
use crate::benchmarks::Preset;

/// Command-line arguments of `slender sensitivity`; explicit lists override the preset.
#[derive(clap::Args, Debug)]
pub struct SensitivityArgs {
    /// Output directory.
    #[arg(long, default_value = "out/sensitivity")]
    pub out: PathBuf,
    /// quick: Ω_shell, n_L ∈ {8, 15}, m_ls ∈ {1, 5}, σ ∈ {0.1, 0.2}, w/L ∈ {0.05, 0.1, 0.2}
    /// (8 configurations per shell model); full: the seed's 216 configurations per shell model
    /// on w/L ∈ {0.05, 0.1, 0.2, 0.5}.
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    pub preset: Preset,
    /// Shell models, comma-separated: midedge, bspline (default: both, a factor of the study).
    #[arg(long, value_delimiter = ',')]
    pub shell_model: Option<Vec<String>>,
    /// Shell sets Ω, comma-separated: shell, combined, ips.
    #[arg(long, value_delimiter = ',')]
    pub materials: Option<Vec<String>>,
    /// Elements along the length n_L, comma-separated (square elements across).
    #[arg(long, value_delimiter = ',')]
    pub elements: Option<Vec<usize>>,
    /// Load steps m_ls of the protocol, comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub load_steps: Option<Vec<usize>>,
    /// Clamp rotations σ of the protocol (rad), comma-separated.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub sigmas: Option<Vec<f64>>,
    /// Aspect ratios w/L of the scored grid, comma-separated, each in [0.01, 1).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub width_ratios: Option<Vec<f64>>,
    /// Γ/Γ_c factors placing the grid around the plate master curve, comma-separated (> 0;
    /// default 0.7, 0.85, 0.93, 1.07, 1.2, 1.5).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub gamma_factors: Option<Vec<f64>>,
    /// Also run the square strip w = L, reported separately and not in the score (costly:
    /// n_L² elements).
    #[arg(long)]
    pub with_square: bool,
    /// Decision threshold ε on |y_tip|/L (default 1e-4, the seed's).
    #[arg(long, allow_hyphen_values = true)]
    pub threshold: Option<f64>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub jobs: Option<usize>,
    #[command(flatten)]
    pub store: StoreArgs,
}

/// Runs the study the flags describe.
pub fn run(a: &SensitivityArgs) -> Result<bool> {
    let benchmark = Sensitivity {
        study: study_from_args(a)?,
    };
    run_benchmark(&benchmark, &a.out, &a.store, a.jobs)
}

/// The study the arguments describe, validated; errors name the flag and the valid range.
fn study_from_args(a: &SensitivityArgs) -> Result<SensitivityStudy> {
    let as_flag = |e: StudyError| match e {
        StudyError::Invalid { field, reason } => {
            anyhow::anyhow!("--{}: {reason}", field.replace('_', "-"))
        }
        other => anyhow::Error::new(other),
    };
    let mut s = Sensitivity::for_preset(a.preset).study;
    if let Some(m) = &a.shell_model {
        s.models = super::shell_models(m)?;
    }
    if let Some(m) = &a.materials {
        s.materials = m
            .iter()
            .map(|n| shell_set_by_name(n.trim()))
            .collect::<Result<_, _>>()
            .map_err(as_flag)?;
    }
    if let Some(v) = &a.elements {
        s.elements = v.clone();
    }
    if let Some(v) = &a.load_steps {
        s.load_steps = v.clone();
    }
    if let Some(v) = &a.sigmas {
        s.sigmas = v.clone();
    }
    if let Some(v) = &a.width_ratios {
        s.width_ratios = v.clone();
    }
    if let Some(v) = &a.gamma_factors {
        s.gamma_factors = v.clone();
    }
    if let Some(t) = a.threshold {
        s.threshold = t;
    }
    if a.with_square {
        s = s.with_square();
    }
    s.validate().map_err(as_flag)?;
    Ok(s)
}
