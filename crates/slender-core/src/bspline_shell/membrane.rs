//! The St-Venant–Kirchhoff membrane term at a quadrature point (design.md §3.2, §3.4):
//!
//!   W_m = ½ (a − ā)ᵀ K_m (a − ā),  K_m from ½λ(tr M)² + μ tr(M²), M = ā⁻¹(a − ā), × h/4·dA,
//!
//! i.e. h[½λ(tr E)² + μ tr E²] per unit rest area with the Green strain E = (a − ā)/2 and the
//! 2-D (plane-stress) Lamé constants. a is quadratic in the control points, so its second
//! derivatives are constants: ∂²a₁₁/∂P_k∂P_l = 2N_k,1 N_l,1 I, and so on.

use nalgebra::Matrix3;

use crate::geometry::Vec3;

use super::patch::{TensorBasis, DU, DV};

/// ∂a_j/∂P_k for the function with basis `n` (columns j = 11, 12, 22).
#[inline]
pub fn strain_gradients(n: &TensorBasis, r1: &Vec3, r2: &Vec3) -> Matrix3<f64> {
    Matrix3::from_columns(&[
        r1 * (2.0 * n[DU]),
        r2 * n[DU] + r1 * n[DV],
        r2 * (2.0 * n[DV]),
    ])
}

/// Σ_j S_j ∂²a_j/∂P_k∂P_l (a multiple of the identity, this scalar) for the stress S =
/// ∂W/∂a (N/m·m², conjugate to (a₁₁, a₁₂, a₂₂)): the membrane's geometric stiffness.
#[inline]
pub fn geometric_coefficient(
    nk: &TensorBasis,
    nl: &TensorBasis,
    stress: &nalgebra::Vector3<f64>,
) -> f64 {
    2.0 * stress[0] * nk[DU] * nl[DU]
        + stress[1] * (nk[DU] * nl[DV] + nk[DV] * nl[DU])
        + 2.0 * stress[2] * nk[DV] * nl[DV]
}
