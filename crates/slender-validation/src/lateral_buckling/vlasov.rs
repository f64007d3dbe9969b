//! Lateral–torsional buckling of a heavy cantilever strip with warping (Vlasov) stiffness.
//!
//! # The eigenproblem
//!
//! A cantilever of length `L` carries the uniform load `q` per length at the centroid, in
//! its stiff plane. The strong-axis moment is `M(s) = q (L − s)²/2`. A lateral deflection
//! `v(s)` with twist `φ(s)` has the second variation (Timoshenko & Gere §6.3 with warping)
//!
//! ```text
//! Π₂ = ½ ∫ [ B v''² + C φ'² + C_w φ''² + 2 M φ v'' ] ds,
//! ```
//!
//! `B` the weak-axis bending stiffness, `C = GJ`, `C_w` the warping stiffness. Clamped at
//! `s = 0` (`v = v' = 0`) `v''` is free, so minimising pointwise gives `B v'' = −M φ` and
//! the reduced form, with `ŝ = s/L`,
//!
//! ```text
//! Π₂ = (C/2L) ∫₀¹ [ K² φ''² + φ'² − (λ²/4)(1 − ŝ)⁴ φ² ] dŝ,
//! K² = C_w/(C L²),   λ = q L³/√(B C).
//! ```
//!
//! Its Euler–Lagrange equation and boundary terms (integrate `K²φ''δφ''` twice and
//! `φ'δφ'` once by parts):
//!
//! ```text
//! K² φ'''' − φ'' − (λ²/4)(1 − ŝ)⁴ φ = 0,
//! [K² φ'' δφ']₀¹ + [(φ' − K² φ''') δφ]₀¹ = 0.
//! ```
//!
//! At the clamp `φ = φ' = 0` (twist and warping restrained, so `δφ = δφ' = 0`); at the
//! free end `δφ`, `δφ'` are arbitrary, giving the natural conditions `φ'' = 0` (no
//! bimoment) and `φ' − K² φ''' = 0` (no torque). For `K = 0` the problem drops to
//! `φ'' + (λ²/4)(1 − ŝ)⁴ φ = 0`, `φ(0) = 0`, `φ'(1) = 0`, whose first eigenvalue is the
//! classical `λ_c = 12.85` (Timoshenko & Gere).
//!
//! # Two independent methods
//!
//! * [`critical_lambda_shooting`]: initial-value shooting from the clamp with the
//!   hand-written DOPRI5 ([`crate::ode`]) and a scan + bisection on the sign of the
//!   boundary determinant at the free end. For `K > 0` the two clamp solutions grow like
//!   `e^{ŝ/K}` and a plain 2×2 determinant would cancel catastrophically, so the
//!   *compound-matrix* method integrates the six Plücker coordinates `p_ij = u_i v_j − u_j v_i`
//!   of the two-dimensional solution space directly (Ng & Reid 1979); the determinant is
//!   linear in them. Segments of length `≤ 20 K` are renormalised (a positive factor,
//!   which keeps the sign).
//! * [`critical_lambda_ritz`]: Rayleigh–Ritz on the energy with C¹ cubic Hermite elements
//!   (exact Gauss integration, mesh graded to the clamp boundary layer of width `~K`), a
//!   generalised symmetric eigen-solve, and Richardson extrapolation in `h⁴`.
//!
//! # Conversion to Γ_shell
//!
//! For a thin strip of width `w` (along gravity) and thickness `h`: `q = ρ g h w`,
//! `C = G w h³/3 = E w h³/(6(1+ν))`, `C_w = E w³ h³/144`, so `K = √((1+ν)/24) · w/L`.
//! With `Γ_shell = ρ h g L³/D`, `D = E h³/(12(1−ν²))`, we have `q L³ = Γ D w` and
//! `λ = Γ D w/√(B C)`:
//!
//! * `B = E w h³/12` (beam, anticlastic curvature free): `√(BC) = E w h³/(6√2 √(1+ν))`,
//!   `λ = Γ/(√2 (1−ν) √(1+ν))`, so `Γ_c = λ_c · √2 (1−ν) √(1+ν)`;
//! * `B = D w` (plate, anticlastic curvature suppressed): `√(BC) = E w h³/(6√2 √(1−ν) (1+ν))`,
//!   `λ = Γ/√(2(1−ν))`, so `Γ_c = λ_c · √(2(1−ν))`.

use super::error::LateralBucklingError;
use super::generalized_eigen::largest_pencil_eigenvalue;
use super::legendre::gauss_legendre;
use crate::numerics::{bisect_sign, Bisection};
use crate::ode::{self, Options};
use faer::Mat;

/// Which weak-axis bending stiffness `B` the strip is given.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WeakAxisStiffness {
    /// `B = E w h³/12`: beam, anticlastic curvature free (narrow strips).
    Beam,
    /// `B = D w = E w h³/(12(1−ν²))`: plate, anticlastic curvature suppressed (wide strips).
    Plate,
}

/// Warping parameter `K = √(C_w/(C L²)) = √((1+ν)/24) · w/L` of a thin strip
/// (dimensionless).
pub fn warping_parameter(w_over_l: f64, nu: f64) -> f64 {
    ((1.0 + nu) / 24.0).sqrt() * w_over_l
}

/// Factor `Γ_c/λ_c` that converts the Vlasov load `λ = qL³/√(BC)` into the shell's
/// gravito-bending parameter `Γ_shell = ρhgL³/D` (derivation in the module docs).
pub fn gamma_per_lambda(nu: f64, stiffness: WeakAxisStiffness) -> f64 {
    match stiffness {
        WeakAxisStiffness::Beam => std::f64::consts::SQRT_2 * (1.0 - nu) * (1.0 + nu).sqrt(),
        WeakAxisStiffness::Plate => (2.0 * (1.0 - nu)).sqrt(),
    }
}

/// Largest warping parameter the solvers accept (`w/L ≈ 8` at ν = 0.5; far beyond where a
/// beam model means anything).
pub const K_MAX: f64 = 2.0;
/// Smallest positive warping parameter the shooting method accepts: its explicit steps
/// scale like `1/K` (9 s at `K = 1e-4`). The Ritz method accepts any `K ∈ [0, K_MAX]`.
pub const K_MIN_POSITIVE_SHOOTING: f64 = 1e-4;

fn invalid_k(k: f64, range: &'static str) -> LateralBucklingError {
    LateralBucklingError::InvalidArgument {
        name: "k (warping parameter)",
        value: k,
        range,
    }
}

fn check_k_shooting(k: f64) -> Result<(), LateralBucklingError> {
    if k == 0.0 || (K_MIN_POSITIVE_SHOOTING..=K_MAX).contains(&k) {
        Ok(())
    } else {
        Err(invalid_k(k, "0 or in [1e-4, 2] for the shooting method"))
    }
}

fn check_k_ritz(k: f64) -> Result<(), LateralBucklingError> {
    if (0.0..=K_MAX).contains(&k) {
        Ok(())
    } else {
        Err(invalid_k(k, "in [0, 2] for the Ritz method"))
    }
}

// ---------------------------------------------------------------------------------------
// Shooting (compound matrix)
// ---------------------------------------------------------------------------------------

/// Relative tolerance of the shooting integration.
const SHOOTING_RTOL: f64 = 1e-12;
/// Absolute tolerance (the state is renormalised to max-norm 1 at each segment start).
const SHOOTING_ATOL: f64 = 1e-15;
/// Longest segment between renormalisations, in units of `K` (growth ≤ e²⁰ per segment).
const SEGMENT_LENGTH_IN_K: f64 = 20.0;
/// First load of the scan; `λ_c(K) ≥ λ_c(0) ≈ 12.85` since warping only adds stiffness.
const SCAN_START: f64 = 4.0;
/// Ratio of successive scan loads. The second eigenvalue is several times the first, so
/// a 4 % step cannot jump over two sign changes.
const SCAN_RATIO: f64 = 1.04;
/// Where the scan gives up.
const SCAN_MAX: f64 = 1e4;
/// Bisection stops when the bracket is this small relative to λ.
const BISECTION_RTOL: f64 = 1e-13;

/// Boundary determinant at the free end for load `λ`; its sign changes at each eigenvalue.
///
/// `K = 0`: `φ'(1)` of the solution with `φ(0) = 0`, `φ'(0) = 1`.
/// `K > 0`: with `u`, `v` the solutions started at the clamp with `(φ, φ', φ'', φ''') =
/// (0,0,1,0)` and `(0,0,0,1)`, the free-end conditions `φ'' = 0`, `φ' − K²φ''' = 0` have a
/// nontrivial combination iff `det [[u₃, v₃], [u₂ − K²u₄, v₂ − K²v₄]] = −p₂₃ − K² p₃₄ = 0`.
pub fn shooting_determinant(k: f64, lambda: f64) -> Result<f64, LateralBucklingError> {
    check_k_shooting(k)?;
    let mu = 0.25 * lambda * lambda;
    let opts = Options::with_tolerances(SHOOTING_RTOL, SHOOTING_ATOL);
    let ode_err = |source| LateralBucklingError::Ode { lambda, source };
    if k == 0.0 {
        let rhs = |s: f64, y: &[f64; 2]| [y[1], -mu * (1.0 - s).powi(4) * y[0]];
        let end = ode::integrate(rhs, 0.0, [0.0, 1.0], 1.0, &opts).map_err(ode_err)?;
        return Ok(end.y[1]);
    }
    let k2 = k * k;
    // Companion form y' = A y with y = (φ, φ', φ'', φ'''): A₁₂ = A₂₃ = A₃₄ = 1,
    // A₄₁ = a(ŝ) = μ(1−ŝ)⁴/K², A₄₃ = b = 1/K². Plücker order (12, 13, 14, 23, 24, 34);
    // p_ij' = Σ_k A_ik p_kj + Σ_k A_jk p_ik.
    let b = 1.0 / k2;
    let rhs = |s: f64, p: &[f64; 6]| {
        let a = mu * (1.0 - s).powi(4) / k2;
        let [p12, p13, p14, p23, p24, p34] = *p;
        [
            p13,
            p23 + p14,
            p24 + b * p13,
            p24,
            p34 - a * p12 + b * p23,
            -a * p13,
        ]
    };
    let segments = (1.0 / (SEGMENT_LENGTH_IN_K * k)).ceil().max(1.0) as usize;
    let mut p = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0];
    for i in 0..segments {
        let s0 = i as f64 / segments as f64;
        let s1 = (i + 1) as f64 / segments as f64;
        let mut seg_opts = opts;
        seg_opts.max_steps = 1_000_000;
        p = ode::integrate(rhs, s0, p, s1, &seg_opts)
            .map_err(ode_err)?
            .y;
        let scale = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        if scale > 0.0 && scale.is_finite() {
            p.iter_mut().for_each(|v| *v /= scale);
        }
    }
    Ok(-p[3] - k2 * p[5])
}

/// Critical load `λ_c = qL³/√(BC)` of the Vlasov cantilever by compound-matrix shooting:
/// geometric scan of the boundary determinant from `λ = 4` in 4 % steps, then bisection
/// to a relative bracket of `1e-13`. Accurate to ~1e-9 relative (set by the ODE tolerance).
pub fn critical_lambda_shooting(k: f64) -> Result<f64, LateralBucklingError> {
    check_k_shooting(k)?;
    let mut lo = SCAN_START;
    let mut d_lo = shooting_determinant(k, lo)?;
    let mut hi;
    let mut d_hi;
    loop {
        hi = lo * SCAN_RATIO;
        d_hi = shooting_determinant(k, hi)?;
        if d_hi == 0.0 {
            return Ok(hi);
        }
        if d_lo.signum() != d_hi.signum() {
            break;
        }
        if hi > SCAN_MAX {
            return Err(LateralBucklingError::NoRootFound {
                k,
                lambda_max: SCAN_MAX,
            });
        }
        lo = hi;
        d_lo = d_hi;
    }
    bisect_sign(
        |lambda| shooting_determinant(k, lambda),
        lo,
        d_lo,
        hi,
        d_hi,
        Bisection::linear(BISECTION_RTOL),
    )
    .map_err(|e| {
        e.into_evaluation_or(|e| LateralBucklingError::Bisection {
            k,
            detail: e.to_string(),
        })
    })
}

// ---------------------------------------------------------------------------------------
// Rayleigh–Ritz with cubic Hermite elements
// ---------------------------------------------------------------------------------------

/// Smallest and largest element counts of one Ritz mesh.
pub const RITZ_ELEMENTS_MIN: usize = 2;
/// Largest element count (dense eigen-solve of size `2n`).
pub const RITZ_ELEMENTS_MAX: usize = 2000;
/// Default coarse mesh of the Richardson pair (the fine one has twice as many elements).
pub const RITZ_ELEMENTS_DEFAULT: usize = 48;

/// Nodes `ŝ_i = g(i/n)` graded toward the clamp: `g(t) = (e^{βt} − 1)/(e^β − 1)`,
/// `β = min(ln(1 + 1/K), 8)`. The map is smooth, so the `h⁴` error expansion that the
/// Richardson step relies on holds in the uniform variable `t`; the first element is
/// `≈ β/(e^β − 1)/n`, well inside the warping boundary layer of width `K`.
fn graded_nodes(k: f64, n: usize) -> Vec<f64> {
    let beta = if k == 0.0 {
        0.0
    } else {
        (1.0 + 1.0 / k).ln().min(8.0)
    };
    (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            if beta < 1e-8 {
                t
            } else {
                (beta * t).exp_m1() / beta.exp_m1()
            }
        })
        .collect()
}

/// One Ritz solve on `n` graded cubic Hermite elements: the smallest `μ = λ²/4` of
/// `A c = μ W c`, `A` from `∫(K²φ''² + φ'²)`, `W` from `∫(1 − ŝ)⁴ φ²`. An upper bound on
/// the exact `μ_c` (Rayleigh–Ritz), converging like `h⁴`.
fn ritz_mu(k: f64, n: usize) -> Result<f64, LateralBucklingError> {
    let nodes = graded_nodes(k, n);
    // (φ, φ') at nodes 1..=n; node 0 has φ = 0, and φ' = 0 only if K > 0: without warping
    // stiffness the clamp cannot restrain the rate of twist (the K = 0 problem is of second
    // order, with the single clamp condition φ(0) = 0).
    let free_clamp_slope = k == 0.0;
    let offset = usize::from(free_clamp_slope);
    let ndof = 2 * n + offset;
    let mut a = Mat::<f64>::zeros(ndof, ndof);
    let mut w = Mat::<f64>::zeros(ndof, ndof);
    // Six Gauss points integrate the degree-10 weight term (1−ŝ)⁴φ² exactly.
    let (gt, gw) = gauss_legendre(6);
    let k2 = k * k;
    for e in 0..n {
        let (s0, s1) = (nodes[e], nodes[e + 1]);
        let h = s1 - s0;
        // Global dof of each local Hermite function (None where the clamp fixes it).
        let dof = |local: usize| -> Option<usize> {
            let node = e + local / 2;
            match (node, local % 2) {
                (0, 0) => None,
                (0, _) => free_clamp_slope.then_some(0),
                (_, slope) => Some(2 * (node - 1) + slope + offset),
            }
        };
        for (t, wq) in gt.iter().zip(&gw) {
            let xi = 0.5 * (t + 1.0);
            let jw = 0.5 * wq * h;
            let s = s0 + h * xi;
            // Hermite cubics on [0,1] for (φ₀, φ₀', φ₁, φ₁'); slopes scaled by h.
            let n_val = [
                1.0 - 3.0 * xi * xi + 2.0 * xi.powi(3),
                h * (xi - 2.0 * xi * xi + xi.powi(3)),
                3.0 * xi * xi - 2.0 * xi.powi(3),
                h * (-xi * xi + xi.powi(3)),
            ];
            let n_d1 = [
                (-6.0 * xi + 6.0 * xi * xi) / h,
                1.0 - 4.0 * xi + 3.0 * xi * xi,
                (6.0 * xi - 6.0 * xi * xi) / h,
                -2.0 * xi + 3.0 * xi * xi,
            ];
            let n_d2 = [
                (-6.0 + 12.0 * xi) / (h * h),
                (-4.0 + 6.0 * xi) / h,
                (6.0 - 12.0 * xi) / (h * h),
                (-2.0 + 6.0 * xi) / h,
            ];
            let weight = (1.0 - s).powi(4);
            for i in 0..4 {
                let Some(gi) = dof(i) else { continue };
                for j in 0..4 {
                    let Some(gj) = dof(j) else { continue };
                    a[(gi, gj)] += jw * (k2 * n_d2[i] * n_d2[j] + n_d1[i] * n_d1[j]);
                    w[(gi, gj)] += jw * weight * n_val[i] * n_val[j];
                }
            }
        }
    }
    let theta =
        largest_pencil_eigenvalue(&a, &w).map_err(|source| LateralBucklingError::Pencil {
            method: "Vlasov Hermite Ritz",
            source,
        })?;
    Ok(1.0 / theta)
}

/// A Rayleigh–Ritz estimate of `λ_c` with its ingredients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RitzEstimate {
    /// `λ_c` on `n` elements (an upper bound).
    pub coarse: f64,
    /// `λ_c` on `2n` elements (an upper bound).
    pub fine: f64,
    /// Richardson extrapolation of `μ = λ²/4` in `h⁴`, returned as `λ`.
    pub extrapolated: f64,
}

/// Critical load `λ_c` of the Vlasov cantilever by Hermite-element Rayleigh–Ritz on
/// `elements` and `2·elements` graded elements, Richardson-extrapolated (`μ ∝ λ²` has an
/// `h⁴` error). With the default 48/96 elements the extrapolated value agrees with the
/// shooting method to ~1e-9 relative for `K = 0` and `K ∈ [1e-4, 1.5]` (tested). For
/// `0 < K < 1e-5` the boundary layer is thinner than the first element and the error grows
/// to ~1e-5 relative (measured against `λ_c(0) + K dλ_c/dK`), still far below any use.
pub fn critical_lambda_ritz(k: f64, elements: usize) -> Result<RitzEstimate, LateralBucklingError> {
    check_k_ritz(k)?;
    if !(RITZ_ELEMENTS_MIN..=RITZ_ELEMENTS_MAX / 2).contains(&elements) {
        return Err(LateralBucklingError::InvalidSize {
            name: "elements",
            value: elements,
            min: RITZ_ELEMENTS_MIN,
            max: RITZ_ELEMENTS_MAX / 2,
        });
    }
    let mu_coarse = ritz_mu(k, elements)?;
    let mu_fine = ritz_mu(k, 2 * elements)?;
    let mu_extrapolated = (16.0 * mu_fine - mu_coarse) / 15.0;
    Ok(RitzEstimate {
        coarse: 2.0 * mu_coarse.sqrt(),
        fine: 2.0 * mu_fine.sqrt(),
        extrapolated: 2.0 * mu_extrapolated.sqrt(),
    })
}

/// `λ_c` on one Ritz mesh of `elements` graded elements (an upper bound; for convergence
/// studies).
pub fn critical_lambda_ritz_single(k: f64, elements: usize) -> Result<f64, LateralBucklingError> {
    check_k_ritz(k)?;
    if !(RITZ_ELEMENTS_MIN..=RITZ_ELEMENTS_MAX).contains(&elements) {
        return Err(LateralBucklingError::InvalidSize {
            name: "elements",
            value: elements,
            min: RITZ_ELEMENTS_MIN,
            max: RITZ_ELEMENTS_MAX,
        });
    }
    Ok(2.0 * ritz_mu(k, elements)?.sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The compound-matrix determinant against the plain 2×2 determinant of two directly
    /// integrated solutions, where the latter is still well conditioned (K = 0.5).
    #[test]
    fn compound_determinant_matches_direct_determinant() {
        let k: f64 = 0.5;
        let k2 = k * k;
        for lambda in [10.0, 30.0, 45.0] {
            let mu = 0.25 * lambda * lambda;
            let rhs = |s: f64, y: &[f64; 4]| {
                [
                    y[1],
                    y[2],
                    y[3],
                    (y[2] + mu * (1.0 - s).powi(4) * y[0]) / k2,
                ]
            };
            let opts = Options::with_tolerances(1e-12, 1e-14);
            let u = ode::integrate(rhs, 0.0, [0.0, 0.0, 1.0, 0.0], 1.0, &opts)
                .unwrap()
                .y;
            let v = ode::integrate(rhs, 0.0, [0.0, 0.0, 0.0, 1.0], 1.0, &opts)
                .unwrap()
                .y;
            // Plücker coordinates of span{u, v}, renormalised like the compound
            // integration (max-norm 1 at the end of its single segment).
            let pl = |i: usize, j: usize| u[i] * v[j] - u[j] * v[i];
            let p = [pl(0, 1), pl(0, 2), pl(0, 3), pl(1, 2), pl(1, 3), pl(2, 3)];
            let scale = p.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let direct = u[2] * (v[1] - k2 * v[3]) - v[2] * (u[1] - k2 * u[3]);
            let direct_normalised = direct / scale;
            let compound = shooting_determinant(k, lambda).unwrap();
            assert!(
                (direct_normalised - compound).abs() < 1e-9,
                "λ = {lambda}: direct {direct_normalised}, compound {compound}"
            );
        }
    }

    #[test]
    fn graded_nodes_are_increasing_and_span_the_unit_interval() {
        for k in [0.0, 1e-3, 0.05, 1.0] {
            let s = graded_nodes(k, 10);
            assert_eq!(s[0], 0.0);
            assert!((s[10] - 1.0).abs() < 1e-15);
            assert!(s.windows(2).all(|p| p[1] > p[0]));
        }
    }
}
