//! The lateral-buckling sweep of the seed's §5 (Figs. 9–11): Γ_shell × w/L, each point decided
//! 2-D or 3-D by the seed's protocol (free end's y beyond ε·L) and by stability (Γ above the
//! critical Γ_c found by bisection on the Hessian inertia along the planar branch).

use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;
use slender_core::ModelError;

use super::case::LateralBucklingCase;
use super::decisions::is_correct;
use crate::lateral_buckling::{critical_gamma, MasterCurve};
use crate::materials::ShellMaterialSet;
use crate::shell_model::ShellModel;

/// Relative width to which the sweeps bisect Γ_c.
pub const SWEEP_TOLERANCE: f64 = 1e-3;

/// Relative width to which the convergence studies bisect Γ_c: far below the differences
/// between meshes, so that the observed order is not bisection noise.
pub const CONVERGENCE_STUDY_TOLERANCE: f64 = 1e-6;

/// Bracket of the Γ_c bisection (the classical narrow-strip value is ≈ 13.7 for ν = 0.35 and
/// warping restraint at most doubles it for w ≤ L, design.md §1.3).
pub const GAMMA_C_BRACKET: (f64, f64) = (2.0, 200.0);

/// The parameter grid and protocol settings.
#[derive(Clone, Debug, PartialEq)]
pub struct LateralBucklingSweep {
    /// Shell set.
    pub material: ShellMaterialSet,
    /// Shell discretization.
    pub model: ShellModel,
    /// Elements along the length (square elements across).
    pub n_length: usize,
    /// Aspect ratios w/L (> 0).
    pub width_ratios: Vec<f64>,
    /// Γ_shell values (> 0).
    pub gammas: Vec<f64>,
    /// Clamp rotation of the protocol (rad).
    pub sigma: f64,
    /// Load steps m_ls of the protocol (≥ 1).
    pub load_steps: usize,
    /// Decision threshold ε on |y_tip|/L.
    pub threshold: f64,
}

/// The critical Γ of one aspect ratio, as written to `critical.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CriticalRecord {
    /// Shell discretization.
    pub model: ShellModel,
    /// w/L.
    pub width_ratio: f64,
    /// Elements (length × width).
    pub n_length: usize,
    /// Elements across.
    pub n_width: usize,
    /// Γ_c from the inertia (NaN if the bracket failed).
    pub gamma_c: f64,
}

/// One protocol point, as written to `results.csv`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LateralBucklingRecord {
    /// w/L.
    pub width_ratio: f64,
    /// Γ_shell.
    pub gamma: f64,
    /// y of the free end's centre / L after the protocol.
    pub tip_deviation: f64,
    /// Protocol verdict: |tip_deviation| > threshold.
    pub protocol_3d: bool,
    /// Stability verdict: Γ > Γ_c (None if Γ_c is unknown).
    pub stability_3d: Option<bool>,
    /// Γ_c of the master curve (the clamped Kirchhoff plate) at this w/L (NaN if unavailable).
    pub master_gamma_c: f64,
    /// Ground truth: Γ > the master curve's Γ_c (None if unavailable).
    pub truth_3d: Option<bool>,
    /// Whether the protocol's verdict equals the truth (a run that did not converge is never
    /// right; None without a truth).
    pub correct: Option<bool>,
    /// Whether every protocol stage converged.
    pub converged: bool,
    /// Relative residual of the final state.
    pub relative_residual: f64,
}

impl LateralBucklingSweep {
    /// The default grid of the benchmark: 8 aspect ratios w/L ∈ {0.05, 0.1, 0.15, 0.2, 0.3,
    /// 0.5, 0.7, 1} and 15 values of Γ_shell log-spaced over [8, 45] (the master curve runs from
    /// Γ_c ≈ 14 at w/L = 0.05 to 29 at w = L for ν = 0.35), with the seed's protocol σ = 0.2,
    /// m_ls = 5, ε = 1e-4.
    pub fn default_grid(material: ShellMaterialSet, model: ShellModel, n_length: usize) -> Self {
        let (lo, hi, count) = (8.0_f64, 45.0_f64, 15);
        Self {
            material,
            model,
            n_length,
            width_ratios: vec![0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0],
            gammas: (0..count)
                .map(|i| lo * (hi / lo).powf(i as f64 / (count - 1) as f64))
                .collect(),
            sigma: 0.2,
            load_steps: 5,
            threshold: 1e-4,
        }
    }

    /// The master curve's Γ_c (clamped Kirchhoff plate, the material's ν) at every aspect
    /// ratio, as (w/L, Γ_c); NaN where the curve is not available.
    pub fn master_critical(&self) -> Vec<(f64, f64)> {
        self.width_ratios
            .iter()
            .map(|&w| {
                let g = critical_gamma(w, self.material.poisson, MasterCurve::KirchhoffPlate)
                    .unwrap_or(f64::NAN);
                (w, g)
            })
            .collect()
    }

    fn case(&self, width_ratio: f64) -> LateralBucklingCase {
        LateralBucklingCase {
            material: self.material,
            width_ratio,
            n_length: self.n_length,
            model: self.model,
        }
    }

    /// Γ_c at one aspect ratio (bisection on the inertia to [`SWEEP_TOLERANCE`]).
    pub fn critical_at(
        &self,
        width_ratio: f64,
        params: &SolverParams,
    ) -> Result<CriticalRecord, ModelError> {
        critical_record(
            self.material,
            self.model,
            width_ratio,
            self.n_length,
            SWEEP_TOLERANCE,
            params,
        )
    }

    /// Γ_c for every aspect ratio, in parallel.
    pub fn critical(&self, params: &SolverParams) -> Result<Vec<CriticalRecord>, ModelError> {
        self.width_ratios
            .par_iter()
            .map(|&w| self.critical_at(w, params))
            .collect()
    }

    /// The (w/L, Γ) points of the protocol in their fixed order (w/L outer).
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.width_ratios
            .iter()
            .flat_map(|&w| self.gammas.iter().map(move |&g| (w, g)))
            .collect()
    }

    /// Runs the protocol at one point (independent of the threshold and of Γ_c).
    pub fn protocol_at(
        &self,
        width_ratio: f64,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<ProtocolPoint, ModelError> {
        if self.load_steps == 0 {
            return Err(ModelError::structure(
                "load_steps",
                "got 0; need at least 1",
            ));
        }
        let out = self
            .case(width_ratio)
            .protocol(gamma, self.sigma, self.load_steps, params)?;
        Ok(ProtocolPoint {
            tip_deviation: out.tip_deviation,
            converged: out.converged,
            relative_residual: out.report.relative_residual,
        })
    }

    /// The record of a protocol point: its verdict by the threshold, by Γ_c of `critical`
    /// (the shell's own stability) and by the master curve `master` (from
    /// [`master_critical`](Self::master_critical)).
    pub fn record(
        &self,
        (width_ratio, gamma): (f64, f64),
        point: &ProtocolPoint,
        critical: &[CriticalRecord],
        master: &[(f64, f64)],
    ) -> LateralBucklingRecord {
        let master_gamma_c = master
            .iter()
            .find(|m| m.0 == width_ratio)
            .map_or(f64::NAN, |m| m.1);
        let truth_3d = master_gamma_c.is_finite().then_some(gamma > master_gamma_c);
        let gc = critical
            .iter()
            .find(|c| c.width_ratio == width_ratio)
            .map(|c| c.gamma_c)
            .filter(|x| x.is_finite());
        let mut r = LateralBucklingRecord {
            width_ratio,
            gamma,
            tip_deviation: point.tip_deviation,
            protocol_3d: point.tip_deviation.abs() > self.threshold,
            stability_3d: gc.map(|c| gamma > c),
            master_gamma_c,
            truth_3d,
            correct: None,
            converged: point.converged,
            relative_residual: point.relative_residual,
        };
        r.correct = is_correct(&r);
        r
    }

    /// Runs the protocol at every (w/L, Γ) and compares with `critical` and the master curve;
    /// records in (w/L, Γ) order whatever the thread count. `progress` is called once per point.
    pub fn run(
        &self,
        critical: &[CriticalRecord],
        params: &SolverParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<LateralBucklingRecord>, ModelError> {
        let master = self.master_critical();
        self.points()
            .par_iter()
            .map(|&wg| {
                let point = self.protocol_at(wg.0, wg.1, params)?;
                progress();
                Ok(self.record(wg, &point, critical, &master))
            })
            .collect()
    }
}

/// Γ_c of `material` with the `model` discretization at `width_ratio` on the mesh with
/// `n_length` elements along the length (square elements), by bisection on the inertia within
/// [`GAMMA_C_BRACKET`] to relative width `tolerance`.
pub fn critical_record(
    material: ShellMaterialSet,
    model: ShellModel,
    width_ratio: f64,
    n_length: usize,
    tolerance: f64,
    params: &SolverParams,
) -> Result<CriticalRecord, ModelError> {
    let c = LateralBucklingCase {
        material,
        width_ratio,
        n_length,
        model,
    };
    let gc = c
        .critical_gamma(GAMMA_C_BRACKET.0, GAMMA_C_BRACKET.1, tolerance, params)?
        .unwrap_or(f64::NAN);
    Ok(CriticalRecord {
        model,
        width_ratio,
        n_length,
        n_width: c.n_width(),
        gamma_c: gc,
    })
}

/// What the protocol measured at one point (the part of a record that costs a solve).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProtocolPoint {
    /// y of the free end's centre / L after the protocol.
    pub tip_deviation: f64,
    /// Whether every protocol stage converged.
    pub converged: bool,
    /// Relative residual of the final state.
    pub relative_residual: f64,
}
