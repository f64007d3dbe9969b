//! The quaternion exponential e(u) = (cos(|u|/2), sin(|u|/2) u/|u|) of a rotation vector u
//! (rad), with its Jacobian and contracted Hessian in the three components of u: what maps a
//! rotation vector given in a chart back to a quaternion when a chain rule passes through it
//! (the time steps' states along a rotation, `crate::dynamics`).
//!
//! Written as e = (C(s), S(s) u) with s = |u|², C = cos(√s/2), S = sin(√s/2)/√s, both entire
//! functions of s: their Taylor series (one branch, no division by |u|) converge for every s,
//! and fast for the |u| ≤ 2π a principal rotation vector ever has.

use nalgebra::{Matrix3, SMatrix, Vector3};

use super::quaternion::Quat;

/// Terms of the series of C, S and their derivatives: at s = (2π)² the last term is below
/// 1e-17 of the first (x = s/4 ≤ π², xᵏ/(2k)! < 3e-18 at k = 15).
const SERIES_TERMS: usize = 20;

/// C(s) = cos(√s/2) and S(s) = sin(√s/2)/√s with their first two derivatives in s.
#[derive(Clone, Copy, Debug)]
struct Coefficients {
    c: [f64; 3],
    s: [f64; 3],
}

impl Coefficients {
    fn at(s: f64) -> Self {
        // C = Σ (−1)ᵏ xᵏ/(2k)!, S = ½ Σ (−1)ᵏ xᵏ/(2k+1)!, x = s/4; d/ds = ¼ d/dx.
        let x = 0.25 * s;
        let (mut c, mut sn) = ([0.0; 3], [0.0; 3]);
        // a_k = (−1)ᵏ/(2k)!, b_k = (−1)ᵏ/(2k+1)!, x^(k−2), x^(k−1), x^k kept as we go.
        let mut a = 1.0;
        let mut b = 1.0;
        let mut xk = 1.0; // x^k
        let mut xk1 = 0.0; // x^(k−1) (0 for k = 0: that term has no derivative)
        let mut xk2 = 0.0; // x^(k−2)
        for k in 0..SERIES_TERMS {
            let kf = k as f64;
            c[0] += a * xk;
            c[1] += a * kf * xk1;
            c[2] += a * kf * (kf - 1.0) * xk2;
            sn[0] += b * xk;
            sn[1] += b * kf * xk1;
            sn[2] += b * kf * (kf - 1.0) * xk2;
            a *= -1.0 / ((2.0 * kf + 1.0) * (2.0 * kf + 2.0));
            b *= -1.0 / ((2.0 * kf + 2.0) * (2.0 * kf + 3.0));
            xk2 = xk1;
            xk1 = xk;
            xk *= x;
        }
        Self {
            c: [c[0], 0.25 * c[1], 0.0625 * c[2]],
            s: [0.5 * sn[0], 0.125 * sn[1], 0.03125 * sn[2]],
        }
    }
}

/// e(u) at one u, with what its derivatives need.
#[derive(Clone, Copy, Debug)]
pub struct QuaternionExp {
    /// e(u) as (w, x, y, z).
    pub value: Quat,
    /// ∂e/∂u (4×3).
    pub jac: SMatrix<f64, 4, 3>,
    u: Vector3<f64>,
    coef: Coefficients,
}

impl QuaternionExp {
    /// e(`u`) and its derivatives; `u` (rad) finite.
    pub fn new(u: &Vector3<f64>) -> Self {
        let coef = Coefficients::at(u.norm_squared());
        let [c, c1, _] = coef.c;
        let [s, s1, _] = coef.s;
        let value = Quat::new(c, s * u.x, s * u.y, s * u.z);
        let mut jac = SMatrix::<f64, 4, 3>::zeros();
        for j in 0..3 {
            jac[(0, j)] = 2.0 * c1 * u[j];
            for i in 0..3 {
                let delta = if i == j { s } else { 0.0 };
                jac[(i + 1, j)] = delta + 2.0 * s1 * u[i] * u[j];
            }
        }
        Self {
            value,
            jac,
            u: *u,
            coef,
        }
    }

    /// Σ_m λ_m ∂²e_m/∂u² (3×3): with ∂²C = 2C′I + 4C″uuᵀ and
    /// ∂²(S uᵢ)/∂u_j∂u_k = 2S′(u_j δ_ik + u_k δ_ij + uᵢ δ_jk) + 4S″ uᵢ u_j u_k.
    pub fn contracted_hessian(&self, lambda: &Quat) -> Matrix3<f64> {
        let u = self.u;
        let [_, c1, c2] = self.coef.c;
        let [_, s1, s2] = self.coef.s;
        let lv = Vector3::new(lambda[1], lambda[2], lambda[3]);
        let lu = lv.dot(&u);
        let uu = u * u.transpose();
        Matrix3::identity() * (2.0 * lambda[0] * c1 + 2.0 * s1 * lu)
            + uu * (4.0 * lambda[0] * c2 + 4.0 * s2 * lu)
            + (u * lv.transpose() + lv * u.transpose()) * (2.0 * s1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    #[test]
    fn value_is_the_unit_quaternion_of_the_rotation_vector() {
        for u in [
            Vector3::new(0.3, -1.2, 0.7),
            Vector3::new(1e-9, 2e-9, -1e-9),
            Vector3::new(2.0, 2.0, -1.5),
            Vector3::zeros(),
        ] {
            let q = UnitQuaternion::from_scaled_axis(u);
            let e = QuaternionExp::new(&u).value;
            let expected = Quat::new(q.w, q.i, q.j, q.k);
            assert!((e - expected).norm() < 1e-15, "{u}: {e} vs {expected}");
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let lambda = Quat::new(0.7, -0.3, 1.1, 0.4);
        for u in [
            Vector3::new(0.3, -1.2, 0.7),
            Vector3::new(1e-3, -2e-3, 5e-4),
            Vector3::new(2.5, 1.5, -2.0),
        ] {
            let e = QuaternionExp::new(&u);
            let h = e.contracted_hessian(&lambda);
            let eps = 1e-5;
            for j in 0..3 {
                let mut d = Vector3::zeros();
                d[j] = eps;
                let (p, m) = (QuaternionExp::new(&(u + d)), QuaternionExp::new(&(u - d)));
                let fd = (p.value - m.value) / (2.0 * eps);
                assert!((fd - e.jac.column(j)).norm() < 1e-9, "jac {j} at {u}");
                let fd2 = (p.jac.transpose() * lambda - m.jac.transpose() * lambda) / (2.0 * eps);
                for k in 0..3 {
                    assert!((fd2[k] - h[(j, k)]).abs() < 1e-8, "hess ({j},{k}) at {u}");
                }
            }
        }
    }
}
