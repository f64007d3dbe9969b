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
    u + bu + b.cross(&bu) * (1.0 / (1.0 + from.dot(to)))
}

/// `v / |v|`, with one division (nalgebra's `normalize` divides each component).
#[inline]
pub fn unit(v: &Vec3) -> Vec3 {
    v * (1.0 / v.norm())
}

/// Signed angle (rad, in (−π, π]) from `u` to `v` about `axis` (right-hand rule). `u` and `v`
/// are assumed orthogonal to `axis`.
pub fn signed_angle(u: &Vec3, v: &Vec3, axis: &Vec3) -> f64 {
    let w = u.cross(v);
    let angle = atan2(w.norm(), u.dot(v));
    if axis.dot(&w) < 0.0 {
        -angle
    } else {
        angle
    }
}

/// (sin x, cos x) for an angle x (rad). The angles of a rod's steps and material frames are
/// mostly small, and there the Taylor series (terms to x¹³ and x¹⁴, truncation below 1e-27
/// relative for |x| ≤ 0.1) costs a few multiplications where libm's general `sin_cos`, with
/// its argument reduction, costs about a hundred instructions; that is why this is written
/// by hand. Larger angles go to `sin_cos`. Either way the result is within a few ulps.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > 0.1 {
        return x.sin_cos();
    }
    let x2 = x * x;
    // Horner in x², the leading term added last so that the correction is small against it.
    const S: [f64; 6] = [
        -1.0 / 6.0,
        1.0 / 120.0,
        -1.0 / 5040.0,
        1.0 / 362_880.0,
        -1.0 / 39_916_800.0,
        1.0 / 6_227_020_800.0,
    ];
    const C: [f64; 7] = [
        -1.0 / 2.0,
        1.0 / 24.0,
        -1.0 / 720.0,
        1.0 / 40_320.0,
        -1.0 / 3_628_800.0,
        1.0 / 479_001_600.0,
        -1.0 / 87_178_291_200.0,
    ];
    let ps = S[0] + x2 * (S[1] + x2 * (S[2] + x2 * (S[3] + x2 * (S[4] + x2 * S[5]))));
    let pc = C[0] + x2 * (C[1] + x2 * (C[2] + x2 * (C[3] + x2 * (C[4] + x2 * (C[5] + x2 * C[6])))));
    let sin = x + x * x2 * ps;
    let cos = 1.0 + x2 * pc;
    (sin, cos)
}

/// atan2(y, x) (rad, in (−π, π]). The reference twists and turns of a rod's frames are mostly
/// small angles, and for |y| ≤ 0.1·x the Taylor series of atan(y/x) (terms to z¹⁵, truncation
/// below 1e-17 relative) costs a division and a few multiplications where libm's general
/// `atan2` costs about a hundred instructions; that is why this is written by hand, as
/// [`sin_cos`] is. Other arguments go to `atan2`. Either way the result is within a few ulps.
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    if !(x > 0.0 && y.abs() <= 0.1 * x) {
        return y.atan2(x);
    }
    let z = y / x;
    if z == 0.0 {
        // ±0 (or an underflow to it) keeps its sign, as atan2 does.
        return z;
    }
    let z2 = z * z;
    // Horner in z², the leading term added last so that the correction is small against it.
    const A: [f64; 7] = [
        -1.0 / 3.0,
        1.0 / 5.0,
        -1.0 / 7.0,
        1.0 / 9.0,
        -1.0 / 11.0,
        1.0 / 13.0,
        -1.0 / 15.0,
    ];
    let p = A[0] + z2 * (A[1] + z2 * (A[2] + z2 * (A[3] + z2 * (A[4] + z2 * (A[5] + z2 * A[6])))));
    z + z * z2 * p
}

/// Rotates `v` about the unit vector `axis` by `angle` (rad), Rodrigues' formula.
#[inline]
pub fn rotate_about_axis(v: &Vec3, axis: &Vec3, angle: f64) -> Vec3 {
    let (s, c) = sin_cos(angle);
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
    fn small_angle_sin_cos_matches_libm() {
        // Both branches, the switch point and the extremes of the series' range: within a
        // few ulps of libm (a dropped or wrong term would be off by far more at 0.1).
        for k in -2000..=2000 {
            let x = k as f64 * 1e-4 + 1.3e-7;
            let (s, c) = sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!(
                (s - s0).abs() <= 4.0 * f64::EPSILON * s0.abs(),
                "sin {x}: {s} vs {s0}"
            );
            assert!((c - c0).abs() <= 4.0 * f64::EPSILON, "cos {x}: {c} vs {c0}");
        }
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(2.0), 2.0_f64.sin_cos());
    }

    #[test]
    fn small_angle_atan2_matches_libm() {
        // Both branches, the switch point, signs, scales and the degenerate arguments: within
        // a few ulps of libm (a dropped or wrong term would be off by far more at 0.1).
        for k in -3000..=3000 {
            let t = k as f64 * 5e-5 + 1.3e-7;
            for (y, x) in [
                (t, 1.0),
                (3.7e-4 * t, 3.7e-4),
                (2.5e3 * t, -2.5e3),
                (1.0, t),
            ] {
                let (a, a0) = (atan2(y, x), y.atan2(x));
                assert!(
                    (a - a0).abs() <= 4.0 * f64::EPSILON * a0.abs(),
                    "atan2({y}, {x}): {a} vs {a0}"
                );
            }
        }
        for (y, x) in [
            (0.0, 1.0),
            (-0.0, 1.0),
            (0.0, 0.0),
            (0.0, -1.0),
            (1e-300, 1e-290),
        ] {
            assert_eq!(
                atan2(y, x).to_bits(),
                f64::atan2(y, x).to_bits(),
                "atan2({y}, {x})"
            );
        }
        assert!(atan2(f64::NAN, 1.0).is_nan() && atan2(0.01, f64::NAN).is_nan());
    }

    #[test]
    fn cross_matrix_is_cross_product() {
        let a = Vec3::new(1.0, 2.0, 3.0);
        let b = Vec3::new(-0.5, 0.25, 4.0);
        assert!((cross_matrix(&a) * b - a.cross(&b)).norm() < 1e-14);
    }
}
