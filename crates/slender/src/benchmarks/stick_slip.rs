//! Stick–slip (Romero's fourth benchmark): a rod released on a rough plane inclined at α,
//! over rods of several decades of stiffness and Γ, Coulomb coefficients μ and tan α / μ
//! around the threshold. Each run through the store; results.csv, summary.csv, the
//! adimensional acceleration against Coulomb's law, the acceleration error and the
//! displacement against tan α / μ, phase diagrams stick/slide; scored against Coulomb's law.
//! The pure parts (rod sets, cases, rows, checks) are in
//! [`slender_validation::stick_slip::sweep`].

use anyhow::{Context as _, Result};
use serde::Serialize;
use slender_validation::cantilever::Check;
use slender_validation::stick_slip::sweep::{
    stick_slip_checks, summaries, StickSlipRow, StickSlipSummary, StickSlipSweep,
    ACCELERATION_TARGET, BAND, DISPLACEMENT_TARGET,
};
use slender_validation::stick_slip::{StickSlipCase, StickSlipResult};

use super::{Benchmark, Context, Preset, SectionSpec};
use crate::output::write_csv;
use crate::plot::{
    plot_lines, plot_phase_diagram_labeled, Curve, LineAxes, Overlay, Phase, PhaseLabels,
    PhasePoint, Scale,
};
use crate::store::runner::RunStats;

/// Section (and output directory).
const SECTION: &str = "stick-slip";
/// The store of runs.
const STORE: &str = "stick-slip";

/// The stick–slip benchmark.
pub struct StickSlip {
    /// Rods, μ, ratios, time stepping.
    pub sweep: StickSlipSweep,
}

impl StickSlip {
    /// The sweep of `preset`.
    pub fn for_preset(preset: Preset) -> Self {
        Self {
            sweep: match preset {
                Preset::Quick => StickSlipSweep::quick(),
                Preset::Full => StickSlipSweep::full(),
            },
        }
    }
}

/// Everything a run depends on: the store key.
#[derive(Serialize)]
struct StickSlipKey {
    case: StickSlipCase,
}

/// What the runs produced.
pub struct StickSlipRecords {
    /// One scored row per run, in sweep order.
    rows: Vec<StickSlipRow>,
}

impl Benchmark for StickSlip {
    type Records = StickSlipRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let s = &self.sweep;
        vec![SectionSpec {
            dir: SECTION.into(),
            title: "Stick–slip of a rod on a rough inclined plane".into(),
            about: format!(
                "Romero's fourth benchmark: a straight rod released at rest on a plane inclined \
                 at α with Coulomb coefficient μ, stepped in time ({} steps of {} s, backward \
                 Euler, friction updated every step). Measured: the stick/slide decision, the \
                 centroid's largest displacement and its acceleration fitted to x₀ + v₀t + ½at²; \
                 against Coulomb's law — no motion while tan α ≤ μ, a = g(sin α − μ cos α) \
                 otherwise, whatever the rod. {} rods (Γ = ρAgL³/EI from {:.1e} to {:.1e}, \
                 E from {:.0e} to {:.0e} Pa) × μ ∈ {:?} × tan α/μ ∈ {:?}; points within \
                 ±{} % of tan α = μ are run and shown, not scored.",
                s.steps,
                s.dt,
                s.rods.len(),
                s.rods
                    .iter()
                    .map(|r| r.gamma(slender_validation::stick_slip::sweep::GRAVITY))
                    .fold(f64::INFINITY, f64::min),
                s.rods
                    .iter()
                    .map(|r| r.gamma(slender_validation::stick_slip::sweep::GRAVITY))
                    .fold(0.0, f64::max),
                s.rods.iter().map(|r| r.young).fold(f64::INFINITY, f64::min),
                s.rods.iter().map(|r| r.young).fold(0.0, f64::max),
                s.mus,
                s.ratios,
                100.0 * BAND
            ),
            caption,
        }]
    }

    fn records(&self, cx: &mut Context) -> Result<Option<StickSlipRecords>> {
        cx.enter(SECTION);
        self.sweep.validate().map_err(|e| anyhow::anyhow!(e))?;
        let points = self.sweep.points();
        let keys: Vec<StickSlipKey> = points
            .iter()
            .map(|p| StickSlipKey { case: p.case })
            .collect();
        let Some(results) = cx.cases(STORE, &keys, |k| -> Result<StickSlipResult> {
            Ok(k.case.run()?)
        })?
        else {
            return Ok(None);
        };
        let rows = points
            .iter()
            .zip(&results)
            .map(|(p, r)| StickSlipRow::new(p, r))
            .collect();
        Ok(Some(StickSlipRecords { rows }))
    }

    /// `results.csv`, `summary.csv` and the figures.
    fn write(&self, r: &StickSlipRecords, cx: &mut Context) -> Result<()> {
        cx.enter(SECTION);
        let out = cx.dir(SECTION);
        write_csv(&out.join("results.csv"), &r.rows)?;
        let summary = summaries(&r.rows);
        write_csv(&out.join("summary.csv"), &summary)?;
        let rods: Vec<&str> = self.sweep.rods.iter().map(|r| r.name).collect();
        let series = |keep: &dyn Fn(&StickSlipRow) -> bool,
                      point: &dyn Fn(&StickSlipRow) -> (f64, f64),
                      sort_by_x: bool|
         -> Vec<Curve> {
            let mut curves = Vec::new();
            for rod in &rods {
                for &mu in &self.sweep.mus {
                    let mut points: Vec<(f64, f64)> = r
                        .rows
                        .iter()
                        .filter(|w| w.rod == *rod && w.mu == mu && keep(w))
                        .map(point)
                        .collect();
                    if sort_by_x {
                        points.sort_by(|a, b| a.0.total_cmp(&b.0));
                    }
                    if points.is_empty() {
                        continue;
                    }
                    curves.push(Curve {
                        label: format!("{rod}, μ = {mu}"),
                        points,
                        dashed: false,
                        markers: true,
                    });
                }
            }
            curves
        };

        // a / (g cos α) against tan α − μ, with Coulomb's law.
        let (lo, hi) = r.rows.iter().fold((0.0f64, 0.0f64), |(a, b), w| {
            (a.min(w.excess), b.max(w.excess))
        });
        // Coulomb's law last and dashed: drawn over the measured points it lies on.
        let mut curves = series(&|_| true, &|w| (w.excess, w.normalized), true);
        curves.push(Curve {
            label: "Coulomb: a/(g cos α) = max(tan α − μ, 0)".into(),
            points: vec![(lo, 0.0), (0.0, 0.0), (hi, hi)],
            dashed: true,
            markers: false,
        });
        let stem = out.join("acceleration");
        plot_lines(
            &stem,
            "Stick–slip: measured acceleration against Coulomb's law",
            LineAxes {
                x_desc: "tan α − μ",
                y_desc: "a / (g cos α)",
                x_scale: Scale::Linear,
                y_scale: Scale::Linear,
            },
            &curves,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;

        // Relative acceleration error of the sliding runs against tan α / μ.
        let max_ratio = self.sweep.ratios.iter().copied().fold(1.0, f64::max);
        let mut curves = series(
            &|w| w.expected_slide && w.converged,
            &|w| (w.ratio, w.relative_error.max(1e-16)),
            true,
        );
        curves.push(Curve {
            label: format!(
                "target {ACCELERATION_TARGET:e} (scored from tan α/μ = {})",
                1.0 + BAND
            ),
            points: vec![
                (1.0 + BAND, ACCELERATION_TARGET),
                (max_ratio, ACCELERATION_TARGET),
            ],
            dashed: true,
            markers: false,
        });
        let stem = out.join("acceleration_error");
        plot_lines(
            &stem,
            "Stick–slip: |a − g(sin α − μ cos α)| / g(sin α − μ cos α) of the sliding runs",
            LineAxes {
                x_desc: "tan α / μ",
                y_desc: "relative acceleration error (floored at 1e-16)",
                x_scale: Scale::Linear,
                y_scale: Scale::Log,
            },
            &curves,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;

        // Largest displacement / L against tan α / μ.
        let min_ratio = self.sweep.ratios.iter().copied().fold(1.0, f64::min);
        let mut curves = series(
            &|w| w.converged,
            &|w| (w.ratio, w.displacement_over_length.max(1e-16)),
            true,
        );
        curves.push(Curve {
            label: format!(
                "target {DISPLACEMENT_TARGET:e} (scored up to tan α/μ = {})",
                1.0 - BAND
            ),
            points: vec![
                (min_ratio, DISPLACEMENT_TARGET),
                (1.0 - BAND, DISPLACEMENT_TARGET),
            ],
            dashed: true,
            markers: false,
        });
        let stem = out.join("displacement");
        plot_lines(
            &stem,
            "Stick–slip: largest centroid displacement over the run",
            LineAxes {
                x_desc: "tan α / μ",
                y_desc: "displacement / L (floored at 1e-16)",
                x_scale: Scale::Linear,
                y_scale: Scale::Log,
            },
            &curves,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;

        // Phase diagrams: (μ, tan α) per rod, (Γ, tan α / μ) for all.
        let labels = PhaseLabels {
            yes: "slide",
            no: "stick",
            ring: "decision against Coulomb (scored point)",
        };
        let phase = |w: &StickSlipRow| {
            if !w.converged {
                Phase::NotConverged
            } else if w.slid {
                Phase::ThreeD
            } else {
                Phase::TwoD
            }
        };
        let range = |v: &mut dyn Iterator<Item = f64>, pad: f64| {
            let (a, b) = v.fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
            (a / pad, b * pad)
        };
        for rod in &self.sweep.rods {
            let mine: Vec<&StickSlipRow> = r.rows.iter().filter(|w| w.rod == rod.name).collect();
            let points: Vec<PhasePoint> = mine
                .iter()
                .filter(|w| w.tan_alpha > 0.0)
                .map(|w| PhasePoint {
                    x: w.mu,
                    y: w.tan_alpha,
                    phase: phase(w),
                    disagrees: w.scored && w.converged && !w.correct,
                })
                .collect();
            let xr = range(&mut mine.iter().map(|w| w.mu), 1.25);
            let yr = range(
                &mut mine.iter().map(|w| w.tan_alpha).filter(|t| *t > 0.0),
                1.1,
            );
            let stem = out.join(format!("phase_{}", rod.name));
            plot_phase_diagram_labeled(
                &stem,
                &format!(
                    "Stick or slide, rod `{}` (Γ = {:.2e}, E = {:.0e} Pa)",
                    rod.name,
                    mine.first().map_or(f64::NAN, |w| w.gamma),
                    rod.young
                ),
                ("Coulomb coefficient μ", "tan α"),
                (xr, yr),
                &|x, y| Some(y > x),
                &points,
                &[Overlay {
                    label: "tan α = μ".into(),
                    points: vec![
                        (xr.0.min(yr.0), xr.0.min(yr.0)),
                        (xr.1.max(yr.1), xr.1.max(yr.1)),
                    ],
                    dashed: false,
                    color: None,
                }],
                &labels,
            )
            .with_context(|| format!("plotting {}", stem.display()))?;
        }
        let points: Vec<PhasePoint> = r
            .rows
            .iter()
            .filter(|w| w.ratio > 0.0)
            .map(|w| PhasePoint {
                x: w.gamma,
                y: w.ratio,
                phase: phase(w),
                disagrees: w.scored && w.converged && !w.correct,
            })
            .collect();
        let xr = range(&mut r.rows.iter().map(|w| w.gamma), 3.0);
        let yr = range(
            &mut r.rows.iter().map(|w| w.ratio).filter(|t| *t > 0.0),
            1.05,
        );
        let stem = out.join("phase_gamma");
        plot_phase_diagram_labeled(
            &stem,
            "Stick or slide against the rod's Γ (every μ)",
            ("Γ = ρAgL³/EI", "tan α / μ"),
            (xr, yr),
            &|_, y| Some(y > 1.0),
            &points,
            &[Overlay {
                label: "tan α = μ".into(),
                points: vec![(xr.0, 1.0), (xr.1, 1.0)],
                dashed: false,
                color: None,
            }],
            &labels,
        )
        .with_context(|| format!("plotting {}", stem.display()))?;
        print_summary(&summary, cx.stats(SECTION));
        Ok(())
    }

    fn checks(&self, r: &StickSlipRecords, cx: &mut Context) -> Result<Vec<Check>> {
        cx.enter(SECTION);
        Ok(stick_slip_checks(&r.rows))
    }
}

/// Captions of the section's figures.
fn caption(stem: &str) -> String {
    match stem {
        "acceleration" => {
            "The adimensional law of the benchmark: measured a/(g cos α) of every run \
             against tan α − μ, per rod and μ, over Coulomb's a/(g cos α) = max(tan α − μ, 0)."
                .into()
        }
        "acceleration_error" => "Relative error of the fitted acceleration of the runs Coulomb \
             says slide, against tan α / μ (the target applies from tan α = 1.01 μ)."
            .into(),
        "displacement" => "Largest displacement of the centroid over the run, as a fraction of L, \
             against tan α / μ (the target applies up to tan α = 0.99 μ; above, the rod slides)."
            .into(),
        "phase_gamma" => "Stick/slide decisions in the (Γ, tan α/μ) plane for every μ, over \
             Coulomb's law (background) and the line tan α = μ: the threshold does not depend \
             on the rod."
            .into(),
        s if s.starts_with("phase_") => format!(
            "Stick/slide decisions of rod `{}` in the (μ, tan α) plane over Coulomb's law \
             (background) and the line tan α = μ; a ring marks a scored point decided against it.",
            s.trim_start_matches("phase_")
        ),
        s => super::words(s),
    }
}

/// Prints the worst figures per rod set.
fn print_summary(s: &[StickSlipSummary], stats: RunStats) {
    println!(
        "stick-slip runs: {} computed, {} reused from the store",
        stats.computed, stats.reused
    );
    println!(
        "{:<8} {:>10} {:>5} {:>6} {:>16} {:>14} {:>10}",
        "rod", "Γ", "runs", "failed", "stick disp / L", "slide a err", "correct %"
    );
    for r in s {
        println!(
            "{:<8} {:>10.3e} {:>5} {:>6} {:>16.3e} {:>14.3e} {:>10.1}",
            r.rod,
            r.gamma,
            r.runs,
            r.not_converged,
            r.worst_stick_displacement,
            r.worst_slide_error,
            r.correct_percent
        );
    }
}
