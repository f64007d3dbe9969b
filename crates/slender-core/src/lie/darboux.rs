//! Maps of a relative-rotation quaternion q = (w, v) (angle φ about the unit axis n, w ≥ 0)
//! to a 3-vector, with their Jacobians and contracted Hessians in the four components of q:
//! the discrete Darboux vectors of a Cosserat rod and the rotation logarithm.
//!
//! Every map is extended off the unit sphere by the formula as written; since the expansions of
//! [`super::quaternion`] stay on the sphere exactly, the chain rule through any extension gives
//! the exact derivatives on the sphere.

use nalgebra::{Matrix3, Matrix4, SMatrix, Vector3};
use serde::{Deserialize, Serialize};

use super::quaternion::{vector_part, Quat};

/// How the discrete Darboux vector (curvature and twist, times the length between the two
/// frames) is computed from the relative rotation q = (w, v) of neighbouring frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(rename_all = "snake_case")]
pub enum DarbouxMeasure {
    /// 2v = 2 sin(φ/2) n: the quaternion form of Lang, Linn & Arnold's discrete Cosserat rod
    /// (design.md §2.2). It saturates for large kinks (at most 2 at φ = π).
    #[default]
    Sine,
    /// 2v/w = 2 tan(φ/2) n (Cayley): for bending alone this is the discrete elastic rod's
    /// curvature binormal κb, so a shear-stiff Cosserat rod with it tends to the discrete
    /// elastic rod. It stiffens large kinks.
    Tangent,
}

/// A map g(q) ∈ ℝ³ evaluated at one q, with its derivatives.
#[derive(Clone, Copy, Debug)]
pub struct QuaternionMap {
    /// g(q).
    pub value: Vector3<f64>,
    /// ∂g/∂q (3×4; columns w, x, y, z).
    pub jac: SMatrix<f64, 3, 4>,
    second: Second,
}

/// What the contracted Hessian of each map needs.
#[derive(Clone, Copy, Debug)]
enum Second {
    /// g is linear in q.
    Linear,
    /// g = 2v/w.
    Tangent { w: f64, v: Vector3<f64> },
    /// g = F(|v|², w) v, with F's partial derivatives.
    Scaled {
        v: Vector3<f64>,
        f_s: f64,
        f_w: f64,
        f_ss: f64,
        f_sw: f64,
        f_ww: f64,
    },
}

impl QuaternionMap {
    /// Σ_k μ_k ∂²g_k/∂q² (4×4).
    pub fn contracted_hessian(&self, mu: &Vector3<f64>) -> Matrix4<f64> {
        let mut h = Matrix4::zeros();
        match self.second {
            Second::Linear => {}
            Second::Tangent { w, v } => {
                // g = 2v/w: ∂²g_k/∂w² = 4v_k/w³, ∂²g_k/∂w∂v_j = −2δ_kj/w².
                h[(0, 0)] = 4.0 * mu.dot(&v) / (w * w * w);
                for j in 0..3 {
                    let c = -2.0 * mu[j] / (w * w);
                    h[(0, j + 1)] = c;
                    h[(j + 1, 0)] = c;
                }
            }
            Second::Scaled {
                v,
                f_s,
                f_w,
                f_ss,
                f_sw,
                f_ww,
            } => {
                // g_i = F v_i with F = F(s, w), s = |v|².
                let mv = mu.dot(&v);
                h[(0, 0)] = f_ww * mv;
                for j in 0..3 {
                    let c = f_w * mu[j] + 2.0 * f_sw * mv * v[j];
                    h[(0, j + 1)] = c;
                    h[(j + 1, 0)] = c;
                    for k in 0..3 {
                        let delta = if j == k { mv } else { 0.0 };
                        h[(j + 1, k + 1)] = 2.0 * f_s * (mu[j] * v[k] + mu[k] * v[j] + delta)
                            + 4.0 * f_ss * mv * v[j] * v[k];
                    }
                }
            }
        }
        h
    }
}

impl DarbouxMeasure {
    /// The measure at `q` (w ≥ 0; the tangent form needs w > 0, i.e. φ < π).
    pub fn evaluate(self, q: &Quat) -> QuaternionMap {
        let v = vector_part(q);
        let mut jac = SMatrix::<f64, 3, 4>::zeros();
        match self {
            Self::Sine => {
                jac.fixed_view_mut::<3, 3>(0, 1)
                    .copy_from(&(Matrix3::identity() * 2.0));
                QuaternionMap {
                    value: v * 2.0,
                    jac,
                    second: Second::Linear,
                }
            }
            Self::Tangent => {
                let w = q[0];
                jac.set_column(0, &(v * (-2.0 / (w * w))));
                jac.fixed_view_mut::<3, 3>(0, 1)
                    .copy_from(&(Matrix3::identity() * (2.0 / w)));
                QuaternionMap {
                    value: v * (2.0 / w),
                    jac,
                    second: Second::Tangent { w, v },
                }
            }
        }
    }
}

/// Switch from the series to the closed forms of F at t = |v|²/w² (the series converges
/// for t < 1; at 0.1 the closed forms lose at most two digits to cancellation).
const SERIES_LIMIT: f64 = 0.1;
/// Terms of the series A(t) = atan(√t)/√t = Σ (−t)^k/(2k+1) (0.1²⁰ is below round-off).
const SERIES_TERMS: usize = 22;

/// The rotation vector θ = φ n = 2 atan2(|v|, w) v/|v| of `q` (w ≥ 0), without derivatives.
pub fn rotation_log_value(q: &Quat) -> Vector3<f64> {
    let w = q[0];
    let v = vector_part(q);
    let s = v.norm_squared();
    if w > 0.0 && s < 1e-10 * w * w {
        // atan(z)/z = 1 − z²/3 + O(z⁴), z² < 1e-10.
        v * (2.0 / w * (1.0 - s / (3.0 * w * w)))
    } else {
        let n = s.sqrt();
        v * (2.0 * n.atan2(w) / n)
    }
}

/// The rotation logarithm θ = φ n = F(|v|², w) v with F = 2 atan2(|v|, w)/|v| (w ≥ 0), and
/// its derivatives.
pub fn rotation_log(q: &Quat) -> QuaternionMap {
    let w = q[0];
    let v = vector_part(q);
    let s = v.norm_squared();
    let rho = s + w * w;
    let (f, f_s, f_ss);
    if w > 0.0 && s < SERIES_LIMIT * w * w {
        // F = (2/w) A(t), t = s/w²: F_s = 2A′/w³, F_ss = 2A″/w⁵. Terms fall like t^k; stop
        // once they are below round-off.
        let t = s / (w * w);
        let (mut a, mut a1, mut a2) = (0.0, 0.0, 0.0);
        let mut tk = 1.0; // t^k
        for k in 0..SERIES_TERMS {
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            let kf = k as f64;
            a += sign / (2.0 * kf + 1.0) * tk;
            // Coefficients of t^k in A′ and A″.
            a1 -= sign * (kf + 1.0) / (2.0 * kf + 3.0) * tk;
            a2 += sign * (kf + 2.0) * (kf + 1.0) / (2.0 * kf + 5.0) * tk;
            tk *= t;
            if tk < 1e-18 {
                break;
            }
        }
        f = 2.0 * a / w;
        f_s = 2.0 * a1 / (w * w * w);
        f_ss = 2.0 * a2 / (w * w * w * w * w);
    } else {
        let n = s.sqrt();
        let ang = n.atan2(w);
        f = 2.0 * ang / n;
        f_s = w / (rho * s) - ang / (s * n);
        f_ss = -w * (s + rho) / (rho * rho * s * s) - w / (2.0 * rho * s * s)
            + 1.5 * ang / (s * s * n);
    }
    let f_w = -2.0 / rho;
    let f_ww = 4.0 * w / (rho * rho);
    let f_sw = 2.0 / (rho * rho);
    let mut jac = SMatrix::<f64, 3, 4>::zeros();
    jac.set_column(0, &(v * f_w));
    let vv = v * v.transpose();
    jac.fixed_view_mut::<3, 3>(0, 1)
        .copy_from(&(Matrix3::identity() * f + vv * (2.0 * f_s)));
    QuaternionMap {
        value: v * f,
        jac,
        second: Second::Scaled {
            v,
            f_s,
            f_w,
            f_ss,
            f_sw,
            f_ww,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Checks value, Jacobian and contracted Hessian of `map` against central differences at
    /// `q` (off the unit sphere too: the extension is differentiated as written).
    fn check(map: impl Fn(&Quat) -> QuaternionMap, q: Quat) {
        let m = map(&q);
        let mu = Vector3::new(0.7, -0.4, 1.3);
        let h = m.contracted_hessian(&mu);
        let eps = 1e-5;
        for i in 0..4 {
            let mut e = Quat::zeros();
            e[i] = eps;
            let d = (map(&(q + e)).value - map(&(q - e)).value) / (2.0 * eps);
            assert!(
                (d - m.jac.column(i)).norm() < 1e-7 * (1.0 + d.norm()),
                "jac col {i}: {d} vs {}",
                m.jac.column(i)
            );
            let dj = (map(&(q + e)).jac.transpose() * mu - map(&(q - e)).jac.transpose() * mu)
                / (2.0 * eps);
            for k in 0..4 {
                assert!(
                    (dj[k] - h[(i, k)]).abs() < 1e-6 * (1.0 + dj[k].abs()),
                    "hess ({i},{k}): {} vs {}",
                    dj[k],
                    h[(i, k)]
                );
            }
        }
    }

    #[test]
    fn maps_match_finite_differences() {
        let qs = [
            Quat::new(0.9, 0.2, -0.3, 0.1),
            Quat::new(0.999, 0.01, -0.02, 0.005),
            Quat::new(0.99999, 1e-4, 2e-4, -1e-4),
            Quat::new(0.2, 0.6, -0.7, 0.3),
            Quat::new(0.1, 0.6, -0.7, 0.3),
        ];
        for q in qs {
            check(rotation_log, q);
            check(|q| DarbouxMeasure::Sine.evaluate(q), q);
            check(|q| DarbouxMeasure::Tangent.evaluate(q), q);
        }
    }

    #[test]
    fn log_is_the_rotation_vector() {
        let theta = Vector3::new(0.4, -1.9, 0.8);
        let q = nalgebra::UnitQuaternion::from_scaled_axis(theta);
        let m = rotation_log(&super::super::quaternion::from_unit(&q));
        assert!((m.value - theta).norm() < 1e-14);
        let small = Vector3::new(1e-9, -2e-9, 3e-10);
        let q = nalgebra::UnitQuaternion::from_scaled_axis(small);
        let m = rotation_log(&super::super::quaternion::from_unit(&q));
        assert!((m.value - small).norm() < 1e-22);
    }
}
