//! The sensitivity study of the lateral-buckling protocol (seed §5.3, Fig. 12): the
//! percentage of correct 2-D/3-D decisions of the protocol for every combination of shell set
//! Ω, elements n_L, load steps m_ls and clamp rotation σ, scored against the Kirchhoff plate
//! master curve over a (w/L, Γ/Γ_c) grid. The pure parts (grid, verdicts, scores, grouping)
//! are in [`slender_validation::lateral_sweep::sensitivity`].

use anyhow::{Context as _, Result};
use slender_validation::cantilever::Check;
use slender_validation::lateral_sweep::sensitivity::{
    group_scores, median, score, shell_set_by_name, summary_by_elements, Configuration,
    ConfigurationScore, GridPoint, Grouping, SensitivityPoint, SensitivityStudy, StudyError,
    Verdict, SQUARE,
};
use slender_validation::lateral_sweep::{sensitivity_checks, LateralBucklingSweep};
use slender_validation::shell_model::ShellModel;

use super::lateral_buckling::{ProtocolKey, PROTOCOL_STORE};
use super::{Benchmark, Context, Preset, SectionSpec};
use crate::output::write_csv;
use crate::plot::{plot_boxplots, BoxPanel, BoxSample};
use crate::store::runner::RunStats;

/// Section (and output directory).
const SECTION: &str = "sensitivity";

/// The sensitivity study.
pub struct Sensitivity {
    /// Configurations and grid.
    pub study: SensitivityStudy,
}

impl Sensitivity {
    /// A subset in quick, the seed's 216 configurations in full.
    pub fn for_preset(preset: Preset) -> Self {
        Self {
            study: match preset {
                Preset::Quick => SensitivityStudy::quick(),
                Preset::Full => SensitivityStudy::full(),
            },
        }
    }
}

/// What the study produced.
pub struct SensitivityRecords {
    /// Every configuration × grid point.
    points: Vec<SensitivityPoint>,
    /// One score per configuration.
    scores: Vec<ConfigurationScore>,
}

impl Benchmark for Sensitivity {
    type Records = SensitivityRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let study = &self.study;
        vec![SectionSpec {
            dir: SECTION.into(),
            title: "Sensitivity of the lateral-buckling protocol".into(),
            about: format!(
                "The seed's §5.3 study (Fig. 12): the share of correct 2-D/3-D decisions of \
                 the protocol over a (w/L, Γ/Γ_c) grid placed on the plate master curve, for \
                 {} configurations (shell model {:?} × Ω × n_L {:?} × m_ls {:?} × σ {:?}); \
                 w = L excluded from the score as in the seed.",
                study.configurations().len(),
                study.models.iter().map(|m| m.name()).collect::<Vec<_>>(),
                study.elements,
                study.load_steps,
                study.sigmas
            ),
            caption,
        }]
    }

    /// The protocol points of every configuration through the store (one progress bar for
    /// all, shared with `slender lateral-buckling`'s points), scored per configuration.
    fn records(&self, cx: &mut Context) -> Result<Option<SensitivityRecords>> {
        cx.enter(SECTION);
        let study = &self.study;
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
                model: c.model,
                n_length: c.n_length,
                width_ratio: g.width_ratio,
                gamma: g.gamma,
                sigma: c.sigma,
                load_steps: c.load_steps,
                solver: params,
            })
            .collect();
        let Some(protocol) = cx.cases(PROTOCOL_STORE, &keys, |k| {
            let sweep = LateralBucklingSweep {
                material: k.material,
                model: k.model,
                n_length: k.n_length,
                width_ratios: vec![k.width_ratio],
                gammas: vec![k.gamma],
                sigma: k.sigma,
                load_steps: k.load_steps,
                threshold: study.threshold,
            };
            Ok(sweep.protocol_at(k.width_ratio, k.gamma, &k.solver)?)
        })?
        else {
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
        Ok(Some(SensitivityRecords { points, scores }))
    }

    /// `points.csv`, `scores.csv` and the box plots `sensitivity.{png,svg}`.
    fn write(&self, r: &SensitivityRecords, cx: &mut Context) -> Result<()> {
        cx.enter(SECTION);
        let out = cx.dir(SECTION);
        let study = &self.study;
        let scores = &r.scores;
        write_csv(&out.join("points.csv"), &r.points)?;
        write_csv(&out.join("scores.csv"), scores)?;
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
                boxes: group_scores(scores, by, study)
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
        print_summary(r, cx.stats(SECTION));
        Ok(())
    }

    fn checks(&self, r: &SensitivityRecords, cx: &mut Context) -> Result<Vec<Check>> {
        cx.enter(SECTION);
        Ok(sensitivity_checks(&r.scores))
    }
}

/// Caption of the section's figure.
fn caption(_stem: &str) -> String {
    "Counterpart of the seed's Fig. 12: share of correct 2-D/3-D decisions per configuration, \
     grouped by shell model, shell set Ω, elements n_L, load steps m_ls and clamp rotation σ \
     (w = L excluded)."
        .into()
}

/// Prints the median / min score per n_L (and at w = L if computed) and the points whose
/// protocol did not converge.
fn print_summary(out: &SensitivityRecords, stats: RunStats) {
    println!(
        "protocol points: {} computed, {} reused from the store",
        stats.computed, stats.reused
    );
    let square = out.scores.iter().any(|s| s.square_points > 0);
    print!(
        "{:<8} {:>4} {:>8} {:>10} {:>8} {:>8}",
        "model", "n_L", "configs", "median %", "min %", "max %"
    );
    if square {
        print!(" {:>14}", "w = L median %");
    }
    println!();
    for model in ShellModel::ALL {
        let mine: Vec<ConfigurationScore> = out
            .scores
            .iter()
            .filter(|s| s.model == model)
            .cloned()
            .collect();
        for s in summary_by_elements(&mine) {
            print!(
                "{:<8} {:>4} {:>8} {:>10.1} {:>8.1} {:>8.1}",
                model.name(),
                s.n_length,
                s.configurations,
                s.median,
                s.min,
                s.max
            );
            if square {
                print!(" {:>14.1}", s.square_median);
            }
            println!();
        }
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
                "  {} {} n_L = {} m_ls = {} σ = {} w/L = {} Γ = {:.3} (Γ/Γ_c = {}): residual {:.2e}",
                p.model,
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
