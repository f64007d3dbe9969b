//! SE(3): the exponential and logarithm of rigid motions, and the derivatives of the
//! translational part of the logarithm.
//!
//! A twist is d = (u, θ) ∈ ℝ⁶ (translation part first, both in body coordinates). Its
//! exponential is the rigid motion (exp θ, V(θ) u) with
//! V(θ) = I + ((1 − cos φ)/φ²)[θ]× + ((φ − sin φ)/φ³)[θ]×², φ = |θ|; the motion t ↦ exp(t d)
//! is a helicoid (a screw), so constant-strain beams (straight, circle, helix) are exact.
//! Its logarithm is θ = log R and u = W(θ) p with
//! W(θ) = V(θ)⁻¹ = I − ½[θ]× + γ(φ²)[θ]×², γ(s) = (1 − (φ/2) cot(φ/2))/φ².

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::geometry::{cross_matrix, Vec3};

use super::darboux::rotation_log_value;
use super::quaternion::from_unit;

/// V(θ) (see the module docs).
pub fn v_matrix(theta: &Vec3) -> Matrix3<f64> {
    let s = theta.norm_squared();
    let (a, b) = if s < 1e-6 {
        (
            0.5 - s / 24.0 + s * s / 720.0,
            1.0 / 6.0 - s / 120.0 + s * s / 5040.0,
        )
    } else {
        let phi = s.sqrt();
        ((1.0 - phi.cos()) / s, (phi - phi.sin()) / (s * phi))
    };
    let k = cross_matrix(theta);
    Matrix3::identity() + k * a + k * k * b
}

/// exp(u, θ): the rotation exp θ and the translation V(θ) u.
pub fn exp(u: &Vec3, theta: &Vec3) -> (UnitQuaternion<f64>, Vec3) {
    (
        UnitQuaternion::from_scaled_axis(*theta),
        v_matrix(theta) * u,
    )
}

/// log(R, p) = (u, θ) with |θ| ≤ π.
pub fn log(rotation: &UnitQuaternion<f64>, translation: &Vec3) -> (Vec3, Vec3) {
    let mut q = from_unit(rotation);
    if q[0] < 0.0 {
        q = -q;
    }
    let theta = rotation_log_value(&q);
    (translation_log_value(&theta, translation), theta)
}

/// |B₂ₙ|/(2n)! for n = 1…17: γ(s) = Σₙ aₙ sⁿ⁻¹ (radius of convergence s = 4π²).
const GAMMA_SERIES: [f64; 17] = [
    0.083_333_333_333_333_33,
    0.001_388_888_888_888_889,
    3.306_878_306_878_307e-5,
    8.267_195_767_195_768e-7,
    2.087_675_698_786_81e-8,
    5.284_190_138_687_493e-10,
    1.338_253_653_068_467_9e-11,
    3.389_680_296_322_582_7e-13,
    8.586_062_056_277_845e-15,
    2.174_868_698_558_062e-16,
    5.509_002_828_360_229_5e-18,
    1.395_446_468_581_252_2e-19,
    3.534_707_039_629_467e-21,
    8.953_517_427_037_546e-23,
    2.267_952_452_337_683e-24,
    5.744_790_668_872_202e-26,
    1.455_172_475_614_865e-27,
];

/// Below this s = φ², γ and its derivatives come from the series (whose terms then fall
/// by s/4π² ≈ 0.06 each); above, from closed forms that lose at most a digit.
const GAMMA_SERIES_LIMIT: f64 = 2.25;

/// γ(s), γ′(s), γ″(s) (derivatives in s = φ²).
fn gamma(s: f64) -> (f64, f64, f64) {
    if s < GAMMA_SERIES_LIMIT {
        gamma_series(s)
    } else {
        gamma_closed(s)
    }
}

/// γ and its derivatives from the series (accurate for s < 4π², used below the limit).
fn gamma_series(s: f64) -> (f64, f64, f64) {
    {
        let (mut g, mut g1, mut g2) = (0.0, 0.0, 0.0);
        // Horner from the highest term.
        for n in (0..GAMMA_SERIES.len()).rev() {
            let a = GAMMA_SERIES[n];
            let nf = n as f64;
            g = g * s + a;
            if n >= 1 {
                g1 = g1 * s + nf * a;
            }
            if n >= 2 {
                g2 = g2 * s + nf * (nf - 1.0) * a;
            }
        }
        (g, g1, g2)
    }
}

/// γ and its derivatives from the closed forms (for s ≥ the limit).
fn gamma_closed(s: f64) -> (f64, f64, f64) {
    {
        let phi = s.sqrt();
        let half = 0.5 * phi;
        let cot = half.cos() / half.sin();
        let csc2 = 1.0 / (half.sin() * half.sin());
        // c = (φ/2) cot(φ/2) and its φ-derivatives.
        let c = half * cot;
        let c_p = 0.5 * cot - 0.25 * phi * csc2;
        let c_pp = -0.5 * csc2 + 0.25 * phi * csc2 * cot;
        let c_s = c_p / (2.0 * phi);
        let c_ss = (phi * c_pp - c_p) / (4.0 * phi * phi * phi);
        let g = (1.0 - c) / s;
        let g1 = (-c_s - g) / s;
        let g2 = (-c_ss - 2.0 * g1) / s;
        (g, g1, g2)
    }
}

/// u = W(θ) r alone (no derivatives).
pub fn translation_log_value(theta: &Vec3, r: &Vec3) -> Vec3 {
    let s = theta.norm_squared();
    let g = if s < GAMMA_SERIES_LIMIT {
        // Horner on the first terms suffices for the value (s < 2.25, ratio ≤ 0.06).
        GAMMA_SERIES.iter().rev().fold(0.0, |acc, a| acc * s + a)
    } else {
        gamma_closed(s).0
    };
    r - theta.cross(r) * 0.5 + (theta * theta.dot(r) - r * s) * g
}

/// u = W(θ) r, the translational part of the SE(3) logarithm of a motion whose rotation is
/// exp θ and translation r, with its derivatives in θ and r.
#[derive(Clone, Copy, Debug)]
pub struct TranslationLog {
    /// u = W(θ) r.
    pub u: Vec3,
    /// ∂u/∂θ.
    pub du_dtheta: Matrix3<f64>,
    /// ∂u/∂r = W(θ).
    pub w: Matrix3<f64>,
    theta: Vec3,
    r: Vec3,
    /// P = θ × (θ × r).
    p: Vec3,
    s: f64,
    g: f64,
    g1: f64,
    g2: f64,
}

impl TranslationLog {
    /// u and its first derivatives at (θ, r) (|θ| < 2π).
    pub fn new(theta: &Vec3, r: &Vec3) -> Self {
        let s = theta.norm_squared();
        let (g, g1, g2) = gamma(s);
        let tr = theta.dot(r);
        let p = theta * tr - r * s;
        // u = r − ½ θ×r + γ P.
        let u = r - theta.cross(r) * 0.5 + p * g;
        // ∂P/∂θ = (θ·r) I + θ rᵀ − 2 r θᵀ.
        let dp = Matrix3::identity() * tr + theta * r.transpose() - r * theta.transpose() * 2.0;
        let du_dtheta = cross_matrix(r) * 0.5 + p * theta.transpose() * (2.0 * g1) + dp * g;
        let w = Matrix3::identity() - cross_matrix(theta) * 0.5
            + (theta * theta.transpose() - Matrix3::identity() * s) * g;
        Self {
            u,
            du_dtheta,
            w,
            theta: *theta,
            r: *r,
            p,
            s,
            g,
            g1,
            g2,
        }
    }

    /// (Σᵢ μᵢ ∂²uᵢ/∂θ², Σᵢ μᵢ ∂²uᵢ/∂θ∂r) (rows θ, columns r); ∂²u/∂r² = 0.
    pub fn contracted(&self, mu: &Vec3) -> (Matrix3<f64>, Matrix3<f64>) {
        let (t, r, s) = (&self.theta, &self.r, self.s);
        let (g, g1, g2) = (self.g, self.g1, self.g2);
        let mp = mu.dot(&self.p);
        let mr = mu.dot(r);
        let mt = mu.dot(t);
        let tr = t.dot(r);
        // (μᵀ ∂P/∂θ)_k = μ_k (θ·r) + (μ·θ) r_k − 2 θ_k (μ·r).
        let pk: Vector3<f64> = mu * tr + r * mt - t * (2.0 * mr);
        let tt = t * t.transpose();
        let s_tt = tt * (4.0 * g2 * mp)
            + Matrix3::identity() * (2.0 * g1 * mp)
            + (t * pk.transpose() + pk * t.transpose()) * (2.0 * g1)
            + (mu * r.transpose() + r * mu.transpose() - Matrix3::identity() * (2.0 * mr)) * g;
        let s_tr = cross_matrix(mu) * 0.5
            + t * (t * mt - mu * s).transpose() * (2.0 * g1)
            + (mu * t.transpose() + Matrix3::identity() * mt - t * mu.transpose() * 2.0) * g;
        (s_tt, s_tr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_inverts_exp() {
        for (u, t) in [
            (Vec3::new(0.1, -0.3, 1.0), Vec3::new(0.4, 0.2, -0.9)),
            (Vec3::new(2.0, 0.5, 0.0), Vec3::new(1e-8, 0.0, 2e-8)),
            (Vec3::new(-1.0, 0.5, 0.3), Vec3::new(0.0, 2.5, 1.5)),
        ] {
            let (r, p) = exp(&u, &t);
            let (u2, t2) = log(&r, &p);
            assert!(
                (u2 - u).norm() < 1e-13 && (t2 - t).norm() < 1e-13,
                "{u2} {t2}"
            );
        }
    }

    #[test]
    fn gamma_series_and_closed_form_agree_with_high_precision_values() {
        // γ(2.25), γ′, γ″ (mpmath, 40 digits), rounded to the nearest f64.
        let exact = [
            0.086_635_728_261_318_66,
            0.001_551_278_087_027_641,
            7.869_810_152_343_017e-5,
        ];
        for (g, g1, g2) in [gamma_series(2.25), gamma_closed(2.25)] {
            assert!((g / exact[0] - 1.0).abs() < 1e-15, "{g}");
            assert!((g1 / exact[1] - 1.0).abs() < 1e-13, "{g1}");
            assert!((g2 / exact[2] - 1.0).abs() < 1e-11, "{g2}");
        }
    }

    #[test]
    fn translation_log_derivatives_match_finite_differences() {
        for theta in [
            Vec3::new(0.3, -0.7, 0.2),
            Vec3::new(1.5, 1.2, -0.9),
            Vec3::new(1e-3, 2e-3, -1e-3),
        ] {
            let r = Vec3::new(0.2, 0.5, 1.1);
            let mu = Vec3::new(-0.4, 0.9, 0.3);
            let t = TranslationLog::new(&theta, &r);
            let (s_tt, s_tr) = t.contracted(&mu);
            let eps = 1e-6;
            for k in 0..3 {
                let mut e = Vec3::zeros();
                e[k] = eps;
                let plus = TranslationLog::new(&(theta + e), &r);
                let minus = TranslationLog::new(&(theta - e), &r);
                let d = (plus.u - minus.u) / (2.0 * eps);
                assert!((d - t.du_dtheta.column(k)).norm() < 1e-8);
                let dd = (plus.du_dtheta.transpose() * mu - minus.du_dtheta.transpose() * mu)
                    / (2.0 * eps);
                assert!(
                    (dd - s_tt.column(k)).norm() < 1e-7,
                    "{dd} {}",
                    s_tt.column(k)
                );
                let plus = TranslationLog::new(&theta, &(r + e));
                let minus = TranslationLog::new(&theta, &(r - e));
                assert!(((plus.u - minus.u) / (2.0 * eps) - t.w.column(k)).norm() < 1e-8);
                let dd = (plus.du_dtheta.transpose() * mu - minus.du_dtheta.transpose() * mu)
                    / (2.0 * eps);
                assert!((dd - s_tr.column(k)).norm() < 1e-7);
            }
        }
    }
}
