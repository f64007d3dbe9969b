//! Self-checks of the lateral-buckling ground truth, as acceptance rows for
//! `slender validate`: the master curves are only worth scoring a shell against if their
//! independent methods agree and they reproduce the classical and documented values.
//!
//! Each row is a measurement against a target; a miss is reported with its figure.
//! Cost: about 2 s on one core.

use super::error::LateralBucklingError;
use super::master_curve::{critical_gamma, narrow_strip_limit, MasterCurve};
use super::plate_buckling::{
    buckling_multiplier, plate_critical_gamma, PlateDiscretization, TensorOrders,
};
use super::vlasov::{
    critical_lambda_ritz, critical_lambda_shooting, WeakAxisStiffness, RITZ_ELEMENTS_DEFAULT,
};
use crate::cantilever::Check;

const BENCHMARK: &str = "lateral-buckling master curve";

fn check(description: &str, measured: f64, target: &str, passed: bool) -> Check {
    Check {
        benchmark: BENCHMARK.into(),
        description: description.into(),
        measured,
        target: target.into(),
        passed: passed && measured.is_finite(),
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// design.md §1.3, ν = 0.35: `(w/L, Γ_c beam B, Γ_c plate B)`, two decimals.
const DESIGN_GAMMA_NU_035: [(f64, f64, f64); 8] = [
    (0.02, 13.93, 14.87),
    (0.05, 14.24, 15.20),
    (0.1, 14.79, 15.79),
    (0.2, 15.98, 17.06),
    (0.3, 17.25, 18.42),
    (0.5, 19.95, 21.30),
    (0.75, 23.49, 25.07),
    (1.0, 27.08, 28.90),
];

/// The acceptance rows (see the module docs). Errors only if a solver fails outright.
pub fn master_curve_checks() -> Result<Vec<Check>, LateralBucklingError> {
    let mut checks = Vec::new();

    // 1. Classical value without warping (Timoshenko & Gere 12.85; design.md 12.8538).
    let lambda0 = critical_lambda_shooting(0.0)?;
    checks.push(check(
        "Vlasov K = 0: |λ_c − 12.8538| (shooting)",
        (lambda0 - 12.8538).abs(),
        "≤ 5e-5",
        (lambda0 - 12.8538).abs() <= 5e-5,
    ));

    // 2. The two independent Vlasov methods.
    let mut worst: f64 = 0.0;
    for k in [0.0, 0.05, 0.2, 0.5, 1.0] {
        let shoot = critical_lambda_shooting(k)?;
        let ritz = critical_lambda_ritz(k, RITZ_ELEMENTS_DEFAULT)?.extrapolated;
        worst = worst.max(rel(ritz, shoot));
    }
    checks.push(check(
        "Vlasov λ_c: shooting vs Hermite Ritz, max relative difference over K ∈ [0, 1]",
        worst,
        "≤ 1e-8",
        worst <= 1e-8,
    ));

    // 3. design.md's Γ_c table (ν = 0.35), both stiffness conventions.
    let mut worst: f64 = 0.0;
    for (r, beam, plate) in DESIGN_GAMMA_NU_035 {
        let gb = critical_gamma(r, 0.35, MasterCurve::VlasovBeamStiffness)?;
        let gp = critical_gamma(r, 0.35, MasterCurve::VlasovPlateStiffness)?;
        worst = worst.max((gb - beam).abs()).max((gp - plate).abs());
    }
    checks.push(check(
        "Vlasov Γ_c (ν = 0.35) vs design.md §1.3 table, max |difference|",
        worst,
        "≤ 0.005 (half the printed digit)",
        worst <= 0.005,
    ));

    // 4. Plate convergence of the default bases.
    let mut worst: f64 = 0.0;
    for r in [0.01, 0.05, 0.2, 0.5, 1.0] {
        let disc = PlateDiscretization::default_for(r);
        let g = plate_critical_gamma(r, 0.35, &disc)?;
        let g_rich = plate_critical_gamma(r, 0.35, &disc.refined(8))?;
        worst = worst.max(rel(g, g_rich));
    }
    checks.push(check(
        "Kirchhoff plate Γ_c: default basis vs 8 more orders, max relative change (w/L ∈ [0.01, 1])",
        worst,
        "≤ 5e-3",
        worst <= 5e-3,
    ));

    // 5. Exact plate reference: ν = 0 cantilever plate under uniform compression, π²/4.
    let uniform = |xs: &[f64], zs: &[f64]| vec![[-1.0, 0.0, 0.0]; xs.len() * zs.len()];
    let orders = TensorOrders {
        along_length: 14,
        across_width: 6,
    };
    let field = TensorOrders {
        along_length: 2,
        across_width: 2,
    };
    let euler = buckling_multiplier(1.0, 0.0, orders, field, uniform)?;
    let e = rel(euler, std::f64::consts::PI.powi(2) / 4.0);
    checks.push(check(
        "Kirchhoff plate, ν = 0, uniform compression: relative error vs π²/4",
        e,
        "≤ 1e-8",
        e <= 1e-8,
    ));

    // 6. Narrow-strip limit: linear extrapolation of the plate from w/L = 0.01, 0.02.
    let limit = narrow_strip_limit(0.35, WeakAxisStiffness::Beam)?;
    let g1 = critical_gamma(0.01, 0.35, MasterCurve::KirchhoffPlate)?;
    let g2 = critical_gamma(0.02, 0.35, MasterCurve::KirchhoffPlate)?;
    let e = rel(2.0 * g1 - g2, limit);
    checks.push(check(
        "Kirchhoff plate (ν = 0.35): w/L → 0 extrapolation vs 12.854(1−ν)√(2(1+ν))",
        e,
        "≤ 1e-3",
        e <= 1e-3,
    ));

    // 7. Plate inside the Vlasov band for w/L ≤ 0.5 (largest excursion outside, relative).
    let mut excursion = f64::NEG_INFINITY;
    for r in [0.05, 0.1, 0.2, 0.3, 0.5] {
        let p = critical_gamma(r, 0.35, MasterCurve::KirchhoffPlate)?;
        let b = critical_gamma(r, 0.35, MasterCurve::VlasovBeamStiffness)?;
        let d = critical_gamma(r, 0.35, MasterCurve::VlasovPlateStiffness)?;
        excursion = excursion.max((b - p) / b).max((p - d) / d);
    }
    checks.push(check(
        "Kirchhoff plate within the Vlasov band for w/L ≤ 0.5 (largest relative excursion past an edge; < 0 = inside by that margin)",
        excursion,
        "≤ 0",
        excursion <= 0.0,
    ));
    Ok(checks)
}
