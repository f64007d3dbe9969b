//! Small geometric primitives shared by the rod model: parallel transport, signed angles,
//! rotations about an axis and the cross-product matrix.

use nalgebra::{Matrix3, Vector3};

/// 3-vector of f64 (m or dimensionless, as the caller uses it).
pub type Vec3 = Vector3<f64>;

/// The matrix `[a]×` with `[a]× b = a × b`.
pub fn cross_matrix(a: &Vec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// Parallel transport of `u` from unit tangent `from` to unit tangent `to`: the rotation about
/// `from × to` that carries `from` onto `to`, applied to `u`.
///
/// Returns `u` unchanged when the tangents are parallel. Undefined (the caller must avoid it)
/// when they are antiparallel; the solver's step cap keeps edges from turning by more than π/4.
pub fn parallel_transport(u: &Vec3, from: &Vec3, to: &Vec3) -> Vec3 {
    let b = from.cross(to);
    if b.norm_squared() <= (f64::EPSILON * 16.0).powi(2) {
        return *u;
    }
    // The rotation about b = from × to that takes `from` to `to` (Rodrigues' formula with
    // sin = |b| and 1 − cos = |b|²/(1 + cos)): no square root, no trigonometry.
    let bu = b.cross(u);
    u + bu + b.cross(&bu) / (1.0 + from.dot(to))
}

/// Signed angle (rad, in (−π, π]) from `u` to `v` about `axis` (right-hand rule). `u` and `v`
/// are assumed orthogonal to `axis`.
pub fn signed_angle(u: &Vec3, v: &Vec3, axis: &Vec3) -> f64 {
    let w = u.cross(v);
    let angle = w.norm().atan2(u.dot(v));
    if axis.dot(&w) < 0.0 {
        -angle
    } else {
        angle
    }
}

/// Rotates `v` about the unit vector `axis` by `angle` (rad), Rodrigues' formula.
pub fn rotate_about_axis(v: &Vec3, axis: &Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c))
}

/// A unit vector orthogonal to the unit vector `t`, chosen deterministically.
pub fn any_orthogonal(t: &Vec3) -> Vec3 {
    // Cross with the coordinate axis least aligned with t for the best conditioning.
    let a = t.abs();
    let e = if a.x <= a.y && a.x <= a.z {
        Vec3::x()
    } else if a.y <= a.z {
        Vec3::y()
    } else {
        Vec3::z()
    };
    t.cross(&e).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transport_maps_tangent_and_preserves_angles() {
        let from = Vec3::new(1.0, 0.2, -0.3).normalize();
        let to = Vec3::new(0.1, 1.0, 0.5).normalize();
        let u = any_orthogonal(&from);
        let tu = parallel_transport(&u, &from, &to);
        assert!((parallel_transport(&from, &from, &to) - to).norm() < 1e-14);
        assert!(tu.dot(&to).abs() < 1e-14);
        assert!((tu.norm() - 1.0).abs() < 1e-14);
        // The binormal is fixed by the transport.
        let b = from.cross(&to).normalize();
        assert!((parallel_transport(&b, &from, &to) - b).norm() < 1e-14);
    }

    #[test]
    fn signed_angle_and_rotation_agree() {
        let axis = Vec3::new(0.3, -0.4, 0.8).normalize();
        let u = any_orthogonal(&axis);
        for &a in &[-3.0, -1.0, 0.0, 0.5, 2.9] {
            let v = rotate_about_axis(&u, &axis, a);
            assert!((signed_angle(&u, &v, &axis) - a).abs() < 1e-13);
        }
    }

    #[test]
    fn cross_matrix_is_cross_product() {
        let a = Vec3::new(1.0, 2.0, 3.0);
        let b = Vec3::new(-0.5, 0.25, 4.0);
        assert!((cross_matrix(&a) * b - a.cross(&b)).norm() < 1e-14);
    }
}
