//! The Kirchhoff–Love bending term at a quadrature point (Kiendl et al. 2009, design.md
//! §3.4):
//!
//!   W_b = ½ (b − b̄)ᵀ K_b (b − b̄),  K_b from ½λ(tr N)² + μ tr(N²), N = ā⁻¹(b − b̄), × h³/12·dA,
//!
//! which is ½Dκ² per unit area for cylindrical bending. b_αβ = r,αβ·n with the exact unit
//! normal n = ã/|ã|, ã = r,2 × r,1; its first and second derivatives with respect to the
//! control points are written out below (checked against finite differences in
//! `tests/bspline_shell.rs`).
//!
//! With δã = A_k δP_k, A_k = N_k,1 [r,2]× − N_k,2 [r,1]×, and Q = (I − n nᵀ)/|ã| (so δn = Q δã):
//!
//!   ∂b_j/∂P_k = N_k,j n + A_kᵀ Q r,j,
//!
//! and, contracted with the bending stress M = ∂W/∂b (R = Σ M_j r,j, c = Q R, β = R·n,
//! Ñ_k = Σ M_j N_k,j):
//!
//!   Σ_j M_j ∂²b_j/∂P_k∂P_l = Ñ_k Q A_l + Ñ_l (Q A_k)ᵀ − [(A_kᵀc)(A_lᵀn)ᵀ + (A_kᵀn)(A_lᵀc)ᵀ]/|ã|
//!                            − β A_kᵀ Q A_l/|ã| + (N_k,1 N_l,2 − N_k,2 N_l,1)[c]×.

use nalgebra::{Matrix3, Vector3};

use crate::geometry::Vec3;

use super::forms::{Forms, SurfaceJet};
use super::patch::{TensorBasis, DU, DUU, DUV, DV, DVV};

/// The cross-product matrix [v]× (so that [v]× x = v × x).
fn cross_matrix(v: &Vec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// What the bending derivatives need at one point, computed once.
pub struct BendingKinematics {
    r1: Vec3,
    r2: Vec3,
    n: Vec3,
    /// Q r,j for j = 11, 12, 22.
    qr: [Vec3; 3],
}

impl BendingKinematics {
    /// Kinematics of `jet` with its `forms`.
    pub fn new(jet: &SurfaceJet, forms: &Forms) -> Self {
        let n = forms.n;
        let inv = 1.0 / forms.jacobian;
        let project = |v: &Vec3| (v - n * n.dot(v)) * inv;
        Self {
            r1: jet.r1,
            r2: jet.r2,
            n,
            qr: [
                project(&jet.r2nd[0]),
                project(&jet.r2nd[1]),
                project(&jet.r2nd[2]),
            ],
        }
    }

    /// A_kᵀ v for a function with basis `n`.
    #[inline]
    fn a_transpose(&self, nk: &TensorBasis, v: &Vec3) -> Vec3 {
        self.r1.cross(v) * nk[DV] - self.r2.cross(v) * nk[DU]
    }

    /// ∂b_j/∂P_k (columns j = 11, 12, 22).
    #[inline]
    pub fn strain_gradients(&self, nk: &TensorBasis) -> Matrix3<f64> {
        Matrix3::from_columns(&[
            self.n * nk[DUU] + self.a_transpose(nk, &self.qr[0]),
            self.n * nk[DUV] + self.a_transpose(nk, &self.qr[1]),
            self.n * nk[DVV] + self.a_transpose(nk, &self.qr[2]),
        ])
    }
}

/// The bending geometric stiffness Σ_j M_j ∂²b_j/∂P_k∂P_l at one point, for a given stress M.
///
/// Every term of the block formula (module docs) is bilinear in the per-function numbers
/// (N_k,1, N_k,2, Ñ_k) and (N_l,1, N_l,2, Ñ_l), so the block is assembled from per-function
/// matrices: block(k, l) = N_k,1 E¹_l + N_k,2 E²_l + Ñ_k Q A_l + Ñ_l (Q A_k)ᵀ, with
/// E¹_l = N_l,1 B₁₁ + N_l,2 B₁₂ and E²_l = N_l,1 B₂₁ + N_l,2 B₂₂ built from six point
/// matrices (four scaled 3×3 sums per block instead of the formula's dozen products).
pub struct BendingGeometric {
    moments: Vector3<f64>,
    /// Q [r,1]×, Q [r,2]×.
    q_r1x: Matrix3<f64>,
    q_r2x: Matrix3<f64>,
    b11: Matrix3<f64>,
    b12: Matrix3<f64>,
    b21: Matrix3<f64>,
    b22: Matrix3<f64>,
}

/// The per-function matrices of [`BendingGeometric`]: (Ñ_k, Q A_k, E¹_k, E²_k).
pub type FunctionGeometry = (f64, Matrix3<f64>, Matrix3<f64>, Matrix3<f64>);

impl BendingGeometric {
    /// Precomputes the contraction with `moments` (J, conjugate to (b₁₁, b₁₂, b₂₂)).
    pub fn new(jet: &SurfaceJet, forms: &Forms, moments: &Vector3<f64>) -> Self {
        let n = forms.n;
        let inv = 1.0 / forms.jacobian;
        let q = (Matrix3::identity() - n * n.transpose()) * inv;
        let r = jet.r2nd[0] * moments[0] + jet.r2nd[1] * moments[1] + jet.r2nd[2] * moments[2];
        let c = q * r;
        let beta = r.dot(&n) * inv;
        let (x1, x2) = (cross_matrix(&jet.r1), cross_matrix(&jet.r2));
        let (q1, q2) = (q * x1, q * x2);
        // a_i = [r,i]×ᵀ c, b_i = [r,i]×ᵀ n (so A_kᵀc = N_k,1 a₂ − N_k,2 a₁, likewise for n).
        let (a1, a2) = (c.cross(&jet.r1), c.cross(&jet.r2));
        let (e1, e2) = (n.cross(&jet.r1), n.cross(&jet.r2));
        let sym = |x: &Vec3, y: &Vec3| (x * y.transpose() + y * x.transpose()) * inv;
        let cross = |x: &Vec3, y: &Vec3| (x * y.transpose()) * inv;
        let cx = cross_matrix(&c);
        Self {
            moments: *moments,
            b11: -sym(&a2, &e2) - x2.transpose() * q2 * beta,
            b12: cross(&a2, &e1) + cross(&e2, &a1) + x2.transpose() * q1 * beta + cx,
            b21: cross(&a1, &e2) + cross(&e1, &a2) + x1.transpose() * q2 * beta - cx,
            b22: -sym(&a1, &e1) - x1.transpose() * q1 * beta,
            q_r1x: q1,
            q_r2x: q2,
        }
    }

    /// The per-function matrices of the function with basis `nk`.
    #[inline]
    pub fn function_data(&self, nk: &TensorBasis) -> FunctionGeometry {
        let m = &self.moments;
        let (k1, k2) = (nk[DU], nk[DV]);
        (
            m[0] * nk[DUU] + m[1] * nk[DUV] + m[2] * nk[DVV],
            self.q_r2x * k1 - self.q_r1x * k2,
            self.b11 * k1 + self.b12 * k2,
            self.b21 * k1 + self.b22 * k2,
        )
    }

    /// The 3×3 block (k, l) from the two functions' bases and data (inlined: it runs per
    /// block and point, and an out-of-line call returns the block through memory).
    #[inline]
    pub fn block(nk: &TensorBasis, dk: &FunctionGeometry, dl: &FunctionGeometry) -> Matrix3<f64> {
        dl.2 * nk[DU] + dl.3 * nk[DV] + dl.1 * dk.0 + dk.1.transpose() * dl.0
    }
}
