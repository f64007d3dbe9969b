//! The twist angle of a rotation about a fixed axis (swing–twist decomposition), with its
//! derivatives in the quaternion's components.
//!
//! Any rotation q factors as q = q_swing ⊗ q_twist with q_twist about the unit axis a and
//! q_swing about an axis ⊥ a; the twist angle is τ = 2 atan2(a·v, w). For a rotation about a
//! itself τ is its angle, so −M τ is the exact potential of a dead moment M a for every
//! rotation about a, and a conservative potential for all others. It is defined unless
//! a·v = w = 0 (a half turn about an axis ⊥ a). Its value is determined up to 2π (and q ≡ −q
//! shifts it by 2π); callers unwrap it by continuity.

use nalgebra::{Matrix4, Vector3};

use super::quaternion::{vector_part, Quat};

/// τ(q) about one axis with its gradient and Hessian in (w, x, y, z).
#[derive(Clone, Copy, Debug)]
pub struct TwistAngle {
    /// τ (rad), in (−2π, 2π].
    pub value: f64,
    /// ∂τ/∂q.
    pub grad: Quat,
    /// ∂²τ/∂q².
    pub hess: Matrix4<f64>,
}

/// The twist angle of `q` about the unit axis `axis` (both in the same coordinates).
pub fn twist_angle(q: &Quat, axis: &Vector3<f64>) -> TwistAngle {
    let w = q[0];
    let alpha = axis.dot(&vector_part(q));
    let rho = alpha * alpha + w * w;
    // τ = 2 atan2(α, w): τ_α = 2w/ρ, τ_w = −2α/ρ, τ_αα = −4wα/ρ², τ_ww = 4wα/ρ²,
    // τ_αw = 2(α² − w²)/ρ².
    let t_a = 2.0 * w / rho;
    let t_w = -2.0 * alpha / rho;
    let r2 = rho * rho;
    let t_aa = -4.0 * w * alpha / r2;
    let t_ww = 4.0 * w * alpha / r2;
    let t_aw = 2.0 * (alpha * alpha - w * w) / r2;
    let mut grad = Quat::zeros();
    grad[0] = t_w;
    let mut hess = Matrix4::zeros();
    hess[(0, 0)] = t_ww;
    for j in 0..3 {
        grad[j + 1] = t_a * axis[j];
        hess[(0, j + 1)] = t_aw * axis[j];
        hess[(j + 1, 0)] = t_aw * axis[j];
        for k in 0..3 {
            hess[(j + 1, k + 1)] = t_aa * axis[j] * axis[k];
        }
    }
    TwistAngle {
        value: 2.0 * alpha.atan2(w),
        grad,
        hess,
    }
}

/// `angle` − `reference` brought into (−π, π]: the continuation of an unwrapped angle.
pub fn wrapped_difference(angle: f64, reference: f64) -> f64 {
    let two_pi = std::f64::consts::TAU;
    let d = (angle - reference) % two_pi;
    if d > std::f64::consts::PI {
        d - two_pi
    } else if d <= -std::f64::consts::PI {
        d + two_pi
    } else {
        d
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    #[test]
    fn rotations_about_the_axis_are_measured_exactly() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        for angle in [-2.5, -0.3, 0.0, 1.0, 3.0] {
            let q = UnitQuaternion::from_scaled_axis(axis * angle);
            let t = twist_angle(&super::super::quaternion::from_unit(&q), &axis);
            assert!((wrapped_difference(t.value, angle)).abs() < 1e-14);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let axis = Vector3::new(0.3, -0.5, 0.8).normalize();
        let q = Quat::new(0.6, -0.3, 0.5, 0.2);
        let t = twist_angle(&q, &axis);
        let eps = 1e-6;
        for i in 0..4 {
            let mut e = Quat::zeros();
            e[i] = eps;
            let d = (twist_angle(&(q + e), &axis).value - twist_angle(&(q - e), &axis).value)
                / (2.0 * eps);
            assert!((d - t.grad[i]).abs() < 1e-8);
            let dg = (twist_angle(&(q + e), &axis).grad - twist_angle(&(q - e), &axis).grad)
                / (2.0 * eps);
            assert!((dg - t.hess.column(i)).norm() < 1e-7);
        }
    }
}
