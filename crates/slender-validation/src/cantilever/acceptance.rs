//! The cantilever benchmark's acceptance targets (issue 2), measured.
//!
//! Each check is a measurement against a target; a failed check is reported with its figure,
//! never bent to pass.

use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;

use super::case::{CantileverCase, MeshKind};
use super::sweep::{run_case, CantileverRecord, SweepError};
use crate::materials::{OMEGA_BUNDLE, OMEGA_ROD};

/// One acceptance target and what was measured.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Check {
    /// Benchmark the check belongs to.
    pub benchmark: String,
    /// What is checked.
    pub description: String,
    /// The measured figure.
    pub measured: f64,
    /// The target, as text (e.g. "≤ 0.5 %").
    pub target: String,
    /// Whether the measured figure meets the target.
    pub passed: bool,
}

fn check(description: String, measured: f64, target: &str, passed: bool) -> Check {
    Check {
        benchmark: "cantilever".into(),
        description,
        measured,
        target: target.into(),
        passed: passed && measured.is_finite(),
    }
}

/// Largest |relative error| (%) of the records matching the filter; NaN if one did not
/// converge (which fails the check) or none matched.
fn worst_percent(records: &[CantileverRecord], keep: impl Fn(&CantileverRecord) -> bool) -> f64 {
    let mut worst = f64::NAN;
    for r in records.iter().filter(|r| keep(r)) {
        if !r.converged {
            return f64::NAN;
        }
        let e = 100.0 * r.rel_error.abs();
        worst = if worst.is_nan() { e } else { worst.max(e) };
    }
    worst
}

/// Element counts of the convergence-order check (Ω_rod, graded mesh).
const ORDER_MESHES: [usize; 4] = [10, 20, 40, 80];
/// Γ values of the convergence-order check.
const ORDER_GAMMAS: [f64; 2] = [1.0, 100.0];
/// The smallest Γ checked (no plateau of the error from an absolute tolerance).
const SMALL_GAMMA: f64 = 1e-3;

fn graded(material: crate::materials::RodMaterialSet, n: usize, gamma: f64) -> CantileverCase {
    CantileverCase {
        material,
        mesh: MeshKind::Graded,
        n_elements: n,
        gamma,
    }
}

/// The cases the targets need beyond the sweep, in a fixed order: Ω_rod on the graded mesh
/// at N = 10, 20, 40, 80 for Γ = 1 and 100 (order of convergence), then Ω_rod and Ω_bundle
/// at N = 20, Γ = 10⁻³.
pub fn check_cases() -> Vec<CantileverCase> {
    let mut cases: Vec<CantileverCase> = ORDER_GAMMAS
        .iter()
        .flat_map(|&gamma| {
            ORDER_MESHES
                .iter()
                .map(move |&n| graded(OMEGA_ROD, n, gamma))
        })
        .collect();
    cases.push(graded(OMEGA_ROD, 20, SMALL_GAMMA));
    cases.push(graded(OMEGA_BUNDLE, 20, SMALL_GAMMA));
    cases
}

/// Relative error of the record of `case` among `extra` (NaN if it is missing).
fn extra_error(extra: &[CantileverRecord], case: &CantileverCase) -> f64 {
    extra
        .iter()
        .find(|r| {
            r.material == case.material.name
                && r.mesh == case.mesh.name()
                && r.n_elements == case.n_elements
                && r.gamma == case.gamma
        })
        .map_or(f64::NAN, |r| r.rel_error)
}

/// Least-squares slope of log|error| against log N.
pub fn convergence_slope(ns: &[usize], errors: &[f64]) -> f64 {
    let xs: Vec<f64> = ns.iter().map(|&n| (n as f64).ln()).collect();
    let ys: Vec<f64> = errors.iter().map(|e| e.abs().ln()).collect();
    let k = xs.len() as f64;
    let mx = xs.iter().sum::<f64>() / k;
    let my = ys.iter().sum::<f64>() / k;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

/// Evaluates the targets on the sweep `records` (which should include Ω_rod and Ω_bundle on
/// the graded mesh with N = 5, 20, 50) plus a few extra runs (convergence order, Γ = 10⁻³),
/// computed here; see [`checks_from_records`] for records computed elsewhere.
pub fn cantilever_checks(
    records: &[CantileverRecord],
    params: &SolverParams,
) -> Result<Vec<Check>, SweepError> {
    let extra = check_cases()
        .iter()
        .map(|case| run_case(case, params))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(checks_from_records(records, &extra))
}

/// The targets from the sweep `records` and the records `extra` of [`check_cases`].
pub fn checks_from_records(records: &[CantileverRecord], extra: &[CantileverRecord]) -> Vec<Check> {
    // (material, N, Γ range, limit %, description): worst relative error on the graded mesh.
    let worst_error_targets = [
        ("rod", 20, (0.1, 1e4), 0.5, "Ω_rod, graded, N = 20: worst |Δy/Δx error| (%) over Γ ∈ [0.1, 10⁴]"),
        ("rod", 50, (0.0, 100.0), 0.1, "Ω_rod, graded, N = 50: worst error (%) over Γ ≤ 100"),
        ("rod", 5, (10.0, 1e3), 3.0, "Ω_rod, graded, N = 5: worst error (%) over Γ ∈ [10, 10³]"),
        ("bundle", 50, (0.0, 1e3), 0.5, "Ω_bundle (finite EA), graded, N = 50: worst error (%) vs the inextensible curve, Γ ≤ 10³"),
    ];
    let mut checks = Vec::new();
    for (material, n, (lo, hi), limit, description) in worst_error_targets {
        let w = worst_percent(records, |r| {
            r.material == material
                && r.mesh == "graded"
                && r.n_elements == n
                && r.gamma >= lo * 0.999
                && r.gamma <= hi * 1.001
        });
        checks.push(check(
            description.into(),
            w,
            &format!("≤ {limit} %"),
            w <= limit,
        ));
    }
    for gamma in ORDER_GAMMAS {
        let errors: Vec<f64> = ORDER_MESHES
            .iter()
            .map(|&n| extra_error(extra, &graded(OMEGA_ROD, n, gamma)))
            .collect();
        let slope = convergence_slope(&ORDER_MESHES, &errors);
        checks.push(check(
            format!("Ω_rod, graded: order of convergence, slope of log|error| vs log N (N = 10…80), Γ = {gamma}"),
            slope,
            "≤ −1.8",
            slope <= -1.8,
        ));
    }
    let e = 100.0 * extra_error(extra, &graded(OMEGA_ROD, 20, SMALL_GAMMA)).abs();
    checks.push(check(
        "Ω_rod, graded, N = 20: error (%) at Γ = 10⁻³ (no plateau from an absolute tolerance)"
            .into(),
        e,
        "≤ 0.5 %",
        e <= 0.5,
    ));
    let e = 100.0 * extra_error(extra, &graded(OMEGA_BUNDLE, 20, SMALL_GAMMA)).abs();
    checks.push(check(
        "Ω_bundle, graded, N = 20: error (%) at Γ = 10⁻³".into(),
        e,
        "≤ 0.5 %",
        e <= 0.5,
    ));
    let failed = records.iter().filter(|r| !r.converged).count();
    let multi = records
        .iter()
        .filter(|r| r.converged && r.load_steps > 1)
        .count();
    checks.push(check(
        format!("sweep: solves that did not converge in one call ({} cases; {multi} needed more than one load step, chosen by the solver)", records.len()),
        failed as f64,
        "= 0",
        failed == 0,
    ));
    checks
}
