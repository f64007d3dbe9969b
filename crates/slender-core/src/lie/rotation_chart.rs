//! Rotation vectors seen from the models' chart, with exact first and second derivatives: how
//! the rotation vector of a frame relative to a fixed one changes under the spatial increment
//! the models' derivatives are taken in (p ← e(δ) ⊗ p, see [`super`]), and how a rotation
//! vector's increment acts on the rotation it names. Both are the derivative of the
//! exponential map (dexp and dexp⁻¹, the left Jacobian of SO(3) and its inverse) and the
//! derivative of that, obtained by the chain rule through the exact quaternion expansions of
//! [`super::quaternion`], the logarithm of [`super::darboux`] and the exponential of
//! [`super::exp_map`].
//!
//! They are what a time step needs on a rotation group: the inertial term measures a frame by
//! its rotation vector from the step's start (a log map), while Newton moves the frame by
//! spatial increments.

use nalgebra::{Matrix3, Matrix4, SMatrix, Vector3};

use super::darboux::{rotation_log, QuaternionMap};
use super::exp_map::QuaternionExp;
use super::quaternion::{conj, Quat, SingleRotation};

/// The map δ ↦ φ(δ) = log(e(δ) ⊗ q₀) at δ = 0: the rotation vector (rad) of a frame relative
/// to a fixed one, q₀ = p ⊗ p̄_ref, as the frame p turns by the spatial increment δ. Its
/// Jacobian is dexp⁻¹ at φ₀ (the inverse of the left Jacobian J_l(φ₀)).
#[derive(Clone, Copy, Debug)]
pub struct LogChart {
    /// φ₀ = log(q₀) (rad, principal: |φ₀| ≤ π).
    pub value: Vector3<f64>,
    /// ∂φ/∂δ = J_l(φ₀)⁻¹ (3×3).
    pub jac: Matrix3<f64>,
    single: SingleRotation,
    log: QuaternionMap,
}

impl LogChart {
    /// The chart at the relative rotation `q0` (either sign: the one with w ≥ 0 is used, so
    /// the rotation vector is the principal one).
    pub fn new(q0: &Quat) -> Self {
        let q = if q0[0] < 0.0 { -q0 } else { *q0 };
        let single = SingleRotation::new(q);
        let log = rotation_log(&q);
        Self {
            value: log.value,
            jac: log.jac * single.jac,
            single,
            log,
        }
    }

    /// Σ_k μ_k ∂²φ_k/∂δ² (3×3).
    pub fn contracted_hessian(&self, mu: &Vector3<f64>) -> Matrix3<f64> {
        let j = self.single.jac;
        let lambda: Quat = self.log.jac.transpose() * mu;
        j.transpose() * self.log.contracted_hessian(mu) * j
            + self.single.contracted_hessian(&lambda)
    }
}

/// The map u ↦ ζ(u) = log(e(u) ⊗ ē(u₀)) at u = u₀: the spatial increment (rad) by which a
/// frame e(u) ⊗ p turns when its rotation vector u (from p) changes. Its Jacobian is the left
/// Jacobian J_l(u₀) = I + (1 − cos θ)/θ² [u₀]× + (θ − sin θ)/θ³ [u₀]×², θ = |u₀|.
#[derive(Clone, Copy, Debug)]
pub struct ExpChart {
    /// ∂ζ/∂u = J_l(u₀) (3×3).
    pub jac: Matrix3<f64>,
    exp: QuaternionExp,
    /// Right multiplication by ē(u₀) as a 4×4 matrix: e ⊗ ē(u₀) = R e.
    right: Matrix4<f64>,
    /// ∂ζ/∂q at q = e(u₀) ⊗ ē(u₀) = 1 (3×4).
    log_jac: SMatrix<f64, 3, 4>,
    log: QuaternionMap,
}

/// The matrix of q ↦ q ⊗ c.
fn right_multiplication(c: &Quat) -> Matrix4<f64> {
    let (w, x, y, z) = (c[0], c[1], c[2], c[3]);
    Matrix4::new(
        w, -x, -y, -z, //
        x, w, z, -y, //
        y, -z, w, x, //
        z, y, -x, w,
    )
}

impl ExpChart {
    /// The chart at `u0` (rad).
    pub fn new(u0: &Vector3<f64>) -> Self {
        let exp = QuaternionExp::new(u0);
        let right = right_multiplication(&conj(&exp.value));
        // e(u₀) ⊗ ē(u₀) is the identity up to round-off; the log's derivatives are taken there.
        let log = rotation_log(&Quat::new(1.0, 0.0, 0.0, 0.0));
        let log_jac = log.jac;
        Self {
            jac: log_jac * right * exp.jac,
            exp,
            right,
            log_jac,
            log,
        }
    }

    /// Σ_k g_k ∂²ζ_k/∂u² (3×3).
    pub fn contracted_hessian(&self, g: &Vector3<f64>) -> Matrix3<f64> {
        let a = self.right * self.exp.jac;
        let lambda: Quat = self.right.transpose() * (self.log_jac.transpose() * g);
        a.transpose() * self.log.contracted_hessian(g) * a + self.exp.contracted_hessian(&lambda)
    }
}

/// The left Jacobian J_l(v) of SO(3) (see [`ExpChart`]).
pub fn left_jacobian(v: &Vector3<f64>) -> Matrix3<f64> {
    ExpChart::new(v).jac
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lie::quaternion::{from_unit, mul};
    use nalgebra::UnitQuaternion;

    fn rotation(v: [f64; 3]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_scaled_axis(Vector3::from(v))
    }

    /// log(e(δ) ⊗ q0) computed directly.
    fn phi(q0: &UnitQuaternion<f64>, d: &Vector3<f64>) -> Vector3<f64> {
        (UnitQuaternion::from_scaled_axis(*d) * q0).scaled_axis()
    }

    #[test]
    fn log_chart_matches_finite_differences() {
        let mu = Vector3::new(0.4, -1.3, 0.8);
        for v in [[0.4, -1.1, 0.9], [1e-4, 3e-4, -2e-4], [2.0, -1.5, 1.0]] {
            let q0 = rotation(v);
            let c = LogChart::new(&from_unit(&q0));
            assert!((c.value - Vector3::from(v)).norm() < 1e-14);
            let h = c.contracted_hessian(&mu);
            let eps = 1e-5;
            for j in 0..3 {
                let mut e = Vector3::zeros();
                e[j] = eps;
                let d = (phi(&q0, &e) - phi(&q0, &-e)) / (2.0 * eps);
                assert!((d - c.jac.column(j)).norm() < 1e-9, "jac {j} at {v:?}");
                for k in 0..3 {
                    let mut f = Vector3::zeros();
                    f[k] = eps;
                    let d2 = (phi(&q0, &(e + f)) - phi(&q0, &(e - f)) - phi(&q0, &(f - e))
                        + phi(&q0, &(-e - f)))
                        / (4.0 * eps * eps);
                    assert!(
                        (mu.dot(&d2) - h[(j, k)]).abs() < 1e-5,
                        "hess ({j},{k}) at {v:?}: {} vs {}",
                        mu.dot(&d2),
                        h[(j, k)]
                    );
                }
            }
        }
    }

    #[test]
    fn exp_chart_matches_finite_differences_and_the_closed_form() {
        let g = Vector3::new(-0.7, 0.2, 1.4);
        for v in [[0.4, -1.1, 0.9], [1e-4, 3e-4, -2e-4], [2.0, -1.5, 1.0]] {
            let u0 = Vector3::from(v);
            let c = ExpChart::new(&u0);
            // ζ(u) = log(e(u) ē(u0)) directly.
            let zeta = |u: &Vector3<f64>| {
                let q = mul(
                    &from_unit(&UnitQuaternion::from_scaled_axis(*u)),
                    &conj(&from_unit(&UnitQuaternion::from_scaled_axis(u0))),
                );
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
                    .scaled_axis()
            };
            let t = u0.norm();
            let k = crate::geometry::cross_matrix(&u0);
            let closed = Matrix3::identity()
                + k * ((1.0 - t.cos()) / (t * t))
                + k * k * ((t - t.sin()) / (t * t * t));
            assert!((closed - c.jac).norm() < 1e-8, "closed form at {v:?}");
            let h = c.contracted_hessian(&g);
            let eps = 1e-5;
            for j in 0..3 {
                let mut e = Vector3::zeros();
                e[j] = eps;
                let d = (zeta(&(u0 + e)) - zeta(&(u0 - e))) / (2.0 * eps);
                assert!((d - c.jac.column(j)).norm() < 1e-9, "jac {j} at {v:?}");
                for kk in 0..3 {
                    let mut f = Vector3::zeros();
                    f[kk] = eps;
                    let d2 = (zeta(&(u0 + e + f)) - zeta(&(u0 + e - f)) - zeta(&(u0 - e + f))
                        + zeta(&(u0 - e - f)))
                        / (4.0 * eps * eps);
                    assert!(
                        (g.dot(&d2) - h[(j, kk)]).abs() < 1e-5,
                        "hess ({j},{kk}) at {v:?}: {} vs {}",
                        g.dot(&d2),
                        h[(j, kk)]
                    );
                }
            }
        }
    }
}
