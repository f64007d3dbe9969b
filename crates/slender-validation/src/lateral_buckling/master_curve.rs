//! The lateral-buckling master curves `Γ_c(w/L; ν)` as a public API for the sweep and the
//! plots: one critical load, a sampler over `w/L`, and all curves at once.
//!
//! `Γ_c` is the critical gravito-bending parameter `Γ_shell = ρhgL³/D` of a strip clamped
//! at `x = 0` with its width `w` along gravity: below it the planar state is stable, above
//! it the strip buckles sideways.

use super::error::{check_poisson_ratio, LateralBucklingError};
use super::plate_buckling::{plate_critical_gamma, PlateDiscretization};
use super::vlasov::{
    critical_lambda_ritz, critical_lambda_shooting, gamma_per_lambda, warping_parameter,
    WeakAxisStiffness, RITZ_ELEMENTS_DEFAULT,
};
use rayon::prelude::*;

/// Which ground truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MasterCurve {
    /// Vlasov beam with weak-axis stiffness `B = E w h³/12` (anticlastic curvature free).
    VlasovBeamStiffness,
    /// Vlasov beam with weak-axis stiffness `B = D w` (anticlastic curvature suppressed).
    VlasovPlateStiffness,
    /// Linear buckling of the clamped Kirchhoff plate (the master curve for shells).
    KirchhoffPlate,
}

impl MasterCurve {
    /// All curves, in plotting order.
    pub const ALL: [MasterCurve; 3] = [
        MasterCurve::KirchhoffPlate,
        MasterCurve::VlasovBeamStiffness,
        MasterCurve::VlasovPlateStiffness,
    ];

    /// Identifier for files and CSV columns.
    pub fn name(self) -> &'static str {
        match self {
            MasterCurve::VlasovBeamStiffness => "vlasov_beam_b",
            MasterCurve::VlasovPlateStiffness => "vlasov_plate_b",
            MasterCurve::KirchhoffPlate => "kirchhoff_plate",
        }
    }

    /// Legend label.
    pub fn label(self) -> &'static str {
        match self {
            MasterCurve::VlasovBeamStiffness => "Vlasov beam, B = E w h³/12",
            MasterCurve::VlasovPlateStiffness => "Vlasov beam, B = D w",
            MasterCurve::KirchhoffPlate => "Kirchhoff plate (linear buckling)",
        }
    }

    /// Valid range of `w/L`: `(0, 4]` for the Vlasov curves, `[0.01, 2]` for the plate.
    pub fn w_over_l_range(self) -> (f64, f64) {
        match self {
            MasterCurve::KirchhoffPlate => (PLATE_W_OVER_L_MIN, PLATE_W_OVER_L_MAX),
            _ => (VLASOV_W_OVER_L_MIN, VLASOV_W_OVER_L_MAX),
        }
    }
}

/// Exclusive lower end of `w/L` for the Vlasov curves: any positive value is accepted
/// (`w/L → 0` is [`narrow_strip_limit`]). Accuracy ~1e-9 relative for `K ≥ 1e-5`
/// (`w/L ≳ 4e-5`), ~1e-5 below.
pub const VLASOV_W_OVER_L_MIN: f64 = 0.0;
/// Largest `w/L` of the Vlasov curves (a beam model means little beyond `w ~ L` anyway).
pub const VLASOV_W_OVER_L_MAX: f64 = 4.0;
/// Smallest `w/L` of the plate curve (its default basis is converged down to here).
pub const PLATE_W_OVER_L_MIN: f64 = 0.01;
/// Largest `w/L` of the plate curve.
pub const PLATE_W_OVER_L_MAX: f64 = 2.0;

fn check_w_over_l(w_over_l: f64, curve: MasterCurve) -> Result<(), LateralBucklingError> {
    let (lo, hi) = curve.w_over_l_range();
    let above_lo = match curve {
        MasterCurve::KirchhoffPlate => w_over_l >= lo,
        _ => w_over_l > lo,
    };
    if !(above_lo && w_over_l <= hi) {
        return Err(LateralBucklingError::InvalidArgument {
            name: "w_over_l (width/length)",
            value: w_over_l,
            range: match curve {
                MasterCurve::KirchhoffPlate => "in [0.01, 2] for the Kirchhoff plate",
                _ => "in (0, 4] for the Vlasov curves",
            },
        });
    }
    Ok(())
}

/// Critical `Γ_shell = ρhgL³/D` at aspect ratio `w_over_l` and Poisson's ratio `nu`.
///
/// Vlasov curves: Hermite Ritz + Richardson (agrees with shooting to ~1e-9; a few ms).
/// Plate: two-stage Legendre Ritz with [`PlateDiscretization::default_for`]
/// (converged to < 0.1 %; 5–100 ms).
///
/// Errors: `nu` NaN or outside `(−1, 0.5)`; `w_over_l` NaN or outside the curve's range
/// ([`MasterCurve::w_over_l_range`]); a solver failure (reported, never hidden).
pub fn critical_gamma(
    w_over_l: f64,
    nu: f64,
    curve: MasterCurve,
) -> Result<f64, LateralBucklingError> {
    check_poisson_ratio(nu)?;
    check_w_over_l(w_over_l, curve)?;
    let vlasov = |stiffness| -> Result<f64, LateralBucklingError> {
        let k = warping_parameter(w_over_l, nu);
        let lambda = critical_lambda_ritz(k, RITZ_ELEMENTS_DEFAULT)?.extrapolated;
        Ok(lambda * gamma_per_lambda(nu, stiffness))
    };
    match curve {
        MasterCurve::VlasovBeamStiffness => vlasov(WeakAxisStiffness::Beam),
        MasterCurve::VlasovPlateStiffness => vlasov(WeakAxisStiffness::Plate),
        MasterCurve::KirchhoffPlate => {
            plate_critical_gamma(w_over_l, nu, &PlateDiscretization::default_for(w_over_l))
        }
    }
}

/// The narrow-strip limit `w/L → 0` of the Vlasov curve with the given weak-axis stiffness:
/// `λ_c(K = 0) · Γ_c/λ_c`, i.e. `12.854 (1−ν) √(2(1+ν))` (beam `B`, also the plate's limit)
/// or `12.854 √(2(1−ν))` (plate `B`, what a rod with lateral stiffness `D w` gives).
/// `λ_c(0)` is computed by shooting.
pub fn narrow_strip_limit(
    nu: f64,
    stiffness: WeakAxisStiffness,
) -> Result<f64, LateralBucklingError> {
    check_poisson_ratio(nu)?;
    Ok(critical_lambda_shooting(0.0)? * gamma_per_lambda(nu, stiffness))
}

/// `(w/L, Γ_c)` at each of `w_over_l` (computed in parallel; each point is independent and
/// deterministic, so the result does not depend on the thread count).
pub fn sample_master_curve(
    curve: MasterCurve,
    nu: f64,
    w_over_l: &[f64],
) -> Result<Vec<(f64, f64)>, LateralBucklingError> {
    w_over_l
        .par_iter()
        .map(|&r| critical_gamma(r, nu, curve).map(|g| (r, g)))
        .collect()
}

/// `n ≥ 2` points `w/L` evenly spaced over `[from, to]` (for plotting).
pub fn linear_samples(from: f64, to: f64, n: usize) -> Vec<f64> {
    let n = n.max(2);
    (0..n)
        .map(|i| from + (to - from) * i as f64 / (n - 1) as f64)
        .collect()
}

/// All master curves of one `ν` on a common grid, for the plots.
#[derive(Clone, Debug, PartialEq)]
pub struct MasterCurves {
    /// Poisson's ratio.
    pub nu: f64,
    /// The `w/L` grid.
    pub w_over_l: Vec<f64>,
    /// `Γ_c` of the Kirchhoff plate at each grid point.
    pub kirchhoff_plate: Vec<f64>,
    /// `Γ_c` of the Vlasov beam with `B = E w h³/12`.
    pub vlasov_beam_stiffness: Vec<f64>,
    /// `Γ_c` of the Vlasov beam with `B = D w`.
    pub vlasov_plate_stiffness: Vec<f64>,
    /// `w/L → 0` limit with `B = E w h³/12` (the plain anisotropic rod's `Γ_c`).
    pub narrow_strip_beam_stiffness: f64,
    /// `w/L → 0` limit with `B = D w`.
    pub narrow_strip_plate_stiffness: f64,
}

/// Computes [`MasterCurves`] at `nu` on the grid `w_over_l` (each value must be valid for
/// the plate, `[0.01, 2]`).
pub fn master_curves(nu: f64, w_over_l: &[f64]) -> Result<MasterCurves, LateralBucklingError> {
    let values = |curve| -> Result<Vec<f64>, LateralBucklingError> {
        Ok(sample_master_curve(curve, nu, w_over_l)?
            .into_iter()
            .map(|(_, g)| g)
            .collect())
    };
    Ok(MasterCurves {
        nu,
        w_over_l: w_over_l.to_vec(),
        kirchhoff_plate: values(MasterCurve::KirchhoffPlate)?,
        vlasov_beam_stiffness: values(MasterCurve::VlasovBeamStiffness)?,
        vlasov_plate_stiffness: values(MasterCurve::VlasovPlateStiffness)?,
        narrow_strip_beam_stiffness: narrow_strip_limit(nu, WeakAxisStiffness::Beam)?,
        narrow_strip_plate_stiffness: narrow_strip_limit(nu, WeakAxisStiffness::Plate)?,
    })
}
