//! `slender sensitivity`: the seed's §5.3 sensitivity study (Fig. 12) — the percentage of
//! correct 2-D/3-D decisions of the lateral-buckling protocol for every combination of shell
//! set Ω, elements n_L, load steps m_ls and clamp rotation σ, scored against the Kirchhoff
//! plate master curve over a (w/L, Γ/Γ_c) grid. The pure parts (grid, verdicts, scores,
//! grouping) are in [`slender_validation::lateral_sweep::sensitivity`].

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use slender_validation::lateral_sweep::sensitivity::{
    group_scores, median, score, shell_set_by_name, summary_by_elements, Configuration,
    ConfigurationScore, GridPoint, Grouping, SensitivityPoint, SensitivityStudy, StudyError,
    Verdict, SQUARE,
};
use slender_validation::lateral_sweep::LateralBucklingSweep;

use crate::lateral_sweep_report::ProtocolKey;
use crate::output::write_csv;
use crate::plot::{plot_boxplots, BoxPanel, BoxSample};
use crate::store::runner::{run_cases, StoreOptions};
use crate::store::BenchmarkStore;
use crate::{Preset, StoreArgs};

/// Command-line arguments of `slender sensitivity`; explicit lists override the preset.
#[derive(clap::Args, Debug)]
pub(crate) struct SensitivityArgs {
    /// Output directory.
    #[arg(long, default_value = "out/sensitivity")]
    pub(crate) out: PathBuf,
    /// quick: Ω_shell, n_L ∈ {8, 15}, m_ls ∈ {1, 5}, σ ∈ {0.1, 0.2}, w/L ∈ {0.05, 0.1, 0.2}
    /// (8 configurations); full: the seed's 216 configurations on w/L ∈ {0.05, 0.1, 0.2, 0.5}.
    #[arg(long, value_enum, default_value_t = Preset::Quick)]
    pub(crate) preset: Preset,
    /// Shell sets Ω, comma-separated: shell, combined, ips.
    #[arg(long, value_delimiter = ',')]
    pub(crate) materials: Option<Vec<String>>,
    /// Elements along the length n_L, comma-separated (square elements across).
    #[arg(long, value_delimiter = ',')]
    pub(crate) elements: Option<Vec<usize>>,
    /// Load steps m_ls of the protocol, comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub(crate) load_steps: Option<Vec<usize>>,
    /// Clamp rotations σ of the protocol (rad), comma-separated.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) sigmas: Option<Vec<f64>>,
    /// Aspect ratios w/L of the scored grid, comma-separated, each in [0.01, 1).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) width_ratios: Option<Vec<f64>>,
    /// Γ/Γ_c factors placing the grid around the plate master curve, comma-separated (> 0;
    /// default 0.7, 0.85, 0.93, 1.07, 1.2, 1.5).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub(crate) gamma_factors: Option<Vec<f64>>,
    /// Also run the square strip w = L, reported separately and not in the score (costly:
    /// n_L² elements).
    #[arg(long)]
    pub(crate) with_square: bool,
    /// Decision threshold ε on |y_tip|/L (default 1e-4, the seed's).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) threshold: Option<f64>,
    /// Worker threads (default: all cores). Results do not depend on it.
    #[arg(long)]
    pub(crate) jobs: Option<usize>,
    #[command(flatten)]
    pub(crate) store: StoreArgs,
}

/// The study the arguments describe, validated; errors name the flag and the valid range.
pub(crate) fn study_from_args(a: &SensitivityArgs) -> Result<SensitivityStudy> {
    let as_flag = |e: StudyError| match e {
        StudyError::Invalid { field, reason } => {
            anyhow::anyhow!("--{}: {reason}", field.replace('_', "-"))
        }
        other => anyhow::Error::new(other),
    };
    let mut s = match a.preset {
        Preset::Quick => SensitivityStudy::quick(),
        Preset::Full => SensitivityStudy::full(),
    };
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

/// The store benchmark of protocol points (shared with `slender lateral-buckling`).
const PROTOCOL_BENCHMARK: &str = "lateral-buckling";

/// What the study produced.
pub(crate) struct SensitivityOutput {
    /// Every configuration × grid point.
    pub(crate) points: Vec<SensitivityPoint>,
    /// One score per configuration.
    pub(crate) scores: Vec<ConfigurationScore>,
    /// Protocol points computed by this run.
    pub(crate) computed: usize,
    /// Protocol points found in the store.
    pub(crate) reused: usize,
}

/// Runs `study` through the store (one progress bar for all configurations, cheapest first),
/// writes `points.csv`, `scores.csv` and `sensitivity.{png,svg}` under `out`; `None` if this
/// run computed one shard only.
pub(crate) fn run(
    study: &SensitivityStudy,
    out: &Path,
    store: &StoreOptions,
) -> Result<Option<SensitivityOutput>> {
    study.validate()?;
    // The benchmark's solver settings, as `slender lateral-buckling` (shared store keys).
    let params = slender_validation::lateral_sweep::solver_params();
    params.validate()?;
    // The grid depends on the set only through ν; the master curve costs ~0.1 s a point.
    let grids: Vec<(&str, Vec<GridPoint>)> = study
        .materials
        .iter()
        .map(|m| Ok((m.name, study.grid(m)?)))
        .collect::<Result<_, StudyError>>()?;
    let cases: Vec<(Configuration, GridPoint)> = study
        .configurations()
        .into_iter()
        .flat_map(|c| {
            let grid = &grids
                .iter()
                .find(|g| g.0 == c.material.name)
                .expect("a grid per material")
                .1;
            grid.iter().map(move |g| (c, *g))
        })
        .collect();
    let keys: Vec<ProtocolKey> = cases
        .iter()
        .map(|(c, g)| ProtocolKey {
            material: c.material,
            n_length: c.n_length,
            width_ratio: g.width_ratio,
            gamma: g.gamma,
            sigma: c.sigma,
            load_steps: c.load_steps,
            solver: params.clone(),
        })
        .collect();
    let protocol_run = run_cases(
        &BenchmarkStore::new(&store.root, PROTOCOL_BENCHMARK),
        store.shard,
        &keys,
        |k| {
            let sweep = LateralBucklingSweep {
                material: k.material,
                n_length: k.n_length,
                width_ratios: vec![k.width_ratio],
                gammas: vec![k.gamma],
                sigma: k.sigma,
                load_steps: k.load_steps,
                threshold: study.threshold,
            };
            Ok(sweep.protocol_at(k.width_ratio, k.gamma, &k.solver)?)
        },
    )?;
    let (computed, reused) = (protocol_run.computed, protocol_run.reused);
    let Some(protocol) = protocol_run.complete() else {
        return Ok(None);
    };
    let points: Vec<SensitivityPoint> = cases
        .iter()
        .zip(&protocol)
        .map(|((c, g), p)| {
            SensitivityPoint::new(
                c,
                g,
                p.tip_deviation,
                p.converged,
                p.relative_residual,
                study.threshold,
            )
        })
        .collect();
    let scores: Vec<ConfigurationScore> = study
        .configurations()
        .iter()
        .map(|c| score(c, &points))
        .collect();
    write_csv(&out.join("points.csv"), &points)?;
    write_csv(&out.join("scores.csv"), &scores)?;

    // The panel is titled Ω already; "Ω_combined" and its neighbours overlapped under a box.
    let label_of = |name: &str| {
        shell_set_by_name(name)
            .map(|m| m.label.trim_start_matches("Ω_").to_string())
            .unwrap_or_else(|_| name.to_string())
    };
    let panels: Vec<BoxPanel> = Grouping::ALL
        .iter()
        .map(|&by| BoxPanel {
            title: by.title().to_string(),
            boxes: group_scores(&scores, by, study)
                .into_iter()
                .map(|(label, values)| BoxSample {
                    label: if by == Grouping::Material {
                        label_of(&label)
                    } else {
                        label
                    },
                    values,
                })
                .collect(),
        })
        .collect();
    let stem = out.join("sensitivity");
    plot_boxplots(
        &stem,
        &format!(
            "Correct 2-D/3-D decisions of the protocol (w < L, ε = {:e}), {} configurations",
            study.threshold,
            scores.len()
        ),
        "correct decisions (%)",
        (0.0, 101.0),
        &panels,
    )
    .with_context(|| format!("plotting {}", stem.display()))?;
    Ok(Some(SensitivityOutput {
        points,
        scores,
        computed,
        reused,
    }))
}

/// Prints the median / min score per n_L (and at w = L if computed) and the points whose
/// protocol did not converge.
pub(crate) fn print_summary(out: &SensitivityOutput) {
    println!(
        "protocol points: {} computed, {} reused from the store",
        out.computed, out.reused
    );
    let square = out.scores.iter().any(|s| s.square_points > 0);
    print!(
        "{:>4} {:>8} {:>10} {:>8} {:>8}",
        "n_L", "configs", "median %", "min %", "max %"
    );
    if square {
        print!(" {:>14}", "w = L median %");
    }
    println!();
    for s in summary_by_elements(&out.scores) {
        print!(
            "{:>4} {:>8} {:>10.1} {:>8.1} {:>8.1}",
            s.n_length, s.configurations, s.median, s.min, s.max
        );
        if square {
            print!(" {:>14.1}", s.square_median);
        }
        println!();
    }
    let all: Vec<f64> = out.scores.iter().map(|s| s.score_percent).collect();
    println!(
        "all {} configurations: median {:.1} %, min {:.1} % (seed Fig. 12: ≈ 70 % at n_L = 8, ≥ 90 % from n_L = 30)",
        all.len(),
        median(&all),
        all.iter().copied().fold(f64::INFINITY, f64::min)
    );
    let failed: Vec<&SensitivityPoint> = out
        .points
        .iter()
        .filter(|p| p.protocol == Verdict::NotConverged)
        .collect();
    if !failed.is_empty() {
        println!(
            "{} protocol runs did not converge (no decision: counted wrong, {} of them at w = L):",
            failed.len(),
            failed.iter().filter(|p| p.width_ratio >= SQUARE).count()
        );
        for p in failed.iter().take(20) {
            println!(
                "  {} n_L = {} m_ls = {} σ = {} w/L = {} Γ = {:.3} (Γ/Γ_c = {}): residual {:.2e}",
                p.material,
                p.n_length,
                p.load_steps,
                p.sigma,
                p.width_ratio,
                p.gamma,
                p.gamma_factor,
                p.relative_residual
            );
        }
        if failed.len() > 20 {
            println!("  … {} more in points.csv", failed.len() - 20);
        }
    }
}
