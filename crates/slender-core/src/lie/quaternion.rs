//! Quaternions as 4-vectors (w, x, y, z), and the exact second-order expansion of a rotation,
//! or of the relative rotation of two frames, under spatial rotation-vector increments.
//!
//! With e(ω) = (1 − |ω|²/8, ω/2) + O(|ω|³), the rotated quaternion e(ω) ⊗ p is a quadratic
//! polynomial in ω up to third-order terms, so its first and second derivatives at ω = 0 are
//! read off exactly; any function of it is then differentiated by the chain rule.

use nalgebra::{Matrix3, SMatrix, UnitQuaternion, Vector3, Vector4};

use crate::geometry::cross_matrix;

/// A quaternion as the 4-vector (w, x, y, z).
pub type Quat = Vector4<f64>;

/// The 4-vector (w, x, y, z) of a unit quaternion.
pub fn from_unit(q: &UnitQuaternion<f64>) -> Quat {
    Quat::new(q.w, q.i, q.j, q.k)
}

/// Hamilton product a ⊗ b.
pub fn mul(a: &Quat, b: &Quat) -> Quat {
    let (aw, ax, ay, az) = (a[0], a[1], a[2], a[3]);
    let (bw, bx, by, bz) = (b[0], b[1], b[2], b[3]);
    Quat::new(
        aw * bw - ax * bx - ay * by - az * bz,
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
    )
}

/// Conjugate (w, −v).
pub fn conj(a: &Quat) -> Quat {
    Quat::new(a[0], -a[1], -a[2], -a[3])
}

/// The vector part v.
pub fn vector_part(a: &Quat) -> Vector3<f64> {
    Vector3::new(a[1], a[2], a[3])
}

/// Half of the pure unit quaternion e_i (i = 0, 1, 2): the derivative of e(ω) along ω_i.
fn half_unit(i: usize) -> Quat {
    let mut e = Quat::zeros();
    e[i + 1] = 0.5;
    e
}

/// The relative rotation Q = R_aᵀ R_b of two frames as the quaternion q = p̄_a ⊗ p_b (sign
/// chosen so that w ≥ 0, i.e. the rotation angle is in [0, π]), expressed in frame a, with its
/// expansion in the spatial increments a, b of the two frames: q(a, b) = p̄_a ē(a) e(b) p_b.
#[derive(Clone, Copy, Debug)]
pub struct RelativeRotation {
    /// q at a = b = 0.
    pub q: Quat,
    /// ∂q/∂b (4×3), column i = ½ p̄_a e_i p_b; ∂q/∂a = −∂q/∂b.
    pub jac_b: SMatrix<f64, 4, 3>,
}

/// The relative rotation p̄_a ⊗ p_b alone, sign chosen so that w ≥ 0.
pub fn relative_quaternion(pa: &UnitQuaternion<f64>, pb: &UnitQuaternion<f64>) -> Quat {
    let q = mul(&conj(&from_unit(pa)), &from_unit(pb));
    if q[0] < 0.0 {
        -q
    } else {
        q
    }
}

impl RelativeRotation {
    /// The relative rotation from frame `pa` to frame `pb`.
    pub fn new(pa: &UnitQuaternion<f64>, pb: &UnitQuaternion<f64>) -> Self {
        let pa_bar = conj(&from_unit(pa));
        let mut pb = from_unit(pb);
        let mut q = mul(&pa_bar, &pb);
        if q[0] < 0.0 {
            q = -q;
            pb = -pb;
        }
        let mut jac_b = SMatrix::<f64, 4, 3>::zeros();
        for i in 0..3 {
            jac_b.set_column(i, &mul(&mul(&pa_bar, &half_unit(i)), &pb));
        }
        Self { q, jac_b }
    }

    /// ∂q/∂(a, b) (4×6, the increment of frame a first).
    pub fn jacobian(&self) -> SMatrix<f64, 4, 6> {
        let mut j = SMatrix::<f64, 4, 6>::zeros();
        j.fixed_view_mut::<4, 3>(0, 0).copy_from(&(-self.jac_b));
        j.fixed_view_mut::<4, 3>(0, 3).copy_from(&self.jac_b);
        j
    }

    /// Σ_m λ_m ∂²q_m/∂(a, b)² (6×6). From q(a, b) = q + ½p̄_a(b − a)p_b − (|a|²+|b|²)/8 q
    /// − ¼ p̄_a a b p_b + O(3) and e_i e_k = −δ_ik + ε_ikl e_l: the diagonal blocks are
    /// −¼(λ·q) I, the (a, b) block ¼(λ·q) I + ½[c]× with c = (∂q/∂b)ᵀλ.
    pub fn contracted_hessian(&self, lambda: &Quat) -> SMatrix<f64, 6, 6> {
        let s = lambda.dot(&self.q);
        let c: Vector3<f64> = self.jac_b.transpose() * lambda;
        let diag = Matrix3::identity() * (-0.25 * s);
        let ab = Matrix3::identity() * (0.25 * s) + cross_matrix(&c) * 0.5;
        let mut h = SMatrix::<f64, 6, 6>::zeros();
        h.fixed_view_mut::<3, 3>(0, 0).copy_from(&diag);
        h.fixed_view_mut::<3, 3>(3, 3).copy_from(&diag);
        h.fixed_view_mut::<3, 3>(0, 3).copy_from(&ab);
        h.fixed_view_mut::<3, 3>(3, 0).copy_from(&ab.transpose());
        h
    }
}

/// One rotation q (e.g. a frame relative to its rest orientation, in space) with its
/// expansion in a spatial increment ω: q(ω) = e(ω) ⊗ q.
#[derive(Clone, Copy, Debug)]
pub struct SingleRotation {
    /// q at ω = 0.
    pub q: Quat,
    /// ∂q/∂ω (4×3), column i = ½ e_i q.
    pub jac: SMatrix<f64, 4, 3>,
}

impl SingleRotation {
    /// The expansion of e(ω) ⊗ `q`.
    pub fn new(q: Quat) -> Self {
        let mut jac = SMatrix::<f64, 4, 3>::zeros();
        for i in 0..3 {
            jac.set_column(i, &mul(&half_unit(i), &q));
        }
        Self { q, jac }
    }

    /// Σ_m λ_m ∂²q_m/∂ω² = −¼(λ·q) I (from −|ω|²/8 q).
    pub fn contracted_hessian(&self, lambda: &Quat) -> Matrix3<f64> {
        Matrix3::identity() * (-0.25 * lambda.dot(&self.q))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rot(v: [f64; 3]) -> UnitQuaternion<f64> {
        UnitQuaternion::from_scaled_axis(Vector3::from(v))
    }

    /// q(a, b) computed exactly.
    fn exact(
        pa: &UnitQuaternion<f64>,
        pb: &UnitQuaternion<f64>,
        a: &Vector3<f64>,
        b: &Vector3<f64>,
    ) -> Quat {
        let pa2 = UnitQuaternion::from_scaled_axis(*a) * pa;
        let pb2 = UnitQuaternion::from_scaled_axis(*b) * pb;
        from_unit(&(pa2.inverse() * pb2))
    }

    #[test]
    fn relative_expansion_matches_finite_differences() {
        let pa = rot([0.3, -1.1, 0.4]);
        let pb = rot([1.2, 0.2, -0.7]);
        let r = RelativeRotation::new(&pa, &pb);
        let sign = if from_unit(&(pa.inverse() * pb))[0] < 0.0 {
            -1.0
        } else {
            1.0
        };
        let j = r.jacobian();
        let lambda = Quat::new(0.3, -0.8, 0.5, 1.1);
        let h = r.contracted_hessian(&lambda);
        let eps = 1e-4;
        let f = |y: &SMatrix<f64, 6, 1>| {
            let a = Vector3::new(y[0], y[1], y[2]);
            let b = Vector3::new(y[3], y[4], y[5]);
            exact(&pa, &pb, &a, &b) * sign
        };
        for i in 0..6 {
            let mut yi = SMatrix::<f64, 6, 1>::zeros();
            yi[i] = eps;
            let d = (f(&yi) - f(&-yi)) / (2.0 * eps);
            assert!((d - j.column(i)).norm() < 1e-8, "column {i}");
            for k in 0..6 {
                let mut yk = SMatrix::<f64, 6, 1>::zeros();
                yk[k] = eps;
                let d2 = (f(&(yi + yk)) - f(&(yi - yk)) - f(&(yk - yi)) + f(&(-yi - yk)))
                    / (4.0 * eps * eps);
                assert!((lambda.dot(&d2) - h[(i, k)]).abs() < 1e-6, "({i}, {k})");
            }
        }
    }
}
