//! The shell cantilever's acceptance targets (issue 4), measured against the 1-D heavy
//! elastica (computed in-code by multiple shooting, independently of both models).
//!
//! With ν = 0, D·w = EI exactly and anticlastic curvature costs nothing, so the master curve
//! is the exact reference for the strip (design.md §1.1, §3.3).

use slender_core::rod::Grading;
use slender_core::solver::SolverParams;
use slender_core::ModelError;

use super::acceptance::Check;
use super::master_curve::master_ratio;
use super::shell_case::ShellCantileverCase;
use super::shell_sweep::ShellCantileverRecord;
use super::sweep::log_space;
use crate::materials::OMEGA_COMBINED;

/// Aspect ratio of the acceptance strip.
pub const ACCEPTANCE_WIDTH_RATIO: f64 = 0.1;

/// One measured point of the acceptance sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellErrorPoint {
    /// Elements along the length.
    pub n_length: usize,
    /// Γ_shell.
    pub gamma: f64,
    /// Relative error of Δy/Δx (NaN if the solve did not converge or the master curve failed).
    pub rel_error: f64,
    /// Newton iterations.
    pub iterations: usize,
    /// Wall time (s).
    pub seconds: f64,
}

/// The acceptance case: Ω_combined with ν = 0, w/L = 0.1, n_L × 2 elements, quadratic grading.
pub fn acceptance_case(n_length: usize, gamma: f64) -> ShellCantileverCase {
    ShellCantileverCase {
        material: OMEGA_COMBINED.with_poisson(0.0),
        width_ratio: ACCEPTANCE_WIDTH_RATIO,
        n_length,
        n_width: 2,
        grading: Grading::Power { exponent: 2.0 },
        gamma,
    }
}

impl From<&ShellCantileverRecord> for ShellErrorPoint {
    fn from(r: &ShellCantileverRecord) -> Self {
        Self {
            n_length: r.n_length,
            gamma: r.gamma,
            rel_error: r.rel_error,
            iterations: r.iterations,
            seconds: r.seconds,
        }
    }
}

/// Meshes n_L of the targets: the fine one (within 1 % for Γ ≤ 100), then the coarse one.
const ACCEPTANCE_MESHES: [usize; 2] = [15, 8];

/// Γ of the targets: 13 log-spaced values from 0.1 to 10³.
fn acceptance_gammas() -> Vec<f64> {
    log_space(0.1, 1e3, 13)
}

/// The cases the targets measure, in a fixed order: [`acceptance_case`] at n_L = 15, then
/// n_L = 8, each over Γ ∈ [0.1, 10³] (13 log-spaced values).
pub fn acceptance_cases() -> Vec<ShellCantileverCase> {
    let gammas = acceptance_gammas();
    ACCEPTANCE_MESHES
        .iter()
        .flat_map(|&n| gammas.iter().map(move |&g| acceptance_case(n, g)))
        .collect()
}

/// Relative errors of the acceptance case over `gammas` at `n_length`.
pub fn shell_error_sweep(
    n_length: usize,
    gammas: &[f64],
    params: &SolverParams,
) -> Result<Vec<ShellErrorPoint>, ModelError> {
    gammas
        .iter()
        .map(|&gamma| {
            let run = acceptance_case(n_length, gamma).run(params)?;
            let rel_error = master_ratio(gamma)
                .map(|m| run.ratio / m - 1.0)
                .unwrap_or(f64::NAN);
            Ok(ShellErrorPoint {
                n_length,
                gamma,
                rel_error,
                iterations: run.report.iterations,
                seconds: run.seconds,
            })
        })
        .collect()
}

/// Largest |error| (%) of the points with Γ in [lo, hi]; NaN if one is NaN.
pub fn worst_percent(points: &[ShellErrorPoint], lo: f64, hi: f64) -> f64 {
    let mut worst: f64 = 0.0;
    for p in points
        .iter()
        .filter(|p| p.gamma >= lo * 0.999 && p.gamma <= hi * 1.001)
    {
        if !p.rel_error.is_finite() {
            return f64::NAN;
        }
        worst = worst.max(100.0 * p.rel_error.abs());
    }
    worst
}

fn check(description: String, measured: f64, limit: f64) -> Check {
    Check {
        benchmark: "shell cantilever".into(),
        description,
        measured,
        target: format!("≤ {limit} %"),
        passed: measured.is_finite() && measured <= limit,
    }
}

/// The targets of issue 4 (parts 1–4), each a measurement: n_L = 15 within 1 % for Γ ≤ 100;
/// n_L = 8 within 2 % for Γ ≤ 10³ (and, separately, over the cable range [10, 10³]).
/// Γ runs over 13 log-spaced values from 0.1 to 10³. Computes the cases; see
/// [`checks_from_records`] for records computed elsewhere.
pub fn shell_cantilever_checks(params: &SolverParams) -> Result<Vec<Check>, ModelError> {
    let gammas = acceptance_gammas();
    let fine = shell_error_sweep(ACCEPTANCE_MESHES[0], &gammas, params)?;
    let coarse = shell_error_sweep(ACCEPTANCE_MESHES[1], &gammas, params)?;
    Ok(checks_from_points(&fine, &coarse))
}

/// The targets from the records of [`acceptance_cases`] (any order).
pub fn checks_from_records(records: &[ShellCantileverRecord]) -> Vec<Check> {
    let at = |n: usize| -> Vec<ShellErrorPoint> {
        records
            .iter()
            .filter(|r| r.n_length == n)
            .map(ShellErrorPoint::from)
            .collect()
    };
    checks_from_points(&at(ACCEPTANCE_MESHES[0]), &at(ACCEPTANCE_MESHES[1]))
}

fn checks_from_points(fine: &[ShellErrorPoint], coarse: &[ShellErrorPoint]) -> Vec<Check> {
    let label = "Ω_combined with ν = 0, w/L = 0.1, quadratic grading, exact director clamp";
    vec![
        check(
            format!("{label}, n_L × n_W = 15 × 2: worst |Δy/Δx error| (%) over Γ ∈ [0.1, 100]"),
            worst_percent(fine, 0.1, 100.0),
            1.0,
        ),
        check(
            format!("{label}, n_L × n_W = 8 × 2: worst |Δy/Δx error| (%) over Γ ∈ [0.1, 10³]"),
            worst_percent(coarse, 0.1, 1e3),
            2.0,
        ),
        check(
            format!("{label}, n_L × n_W = 8 × 2: worst |Δy/Δx error| (%) over the cable range Γ ∈ [10, 10³]"),
            worst_percent(coarse, 10.0, 1e3),
            2.0,
        ),
    ]
}
