//! The seed's §5.3 sensitivity study (Fig. 12): how often the perturbation protocol decides
//! 2-D/3-D correctly, as a function of the shell set Ω, the elements along the length n_L,
//! the load steps m_ls and the clamp rotation σ — and of the shell model (mid-edge or C¹
//! B-spline), a factor the seed did not have.
//!
//! This module holds the pure parts — the study's parameters and their validation, the
//! (Γ_shell, w/L) grid placed on the master curve, the verdicts, the scores and their
//! grouping; the protocol runs themselves are [`super::LateralBucklingSweep::protocol_at`].
//!
//! **Ground truth** at (w/L, Γ): 3-D iff Γ > Γ_c(w/L, ν), Γ_c the linear buckling load of
//! the clamped Kirchhoff plate ([`MasterCurve::KirchhoffPlate`]), computed without any shell.
//!
//! **Grid**: at each w/L the points sit at Γ = f·Γ_c for factors f, so the grid straddles
//! the master curve at every aspect ratio whatever ν. The default factors leave out the band
//! f ∈ [0.95, 1.05]: the shell's own Γ_c (Hessian inertia) lies below the plate's by a few
//! per cent at the mesh sizes of the study — at w/L = 0.1, 14.42 at n_L = 30 (−3 %) and 14.04
//! at n_L = 15 (−6 %) against the plate's 14.87 — so within that band a correct model with a
//! correct protocol is right or wrong by mesh error alone: a coin toss that measures the
//! discretization, not the protocol. Outside it, coarse meshes still lose points near the
//! curve (f = 0.93), which is the mesh sensitivity the seed's Fig. 12 shows.
//!
//! **Score** of a configuration: the percentage of correct decisions over the points with
//! w < L. The square strip w = L is scored separately, as the seed does (its Fig. 12 leaves
//! it out). A point whose protocol did not converge is not a decision: it counts as wrong.

use serde::{Deserialize, Serialize};
use thiserror::Error;

use crate::lateral_buckling::{critical_gamma, LateralBucklingError, MasterCurve};
use crate::materials::{ShellMaterialSet, SHELL_SETS};
use crate::shell_model::ShellModel;

/// The seed's decision threshold ε on |y_tip|/L.
pub const DEFAULT_THRESHOLD: f64 = 1e-4;

/// Default Γ/Γ_c factors: three below and three above the master curve, none in the
/// [0.95, 1.05] band where mesh error decides (see the module documentation).
pub const DEFAULT_GAMMA_FACTORS: [f64; 6] = [0.7, 0.85, 0.93, 1.07, 1.2, 1.5];

/// Default aspect ratios w/L of the scored grid (w = L is added by `with_square`).
pub const DEFAULT_WIDTH_RATIOS: [f64; 4] = [0.05, 0.1, 0.2, 0.5];

/// The square strip's aspect ratio, scored separately.
pub const SQUARE: f64 = 1.0;

/// Valid aspect ratios: the plate master curve starts at 0.01, the seed stops at w = L.
pub const WIDTH_RATIO_RANGE: (f64, f64) = (0.01, 1.0);

/// A study input that cannot be run.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum StudyError {
    /// A parameter list or value is invalid; `field` is the [`SensitivityStudy`] field.
    #[error("invalid `{field}`: {reason}")]
    Invalid {
        /// The study field (its CLI flag is the same name with `-` for `_`).
        field: &'static str,
        /// What is wrong and what is valid.
        reason: String,
    },
    /// The master curve could not be evaluated.
    #[error("plate master curve at w/L = {width_ratio}, ν = {poisson}: {source}")]
    MasterCurve {
        /// w/L.
        width_ratio: f64,
        /// Poisson's ratio.
        poisson: f64,
        /// Why.
        source: LateralBucklingError,
    },
}

fn invalid(field: &'static str, reason: impl Into<String>) -> StudyError {
    StudyError::Invalid {
        field,
        reason: reason.into(),
    }
}

/// The shell set called `name` (`shell`, `combined`, `ips`).
pub fn shell_set_by_name(name: &str) -> Result<ShellMaterialSet, StudyError> {
    SHELL_SETS
        .iter()
        .copied()
        .find(|s| s.name == name)
        .ok_or_else(|| {
            invalid(
                "materials",
                format!("unknown set `{name}`; valid: shell, combined, ips"),
            )
        })
}

/// The parameters of the study: every combination of `models` × `materials` × `elements` ×
/// `load_steps` × `sigmas` is one configuration, run over the same (w/L, Γ/Γ_c) grid.
#[derive(Clone, Debug, PartialEq)]
pub struct SensitivityStudy {
    /// Shell models.
    pub models: Vec<ShellModel>,
    /// Shell sets Ω.
    pub materials: Vec<ShellMaterialSet>,
    /// Elements along the length n_L (square elements across).
    pub elements: Vec<usize>,
    /// Load steps m_ls of the protocol.
    pub load_steps: Vec<usize>,
    /// Clamp rotations σ of the protocol (rad).
    pub sigmas: Vec<f64>,
    /// Aspect ratios w/L, each in [0.01, 1]; w = 1 is scored separately.
    pub width_ratios: Vec<f64>,
    /// Γ/Γ_c factors placing the grid on the master curve (> 0).
    pub gamma_factors: Vec<f64>,
    /// Decision threshold ε on |y_tip|/L (> 0).
    pub threshold: f64,
}

impl SensitivityStudy {
    /// The seed's 216 configurations for each shell model (432 in all): Ω ∈ {Ω_shell,
    /// Ω_combined, Ω_IPS}, n_L ∈ {8, 15, 20, 30, 45, 60}, m_ls ∈ {1, 3, 5}, σ ∈ {0.1, 0.2, 0.3,
    /// 0.4}, on the default grid.
    pub fn full() -> Self {
        Self {
            models: ShellModel::ALL.to_vec(),
            materials: ["shell", "combined", "ips"]
                .iter()
                .map(|n| shell_set_by_name(n).expect("built-in set"))
                .collect(),
            elements: vec![8, 15, 20, 30, 45, 60],
            load_steps: vec![1, 3, 5],
            sigmas: vec![0.1, 0.2, 0.3, 0.4],
            width_ratios: DEFAULT_WIDTH_RATIOS.to_vec(),
            gamma_factors: DEFAULT_GAMMA_FACTORS.to_vec(),
            threshold: DEFAULT_THRESHOLD,
        }
    }

    /// A small subset for CI (8 configurations per model, 144 protocol runs each): Ω_shell,
    /// n_L ∈ {8, 15}, m_ls ∈ {1, 5}, σ ∈ {0.1, 0.2}, w/L ∈ {0.05, 0.1, 0.2}.
    pub fn quick() -> Self {
        Self {
            materials: vec![shell_set_by_name("shell").expect("built-in set")],
            elements: vec![8, 15],
            load_steps: vec![1, 5],
            sigmas: vec![0.1, 0.2],
            width_ratios: vec![0.05, 0.1, 0.2],
            ..Self::full()
        }
    }

    /// Adds w = L to the grid (scored separately) unless it is there already.
    pub fn with_square(mut self) -> Self {
        if !self.width_ratios.contains(&SQUARE) {
            self.width_ratios.push(SQUARE);
        }
        self
    }

    /// Checks every list and value; the error names the field and the valid range.
    pub fn validate(&self) -> Result<(), StudyError> {
        non_empty("models", self.models.len())?;
        for (i, m) in self.models.iter().enumerate() {
            if self.models[..i].contains(m) {
                return Err(invalid("models", format!("`{m}` given twice")));
            }
        }
        non_empty("materials", self.materials.len())?;
        for (i, m) in self.materials.iter().enumerate() {
            if self.materials[..i].iter().any(|o| o.name == m.name) {
                return Err(invalid("materials", format!("`{}` given twice", m.name)));
            }
        }
        check_counts("elements", &self.elements)?;
        check_counts("load_steps", &self.load_steps)?;
        check_values("sigmas", &self.sigmas, "finite and > 0 (rad)", |s| {
            s.is_finite() && s > 0.0
        })?;
        let (lo, hi) = WIDTH_RATIO_RANGE;
        check_values(
            "width_ratios",
            &self.width_ratios,
            "in [0.01, 1] (the plate master curve starts at 0.01; the seed stops at w = L)",
            |w| (lo..=hi).contains(&w),
        )?;
        if self.width_ratios.iter().all(|&w| w >= SQUARE) {
            return Err(invalid(
                "width_ratios",
                "needs a value < 1: w = L is not part of the score",
            ));
        }
        check_values(
            "gamma_factors",
            &self.gamma_factors,
            "finite and > 0",
            |f| f.is_finite() && f > 0.0,
        )?;
        if !(self.gamma_factors.iter().any(|&f| f < 1.0)
            && self.gamma_factors.iter().any(|&f| f > 1.0))
        {
            return Err(invalid(
                "gamma_factors",
                "needs a factor < 1 and one > 1, so that the grid has 2-D and 3-D points",
            ));
        }
        if !(self.threshold.is_finite() && self.threshold > 0.0) {
            return Err(invalid(
                "threshold",
                format!("got {}; must be finite and > 0", self.threshold),
            ));
        }
        Ok(())
    }

    /// The configurations, cheapest first: n_L ascending (outermost), then the model, Ω,
    /// m_ls, σ in the order given.
    pub fn configurations(&self) -> Vec<Configuration> {
        let mut elements = self.elements.clone();
        elements.sort_unstable();
        let mut out = Vec::new();
        for &n_length in &elements {
            for &model in &self.models {
                for &material in &self.materials {
                    for &load_steps in &self.load_steps {
                        for &sigma in &self.sigmas {
                            out.push(Configuration {
                                model,
                                material,
                                n_length,
                                load_steps,
                                sigma,
                            });
                        }
                    }
                }
            }
        }
        out
    }

    /// The grid of `material`: for each w/L (ascending), Γ = f·Γ_c(w/L, ν) for each factor.
    pub fn grid(&self, material: &ShellMaterialSet) -> Result<Vec<GridPoint>, StudyError> {
        let mut widths = self.width_ratios.clone();
        widths.sort_by(f64::total_cmp);
        let mut out = Vec::new();
        for w in widths {
            let nu = material.poisson;
            let gamma_c = critical_gamma(w, nu, MasterCurve::KirchhoffPlate).map_err(|e| {
                StudyError::MasterCurve {
                    width_ratio: w,
                    poisson: nu,
                    source: e,
                }
            })?;
            out.extend(self.gamma_factors.iter().map(|&f| GridPoint {
                width_ratio: w,
                gamma_factor: f,
                gamma: f * gamma_c,
                gamma_c,
            }));
        }
        Ok(out)
    }
}

fn non_empty(field: &'static str, len: usize) -> Result<(), StudyError> {
    if len == 0 {
        Err(invalid(field, "is empty; give at least one value"))
    } else {
        Ok(())
    }
}

fn check_counts(field: &'static str, v: &[usize]) -> Result<(), StudyError> {
    non_empty(field, v.len())?;
    if let Some(n) = v.iter().find(|&&n| n == 0) {
        return Err(invalid(field, format!("contains {n}; each must be >= 1")));
    }
    if let Some(n) = v.iter().enumerate().find(|(i, n)| v[..*i].contains(n)) {
        return Err(invalid(field, format!("contains {} twice", n.1)));
    }
    Ok(())
}

fn check_values(
    field: &'static str,
    v: &[f64],
    valid: &str,
    ok: impl Fn(f64) -> bool,
) -> Result<(), StudyError> {
    non_empty(field, v.len())?;
    if let Some(x) = v.iter().find(|&&x| !ok(x)) {
        return Err(invalid(
            field,
            format!("contains {x}; each must be {valid}"),
        ));
    }
    if let Some((_, x)) = v.iter().enumerate().find(|(i, x)| v[..*i].contains(x)) {
        return Err(invalid(field, format!("contains {x} twice")));
    }
    Ok(())
}

/// One configuration of the study (one box-plot sample).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Configuration {
    /// Shell model.
    pub model: ShellModel,
    /// Shell set Ω.
    pub material: ShellMaterialSet,
    /// Elements along the length n_L.
    pub n_length: usize,
    /// Load steps m_ls.
    pub load_steps: usize,
    /// Clamp rotation σ (rad).
    pub sigma: f64,
}

/// One (w/L, Γ) point of the grid and its ground truth.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridPoint {
    /// w/L.
    pub width_ratio: f64,
    /// Γ/Γ_c.
    pub gamma_factor: f64,
    /// Γ_shell = f·Γ_c.
    pub gamma: f64,
    /// Γ_c of the plate master curve at this w/L and the set's ν.
    pub gamma_c: f64,
}

impl GridPoint {
    /// The ground truth: 3-D iff Γ > Γ_c.
    pub fn truth(&self) -> Verdict {
        if self.gamma > self.gamma_c {
            Verdict::ThreeD
        } else {
            Verdict::TwoD
        }
    }
}

/// A 2-D/3-D decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Verdict {
    /// The strip stays in its plane.
    #[serde(rename = "2d")]
    TwoD,
    /// The strip buckles out of its plane.
    #[serde(rename = "3d")]
    ThreeD,
    /// The protocol did not converge: no decision.
    #[serde(rename = "not-converged")]
    NotConverged,
}

/// The protocol's verdict: 3-D iff |y_tip|/L > ε; no decision if any stage did not
/// converge or the deviation is not finite.
pub fn protocol_verdict(tip_deviation: f64, converged: bool, threshold: f64) -> Verdict {
    if !converged || !tip_deviation.is_finite() {
        Verdict::NotConverged
    } else if tip_deviation.abs() > threshold {
        Verdict::ThreeD
    } else {
        Verdict::TwoD
    }
}

/// One scored point, as written to `points.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SensitivityPoint {
    /// Shell model.
    pub model: ShellModel,
    /// Shell set name.
    pub material: String,
    /// n_L.
    pub n_length: usize,
    /// m_ls.
    pub load_steps: usize,
    /// σ (rad).
    pub sigma: f64,
    /// w/L.
    pub width_ratio: f64,
    /// Γ/Γ_c.
    pub gamma_factor: f64,
    /// Γ_shell.
    pub gamma: f64,
    /// Γ_c of the plate master curve.
    pub gamma_c: f64,
    /// y of the free end's centre / L after the protocol.
    pub tip_deviation: f64,
    /// The protocol's verdict.
    pub protocol: Verdict,
    /// The master curve's verdict.
    pub truth: Verdict,
    /// Whether the protocol decided, and decided as the truth.
    pub correct: bool,
    /// Whether every protocol stage converged.
    pub converged: bool,
    /// Relative residual of the final state.
    pub relative_residual: f64,
}

impl SensitivityPoint {
    /// The scored point of `config` at `grid` from the protocol's outcome.
    pub fn new(
        config: &Configuration,
        grid: &GridPoint,
        tip_deviation: f64,
        converged: bool,
        relative_residual: f64,
        threshold: f64,
    ) -> Self {
        let protocol = protocol_verdict(tip_deviation, converged, threshold);
        let truth = grid.truth();
        Self {
            model: config.model,
            material: config.material.name.to_string(),
            n_length: config.n_length,
            load_steps: config.load_steps,
            sigma: config.sigma,
            width_ratio: grid.width_ratio,
            gamma_factor: grid.gamma_factor,
            gamma: grid.gamma,
            gamma_c: grid.gamma_c,
            tip_deviation,
            protocol,
            truth,
            correct: protocol == truth,
            converged,
            relative_residual,
        }
    }
}

/// The score of one configuration, as written to `scores.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConfigurationScore {
    /// Shell model.
    pub model: ShellModel,
    /// Shell set name.
    pub material: String,
    /// n_L.
    pub n_length: usize,
    /// m_ls.
    pub load_steps: usize,
    /// σ (rad).
    pub sigma: f64,
    /// Correct decisions over the points with w < L (%).
    pub score_percent: f64,
    /// Points with w < L.
    pub points: usize,
    /// Points with w < L whose protocol did not converge (counted wrong).
    pub not_converged: usize,
    /// Correct decisions at w = L (%), if computed.
    pub square_score_percent: Option<f64>,
    /// Points at w = L.
    pub square_points: usize,
}

/// Percentage of `correct` points (NaN for none).
fn percent<'a>(points: impl Iterator<Item = &'a SensitivityPoint>) -> (f64, usize) {
    let (n, ok) = points.fold((0usize, 0usize), |(n, ok), p| {
        (n + 1, ok + usize::from(p.correct))
    });
    if n == 0 {
        (f64::NAN, 0)
    } else {
        (100.0 * ok as f64 / n as f64, n)
    }
}

/// The score of `config` from its `points` (the points of other configurations are ignored).
pub fn score(config: &Configuration, points: &[SensitivityPoint]) -> ConfigurationScore {
    let mine: Vec<&SensitivityPoint> = points
        .iter()
        .filter(|p| {
            p.model == config.model
                && p.material == config.material.name
                && p.n_length == config.n_length
                && p.load_steps == config.load_steps
                && p.sigma == config.sigma
        })
        .collect();
    let scored = || mine.iter().copied().filter(|p| p.width_ratio < SQUARE);
    let (score_percent, n) = percent(scored());
    let (square, n_square) = percent(mine.iter().copied().filter(|p| p.width_ratio >= SQUARE));
    ConfigurationScore {
        model: config.model,
        material: config.material.name.to_string(),
        n_length: config.n_length,
        load_steps: config.load_steps,
        sigma: config.sigma,
        score_percent,
        points: n,
        not_converged: scored()
            .filter(|p| p.protocol == Verdict::NotConverged)
            .count(),
        square_score_percent: (n_square > 0).then_some(square),
        square_points: n_square,
    }
}

/// Which parameter a box-plot panel groups by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Grouping {
    /// Shell model.
    Model,
    /// Shell set Ω.
    Material,
    /// n_L.
    Elements,
    /// m_ls.
    LoadSteps,
    /// σ.
    Sigma,
}

impl Grouping {
    /// The shell model, then the four panels of the seed's Fig. 12 in its order.
    pub const ALL: [Grouping; 5] = [
        Grouping::Model,
        Grouping::Material,
        Grouping::Elements,
        Grouping::LoadSteps,
        Grouping::Sigma,
    ];

    /// Axis title.
    pub fn title(self) -> &'static str {
        match self {
            Grouping::Model => "shell model",
            Grouping::Material => "Ω",
            Grouping::Elements => "n_L",
            Grouping::LoadSteps => "m_ls",
            Grouping::Sigma => "σ (rad)",
        }
    }

    /// The group label of a score.
    fn label(self, s: &ConfigurationScore) -> String {
        match self {
            Grouping::Model => s.model.name().to_string(),
            Grouping::Material => s.material.clone(),
            Grouping::Elements => s.n_length.to_string(),
            Grouping::LoadSteps => s.load_steps.to_string(),
            Grouping::Sigma => s.sigma.to_string(),
        }
    }

    /// The group's sort key (the parameter's value; materials keep the study's order).
    fn order(self, s: &ConfigurationScore, study: &SensitivityStudy) -> f64 {
        match self {
            Grouping::Model => study
                .models
                .iter()
                .position(|m| *m == s.model)
                .unwrap_or(usize::MAX) as f64,
            Grouping::Material => study
                .materials
                .iter()
                .position(|m| m.name == s.material)
                .unwrap_or(usize::MAX) as f64,
            Grouping::Elements => s.n_length as f64,
            Grouping::LoadSteps => s.load_steps as f64,
            Grouping::Sigma => s.sigma,
        }
    }
}

/// The scores (w < L) grouped by one parameter: (label, scores) per value of it, in
/// ascending parameter order (materials in the study's order).
pub fn group_scores(
    scores: &[ConfigurationScore],
    by: Grouping,
    study: &SensitivityStudy,
) -> Vec<(String, Vec<f64>)> {
    let mut keys: Vec<(f64, String)> = Vec::new();
    for s in scores {
        let k = (by.order(s, study), by.label(s));
        if !keys.iter().any(|x| x.1 == k.1) {
            keys.push(k);
        }
    }
    keys.sort_by(|a, b| a.0.total_cmp(&b.0));
    keys.into_iter()
        .map(|(_, label)| {
            let v = scores
                .iter()
                .filter(|s| by.label(s) == label)
                .map(|s| s.score_percent)
                .collect();
            (label, v)
        })
        .collect()
}

/// Median of the finite values (mean of the two middle ones for an even count); NaN if none.
pub fn median(values: &[f64]) -> f64 {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// The scores (w < L) of the configurations with one n_L: the seed's headline figures
/// (≈ 70 % at n_L = 8, ≥ 90 % from n_L = 30).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementsSummary {
    /// n_L.
    pub n_length: usize,
    /// Configurations with this n_L.
    pub configurations: usize,
    /// Median score (%).
    pub median: f64,
    /// Lowest score (%).
    pub min: f64,
    /// Highest score (%).
    pub max: f64,
    /// Median score at w = L (%), NaN if w = L was not run.
    pub square_median: f64,
}

/// One [`ElementsSummary`] per n_L, ascending.
pub fn summary_by_elements(scores: &[ConfigurationScore]) -> Vec<ElementsSummary> {
    let mut ns: Vec<usize> = scores.iter().map(|s| s.n_length).collect();
    ns.sort_unstable();
    ns.dedup();
    ns.into_iter()
        .map(|n| {
            let at: Vec<&ConfigurationScore> = scores.iter().filter(|s| s.n_length == n).collect();
            let v: Vec<f64> = at.iter().map(|s| s.score_percent).collect();
            let sq: Vec<f64> = at.iter().filter_map(|s| s.square_score_percent).collect();
            ElementsSummary {
                n_length: n,
                configurations: at.len(),
                median: median(&v),
                min: v.iter().copied().fold(f64::INFINITY, f64::min),
                max: v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                square_median: median(&sq),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config(n_length: usize, sigma: f64) -> Configuration {
        Configuration {
            model: ShellModel::Midedge,
            material: shell_set_by_name("shell").unwrap(),
            n_length,
            load_steps: 1,
            sigma,
        }
    }

    fn grid_point(width_ratio: f64, gamma_factor: f64) -> GridPoint {
        GridPoint {
            width_ratio,
            gamma_factor,
            gamma: gamma_factor * 20.0,
            gamma_c: 20.0,
        }
    }

    #[test]
    fn presets_are_valid_and_the_full_one_is_the_seeds_216() {
        let full = SensitivityStudy::full();
        full.validate().unwrap();
        assert_eq!(full.configurations().len(), 2 * 216);
        let one = SensitivityStudy {
            models: vec![ShellModel::Bspline],
            ..SensitivityStudy::full()
        };
        assert_eq!(one.configurations().len(), 216);
        let quick = SensitivityStudy::quick();
        quick.validate().unwrap();
        assert_eq!(quick.configurations().len(), 2 * 8);
        assert!(DEFAULT_GAMMA_FACTORS
            .iter()
            .all(|f| !(0.95..=1.05).contains(f)));
    }

    #[test]
    fn configurations_run_cheapest_first() {
        let mut s = SensitivityStudy::full();
        s.elements = vec![30, 8, 15];
        let n: Vec<usize> = s.configurations().iter().map(|c| c.n_length).collect();
        assert!(n.windows(2).all(|w| w[0] <= w[1]), "{n:?}");
        assert_eq!(n.first(), Some(&8));
    }

    #[test]
    fn grid_straddles_the_master_curve_at_every_width() {
        let s = SensitivityStudy::full().with_square();
        for m in &s.materials {
            let grid = s.grid(m).unwrap();
            assert_eq!(grid.len(), 5 * 6);
            for &w in &s.width_ratios {
                let at: Vec<&GridPoint> = grid.iter().filter(|p| p.width_ratio == w).collect();
                // Γ_c recomputed here from the master curve, not taken from the grid.
                let gc = critical_gamma(w, m.poisson, MasterCurve::KirchhoffPlate).unwrap();
                assert!(
                    at.iter().any(|p| p.gamma < gc),
                    "nothing below Γ_c at w = {w}"
                );
                assert!(
                    at.iter().any(|p| p.gamma > gc),
                    "nothing above Γ_c at w = {w}"
                );
                for p in at {
                    assert!((p.gamma / gc - p.gamma_factor).abs() < 1e-12);
                    assert_eq!(p.truth() == Verdict::ThreeD, p.gamma > gc);
                }
            }
        }
    }

    #[test]
    fn verdicts_follow_the_threshold_and_convergence() {
        assert_eq!(protocol_verdict(2e-4, true, 1e-4), Verdict::ThreeD);
        assert_eq!(protocol_verdict(-2e-4, true, 1e-4), Verdict::ThreeD);
        assert_eq!(protocol_verdict(5e-5, true, 1e-4), Verdict::TwoD);
        assert_eq!(protocol_verdict(1.0, false, 1e-4), Verdict::NotConverged);
        assert_eq!(
            protocol_verdict(f64::NAN, true, 1e-4),
            Verdict::NotConverged
        );
    }

    #[test]
    fn score_counts_wrong_and_unconverged_points_and_leaves_out_the_square() {
        let c = config(8, 0.1);
        let other = config(15, 0.1);
        let pts = vec![
            // Below Γ_c, stays planar: right.
            SensitivityPoint::new(&c, &grid_point(0.1, 0.8), 1e-6, true, 1e-10, 1e-4),
            // Above Γ_c, buckles: right.
            SensitivityPoint::new(&c, &grid_point(0.1, 1.2), 0.3, true, 1e-10, 1e-4),
            // Above Γ_c, stays planar: wrong.
            SensitivityPoint::new(&c, &grid_point(0.2, 1.2), 1e-6, true, 1e-10, 1e-4),
            // Not converged though its deviation says 3-D as the truth: wrong.
            SensitivityPoint::new(&c, &grid_point(0.2, 1.5), 0.3, false, 1e-3, 1e-4),
            // The square, wrong: not in the score.
            SensitivityPoint::new(&c, &grid_point(1.0, 0.8), 0.3, true, 1e-10, 1e-4),
            // Another configuration, all wrong: ignored.
            SensitivityPoint::new(&other, &grid_point(0.1, 0.8), 0.3, true, 1e-10, 1e-4),
        ];
        assert!(!pts[3].correct);
        let s = score(&c, &pts);
        assert_eq!(s.points, 4);
        assert_eq!(s.score_percent, 50.0);
        assert_eq!(s.not_converged, 1);
        assert_eq!(s.square_points, 1);
        assert_eq!(s.square_score_percent, Some(0.0));
        let o = score(&other, &pts);
        assert_eq!(
            (o.points, o.score_percent, o.square_score_percent),
            (1, 0.0, None)
        );
    }

    #[test]
    fn groups_collect_the_scores_of_each_value() {
        let study = SensitivityStudy::full();
        let mk = |n, sigma, pct| ConfigurationScore {
            model: ShellModel::Midedge,
            material: "shell".into(),
            n_length: n,
            load_steps: 3,
            sigma,
            score_percent: pct,
            points: 10,
            not_converged: 0,
            square_score_percent: None,
            square_points: 0,
        };
        let scores = vec![
            mk(15, 0.2, 90.0),
            mk(8, 0.1, 60.0),
            mk(8, 0.2, 70.0),
            mk(15, 0.1, 100.0),
        ];
        let by_n = group_scores(&scores, Grouping::Elements, &study);
        assert_eq!(
            by_n,
            vec![
                ("8".to_string(), vec![60.0, 70.0]),
                ("15".to_string(), vec![90.0, 100.0])
            ]
        );
        let by_sigma = group_scores(&scores, Grouping::Sigma, &study);
        assert_eq!(by_sigma[0], ("0.1".to_string(), vec![60.0, 100.0]));
        assert_eq!(group_scores(&scores, Grouping::LoadSteps, &study).len(), 1);
        assert_eq!(
            group_scores(&scores, Grouping::Model, &study),
            vec![("midedge".to_string(), vec![90.0, 60.0, 70.0, 100.0])]
        );
        assert_eq!(median(&[60.0, 70.0, 100.0]), 70.0);
        assert_eq!(median(&[60.0, 70.0, 90.0, 100.0]), 80.0);
        assert!(median(&[f64::NAN]).is_nan());
        let summary = summary_by_elements(&scores);
        assert_eq!(summary.len(), 2);
        assert_eq!(
            (
                summary[0].n_length,
                summary[0].configurations,
                summary[0].median
            ),
            (8, 2, 65.0)
        );
        assert_eq!((summary[1].min, summary[1].max), (90.0, 100.0));
        assert!(summary[1].square_median.is_nan());
    }

    #[test]
    fn bad_inputs_name_the_field_and_the_range() {
        let field = |s: SensitivityStudy| match s.validate() {
            Err(StudyError::Invalid { field, reason }) => (field, reason),
            other => panic!("expected an error, got {other:?}"),
        };
        let base = SensitivityStudy::quick;
        assert_eq!(
            field(SensitivityStudy {
                models: vec![],
                ..base()
            })
            .0,
            "models"
        );
        assert_eq!(
            field(SensitivityStudy {
                elements: vec![],
                ..base()
            })
            .0,
            "elements"
        );
        assert_eq!(
            field(SensitivityStudy {
                elements: vec![0],
                ..base()
            })
            .0,
            "elements"
        );
        assert_eq!(
            field(SensitivityStudy {
                load_steps: vec![3, 3],
                ..base()
            })
            .0,
            "load_steps"
        );
        let (f, r) = field(SensitivityStudy {
            sigmas: vec![f64::NAN],
            ..base()
        });
        assert_eq!(f, "sigmas");
        assert!(r.contains("finite"), "{r}");
        let (f, r) = field(SensitivityStudy {
            width_ratios: vec![1.5],
            ..base()
        });
        assert_eq!(f, "width_ratios");
        assert!(r.contains("[0.01, 1]"), "{r}");
        assert_eq!(
            field(SensitivityStudy {
                width_ratios: vec![1.0],
                ..base()
            })
            .0,
            "width_ratios"
        );
        assert_eq!(
            field(SensitivityStudy {
                gamma_factors: vec![-1.0, 2.0],
                ..base()
            })
            .0,
            "gamma_factors"
        );
        assert_eq!(
            field(SensitivityStudy {
                gamma_factors: vec![1.1, 1.2],
                ..base()
            })
            .0,
            "gamma_factors"
        );
        assert_eq!(
            field(SensitivityStudy {
                threshold: 0.0,
                ..base()
            })
            .0,
            "threshold"
        );
        assert!(matches!(
            shell_set_by_name("steel"),
            Err(StudyError::Invalid {
                field: "materials",
                ..
            })
        ));
    }
}
