//! The stick–slip sweep: rods of several decades of stiffness and of Γ = ρAgL³/EI, Coulomb
//! coefficients μ, and inclinations placed by the ratio tan α / μ around the threshold 1
//! (dense near it); each point decided stick or slide, scored against Coulomb's law.
//!
//! This module holds the pure parts — the rod sets, the presets, the cases, one scored row
//! per run and the acceptance checks; the runs themselves are [`StickSlipCase::run`].
//!
//! **Ground truth** at (μ, α): stick iff tan α ≤ μ (whatever the rod), slide with
//! a = g (sin α − μ cos α) otherwise. **Scored**: points outside the band
//! |tan α / μ − 1| < [`BAND`]; inside it the points are run and shown, not scored.

use serde::{Deserialize, Serialize};

use super::{StickSlipCase, StickSlipResult};
use crate::cantilever::Check;

/// Half-width of the unscored band around the threshold, in tan α / μ.
pub const BAND: f64 = 0.01;
/// Largest displacement of a sticking rod, as a fraction of its length.
pub const DISPLACEMENT_TARGET: f64 = 1e-9;
/// Largest relative error of a sliding rod's acceleration.
pub const ACCELERATION_TARGET: f64 = 1e-3;
/// Standard gravity (m/s²).
pub const GRAVITY: f64 = 9.81;

/// One rod of the sweep (solid circular section).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct RodSet {
    /// Short name (files, CSV).
    pub name: &'static str,
    /// Length L (m).
    pub length: f64,
    /// Diameter d (m).
    pub diameter: f64,
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
}

impl RodSet {
    /// Γ = ρ A g L³ / (E I) = 16 ρ g L³ / (E d²) for a solid circle.
    pub fn gamma(&self, gravity: f64) -> f64 {
        16.0 * self.density * gravity * self.length.powi(3) / (self.young * self.diameter.powi(2))
    }
}

/// The rod sets: a soft polymer cable (E = 1 MPa, Γ ≈ 6·10³), a stiff polymer rod (1 GPa,
/// Γ ≈ 6) and a steel wire (200 GPa, Γ ≈ 4·10⁻²).
pub const ROD_SETS: [RodSet; 3] = [
    RodSet {
        name: "soft",
        length: 1.0,
        diameter: 0.006,
        young: 1e6,
        density: 1400.0,
    },
    RodSet {
        name: "polymer",
        length: 1.0,
        diameter: 0.006,
        young: 1e9,
        density: 1400.0,
    },
    RodSet {
        name: "steel",
        length: 0.3,
        diameter: 0.002,
        young: 2e11,
        density: 7800.0,
    },
];

/// The rod set called `name`.
pub fn rod_set_by_name(name: &str) -> Option<RodSet> {
    ROD_SETS.iter().copied().find(|r| r.name == name)
}

/// The sweep's parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct StickSlipSweep {
    /// Rods.
    pub rods: Vec<RodSet>,
    /// Coulomb coefficients μ.
    pub mus: Vec<f64>,
    /// tan α / μ.
    pub ratios: Vec<f64>,
    /// Elements along each rod.
    pub elements: usize,
    /// Time step (s).
    pub dt: f64,
    /// Steps per run.
    pub steps: usize,
}

/// One point of the sweep: its rod, ratio and case.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SweepPoint {
    /// The rod.
    pub rod: RodSet,
    /// tan α / μ.
    pub ratio: f64,
    /// The run.
    pub case: StickSlipCase,
}

impl StickSlipSweep {
    /// 3 rods × μ ∈ {0.2, 0.5, 1} × 16 ratios in [0.5, 1.5], down to ±0.5 % of the threshold.
    pub fn quick() -> Self {
        Self {
            rods: ROD_SETS.to_vec(),
            mus: vec![0.2, 0.5, 1.0],
            ratios: vec![
                0.5, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 1.005, 1.01, 1.02, 1.05, 1.1, 1.2, 1.3,
                1.4, 1.5,
            ],
            elements: 20,
            dt: 2e-3,
            steps: 60,
        }
    }

    /// 3 rods × 6 values of μ × 28 ratios, down to ±0.1 % of the threshold.
    pub fn full() -> Self {
        Self {
            mus: vec![0.1, 0.2, 0.3, 0.5, 0.8, 1.0],
            ratios: vec![
                0.5, 0.6, 0.7, 0.8, 0.85, 0.9, 0.93, 0.95, 0.97, 0.98, 0.99, 0.995, 0.999, 1.001,
                1.005, 1.01, 1.02, 1.03, 1.05, 1.07, 1.1, 1.15, 1.2, 1.25, 1.3, 1.35, 1.4, 1.5,
            ],
            ..Self::quick()
        }
    }

    /// Checks the parameters; the message names the field and the valid range.
    pub fn validate(&self) -> Result<(), String> {
        if self.rods.is_empty() {
            return Err("rods: give at least one rod set".into());
        }
        if self.mus.is_empty() || self.mus.iter().any(|m| !(m.is_finite() && *m > 0.0)) {
            return Err(format!("mus: {:?}: give values > 0", self.mus));
        }
        if self.ratios.is_empty() || self.ratios.iter().any(|r| !(r.is_finite() && *r >= 0.0)) {
            return Err(format!("ratios: {:?}: give values >= 0", self.ratios));
        }
        if self.elements < 2 {
            return Err(format!("elements: {}: must be >= 2", self.elements));
        }
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(format!("dt: {}: must be > 0", self.dt));
        }
        if self.steps < 3 {
            return Err(format!(
                "steps: {}: must be >= 3 (the fit needs three samples)",
                self.steps
            ));
        }
        Ok(())
    }

    /// Every point, rod-major, then μ, then ratio.
    pub fn points(&self) -> Vec<SweepPoint> {
        let mut v = Vec::new();
        for rod in &self.rods {
            for &mu in &self.mus {
                for &ratio in &self.ratios {
                    v.push(SweepPoint {
                        rod: *rod,
                        ratio,
                        case: StickSlipCase {
                            mu,
                            alpha: (ratio * mu).atan(),
                            length: rod.length,
                            elements: self.elements,
                            diameter: rod.diameter,
                            young: rod.young,
                            density: rod.density,
                            gravity: GRAVITY,
                            dt: self.dt,
                            steps: self.steps,
                        },
                    });
                }
            }
        }
        v
    }
}

/// Coulomb's decision at tan α / μ = `ratio`: slide iff tan α > μ.
pub fn slides(ratio: f64) -> bool {
    ratio > 1.0
}

/// Whether `ratio` is scored (outside the band around the threshold, bounds included).
pub fn scored(ratio: f64) -> bool {
    (ratio - 1.0).abs() >= BAND * (1.0 - 1e-9)
}

/// One run, scored: a row of `results.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StickSlipRow {
    /// Rod set.
    pub rod: String,
    /// Γ = ρAgL³/EI.
    pub gamma: f64,
    /// E (Pa).
    pub young: f64,
    /// μ.
    pub mu: f64,
    /// tan α / μ.
    pub ratio: f64,
    /// tan α.
    pub tan_alpha: f64,
    /// tan α − μ.
    pub excess: f64,
    /// Outside the band around the threshold.
    pub scored: bool,
    /// Every step converged.
    pub converged: bool,
    /// Coulomb: slide.
    pub expected_slide: bool,
    /// The run: slide (contacts sliding at the end).
    pub slid: bool,
    /// The decision agrees with Coulomb.
    pub correct: bool,
    /// Largest centroid displacement / L.
    pub displacement_over_length: f64,
    /// Measured acceleration (m/s²).
    pub acceleration: f64,
    /// g (sin α − μ cos α), clamped at 0 (m/s²).
    pub exact: f64,
    /// a / (g cos α), measured.
    pub normalized: f64,
    /// |a − exact| / exact where Coulomb says slide, else NaN.
    pub relative_error: f64,
    /// Newton iterations over the run.
    pub iterations: usize,
    /// Why a step failed, if one did.
    pub failure: String,
}

impl StickSlipRow {
    /// The row of `point` run with result `r`.
    pub fn new(point: &SweepPoint, r: &StickSlipResult) -> Self {
        let c = &point.case;
        let expected_slide = slides(point.ratio);
        Self {
            rod: point.rod.name.into(),
            gamma: point.rod.gamma(c.gravity),
            young: c.young,
            mu: c.mu,
            ratio: point.ratio,
            tan_alpha: c.alpha.tan(),
            excess: c.alpha.tan() - c.mu,
            scored: scored(point.ratio),
            converged: r.converged,
            expected_slide,
            slid: r.slid,
            correct: r.converged && r.slid == expected_slide,
            displacement_over_length: r.displacement / c.length,
            acceleration: r.acceleration,
            exact: r.exact,
            normalized: r.acceleration / (c.gravity * c.alpha.cos()),
            relative_error: if expected_slide {
                ((r.acceleration - r.exact) / r.exact).abs()
            } else {
                f64::NAN
            },
            iterations: r.iterations,
            failure: r.failure.clone().unwrap_or_default(),
        }
    }
}

/// Worst figures of one rod set (or of all, `rod = "all"`): a row of `summary.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StickSlipSummary {
    /// Rod set.
    pub rod: String,
    /// Γ.
    pub gamma: f64,
    /// Runs.
    pub runs: usize,
    /// Runs that did not converge.
    pub not_converged: usize,
    /// Largest displacement / L with tan α ≤ (1 − BAND) μ (NaN if a run failed).
    pub worst_stick_displacement: f64,
    /// Largest |a − exact| / exact with tan α ≥ (1 + BAND) μ (NaN if a run failed).
    pub worst_slide_error: f64,
    /// Scored points.
    pub scored: usize,
    /// Correct decisions among them (%).
    pub correct_percent: f64,
}

/// Largest of `values`; NaN if one is NaN or there are none (a failed run fails the check).
fn worst(values: impl Iterator<Item = f64>) -> f64 {
    let mut w = f64::NAN;
    let mut first = true;
    for v in values {
        if v.is_nan() {
            return f64::NAN;
        }
        w = if first { v } else { w.max(v) };
        first = false;
    }
    w
}

/// The summary of `rows` under the name `rod`.
pub fn summarize(rod: &str, rows: &[&StickSlipRow]) -> StickSlipSummary {
    let below = rows.iter().filter(|r| r.scored && !r.expected_slide);
    let above = rows.iter().filter(|r| r.scored && r.expected_slide);
    let scored: Vec<_> = rows.iter().filter(|r| r.scored).collect();
    let correct = scored.iter().filter(|r| r.correct).count();
    let nan_if_failed = |r: &&&StickSlipRow, v: f64| if r.converged { v } else { f64::NAN };
    StickSlipSummary {
        rod: rod.into(),
        gamma: rows.first().map_or(f64::NAN, |r| r.gamma),
        runs: rows.len(),
        not_converged: rows.iter().filter(|r| !r.converged).count(),
        worst_stick_displacement: worst(
            below.map(|r| nan_if_failed(&r, r.displacement_over_length)),
        ),
        worst_slide_error: worst(above.map(|r| nan_if_failed(&r, r.relative_error))),
        scored: scored.len(),
        correct_percent: if scored.is_empty() {
            f64::NAN
        } else {
            100.0 * correct as f64 / scored.len() as f64
        },
    }
}

/// One summary per rod set (in order of first appearance), then `all`.
pub fn summaries(rows: &[StickSlipRow]) -> Vec<StickSlipSummary> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        if !names.contains(&r.rod.as_str()) {
            names.push(&r.rod);
        }
    }
    let mut v: Vec<StickSlipSummary> = names
        .iter()
        .map(|n| summarize(n, &rows.iter().filter(|r| r.rod == *n).collect::<Vec<_>>()))
        .collect();
    let mut all = summarize("all", &rows.iter().collect::<Vec<_>>());
    all.gamma = f64::NAN;
    v.push(all);
    v
}

fn check(description: String, measured: f64, target: &str, passed: bool) -> Check {
    Check {
        benchmark: "stick-slip".into(),
        description,
        measured,
        target: target.into(),
        passed: passed && measured.is_finite(),
    }
}

/// The acceptance checks: every run converged; below the threshold the worst displacement,
/// above it the worst acceleration error; the share of correct decisions outside the band,
/// per rod set.
pub fn stick_slip_checks(rows: &[StickSlipRow]) -> Vec<Check> {
    let s = summaries(rows);
    let all = s.last().expect("the `all` summary");
    let mut v = vec![
        check(
            format!("runs that did not converge (of {})", all.runs),
            all.not_converged as f64,
            "= 0",
            all.not_converged == 0,
        ),
        check(
            format!(
                "worst centroid displacement / L while tan α ≤ {} μ, every rod (Coulomb: 0)",
                1.0 - BAND
            ),
            all.worst_stick_displacement,
            "≤ 1e-9",
            all.worst_stick_displacement <= DISPLACEMENT_TARGET,
        ),
        check(
            format!(
                "worst |a − g(sin α − μ cos α)| / g(sin α − μ cos α) while tan α ≥ {} μ, every rod",
                1.0 + BAND
            ),
            all.worst_slide_error,
            "≤ 1e-3",
            all.worst_slide_error <= ACCELERATION_TARGET,
        ),
    ];
    for r in &s[..s.len() - 1] {
        v.push(check(
            format!(
                "correct stick/slide decisions (%) outside ±{} % of tan α = μ, rod `{}` (Γ = {:.2e}, {} points)",
                100.0 * BAND,
                r.rod,
                r.gamma,
                r.scored
            ),
            r.correct_percent,
            "= 100 %",
            r.correct_percent == 100.0,
        ));
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(
        rod: &str,
        ratio: f64,
        slid: bool,
        disp: f64,
        err: f64,
        converged: bool,
    ) -> StickSlipRow {
        let expected_slide = slides(ratio);
        StickSlipRow {
            rod: rod.into(),
            gamma: 1.0,
            young: 1e9,
            mu: 0.5,
            ratio,
            tan_alpha: 0.5 * ratio,
            excess: 0.5 * ratio - 0.5,
            scored: scored(ratio),
            converged,
            expected_slide,
            slid,
            correct: converged && slid == expected_slide,
            displacement_over_length: disp,
            acceleration: 1.0,
            exact: 1.0,
            normalized: 0.0,
            relative_error: if expected_slide { err } else { f64::NAN },
            iterations: 1,
            failure: String::new(),
        }
    }

    #[test]
    fn the_band_is_left_out_and_its_edges_are_scored() {
        assert!(scored(0.99) && scored(1.01) && scored(0.5));
        assert!(!scored(0.995) && !scored(1.005) && !scored(1.0));
        assert!(!slides(1.0) && slides(1.001));
    }

    #[test]
    fn checks_report_the_worst_figures_and_fail_on_a_wrong_decision() {
        let rows = vec![
            row("a", 0.5, false, 1e-11, 0.0, true),
            row("a", 0.99, false, 3e-11, 0.0, true),
            row("a", 0.995, true, 1e-3, 0.0, true), // in the band: not scored
            row("a", 1.01, true, 1e-4, 2e-7, true),
            row("b", 0.99, false, 5e-11, 0.0, true),
            row("b", 1.5, false, 1e-12, 1.0, true), // stuck above: wrong
        ];
        let c = stick_slip_checks(&rows);
        assert_eq!(c.len(), 5);
        assert!(c[0].passed && c[0].measured == 0.0);
        assert!(c[1].passed && c[1].measured == 5e-11);
        assert!(!c[2].passed && c[2].measured == 1.0);
        assert!(c[3].passed && c[3].measured == 100.0);
        assert!(!c[4].passed && c[4].measured == 50.0);
    }

    #[test]
    fn a_failed_run_fails_every_figure_it_enters() {
        let rows = vec![
            row("a", 0.9, false, 1e-11, 0.0, false),
            row("a", 1.1, true, 1e-4, 1e-6, true),
        ];
        let c = stick_slip_checks(&rows);
        assert!(!c[0].passed && c[0].measured == 1.0);
        assert!(!c[1].passed && c[1].measured.is_nan());
        assert!(c[2].passed);
        assert!(!c[3].passed && c[3].measured == 50.0);
    }

    #[test]
    fn points_cover_rods_mus_and_ratios() {
        let s = StickSlipSweep::quick();
        s.validate().unwrap();
        let p = s.points();
        assert_eq!(p.len(), s.rods.len() * s.mus.len() * s.ratios.len());
        for q in &p {
            assert!((q.case.alpha.tan() / q.case.mu - q.ratio).abs() < 1e-12);
        }
        assert!(StickSlipSweep::full().points().len() > p.len());
        let g: Vec<f64> = ROD_SETS.iter().map(|r| r.gamma(GRAVITY)).collect();
        assert!(g[0] / g[2] > 1e4, "{g:?}");
    }
}
