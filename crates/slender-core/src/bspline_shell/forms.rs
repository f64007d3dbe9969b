//! The fundamental forms of the deformed surface at a quadrature point, exactly from the
//! control points (Kiendl et al. 2009): tangents r,α, second derivatives r,αβ, the unit
//! normal n, the first fundamental form a_αβ = r,α·r,β and the second b_αβ = r,αβ·n.
//!
//! Symmetric 2×2 forms are stored as (X₁₁, X₁₂, X₂₂) with index 1 = u (length) and 2 = v
//! (width). The normal is n = (r,2 × r,1)/|r,2 × r,1|, which is +y on the rest strip.

use nalgebra::Vector3;

use crate::geometry::Vec3;

use super::patch::{TensorBasis, DU, DUU, DUV, DV, DVV};

/// Surface derivatives at a point: r,1, r,2, r,11, r,12, r,22 (m and dimensionless).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceJet {
    /// ∂r/∂u.
    pub r1: Vec3,
    /// ∂r/∂v.
    pub r2: Vec3,
    /// ∂²r/∂u², ∂²r/∂u∂v, ∂²r/∂v² (1/m).
    pub r2nd: [Vec3; 3],
}

impl SurfaceJet {
    /// The jet of the surface with control points `points[controls[k]]` and basis `basis[k]`
    /// (inlined into the element loops, once per point).
    #[inline]
    pub fn new<const NB: usize>(
        basis: &[TensorBasis; NB],
        controls: &[usize; NB],
        points: &[Vec3],
    ) -> Self {
        let mut jet = Self {
            r1: Vec3::zeros(),
            r2: Vec3::zeros(),
            r2nd: [Vec3::zeros(); 3],
        };
        for (n, &c) in basis.iter().zip(controls) {
            let p = &points[c];
            jet.r1 += p * n[DU];
            jet.r2 += p * n[DV];
            jet.r2nd[0] += p * n[DUU];
            jet.r2nd[1] += p * n[DUV];
            jet.r2nd[2] += p * n[DVV];
        }
        jet
    }

    /// The change of the jet when control point k moves by `d[k]`.
    pub fn of_step<const NB: usize>(basis: &[TensorBasis; NB], d: &[Vec3; NB]) -> (Vec3, Vec3) {
        let mut r1 = Vec3::zeros();
        let mut r2 = Vec3::zeros();
        for (n, dk) in basis.iter().zip(d) {
            r1 += dk * n[DU];
            r2 += dk * n[DV];
        }
        (r1, r2)
    }
}

/// The forms at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Forms {
    /// First fundamental form (a₁₁, a₁₂, a₂₂).
    pub a: Vector3<f64>,
    /// Second fundamental form (b₁₁, b₁₂, b₂₂) (1/m).
    pub b: Vector3<f64>,
    /// Unit normal.
    pub n: Vec3,
    /// |r,2 × r,1|: the area element relative to the parameter plane.
    pub jacobian: f64,
}

impl Forms {
    /// The forms of `jet`.
    pub fn new(jet: &SurfaceJet) -> Self {
        let normal = jet.r2.cross(&jet.r1);
        let jacobian = normal.norm();
        let n = normal / jacobian;
        Self {
            a: first_form(&jet.r1, &jet.r2),
            b: Vector3::new(
                jet.r2nd[0].dot(&n),
                jet.r2nd[1].dot(&n),
                jet.r2nd[2].dot(&n),
            ),
            n,
            jacobian,
        }
    }
}

/// (r₁·r₁, r₁·r₂, r₂·r₂).
pub fn first_form(r1: &Vec3, r2: &Vec3) -> Vector3<f64> {
    Vector3::new(r1.dot(r1), r1.dot(r2), r2.dot(r2))
}
