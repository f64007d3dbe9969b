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
    fn a_transpose(&self, nk: &TensorBasis, v: &Vec3) -> Vec3 {
        self.r1.cross(v) * nk[DV] - self.r2.cross(v) * nk[DU]
    }

    /// ∂b_j/∂P_k (columns j = 11, 12, 22).
    pub fn strain_gradients(&self, nk: &TensorBasis) -> Matrix3<f64> {
        Matrix3::from_columns(&[
            self.n * nk[DUU] + self.a_transpose(nk, &self.qr[0]),
            self.n * nk[DUV] + self.a_transpose(nk, &self.qr[1]),
            self.n * nk[DVV] + self.a_transpose(nk, &self.qr[2]),
        ])
    }
}

/// The bending geometric stiffness Σ_j M_j ∂²b_j/∂P_k∂P_l at one point, for a given stress M.
pub struct BendingGeometric {
    moments: Vector3<f64>,
    inv_jacobian: f64,
    beta: f64,
    /// Q [r,1]×, Q [r,2]×.
    q_r1x: Matrix3<f64>,
    q_r2x: Matrix3<f64>,
    /// [r,a]×ᵀ Q [r,b]× for (a, b) = (1,1), (1,2), (2,1), (2,2).
    t11: Matrix3<f64>,
    t12: Matrix3<f64>,
    t21: Matrix3<f64>,
    t22: Matrix3<f64>,
    cx: Matrix3<f64>,
    c: Vec3,
    kin_n: Vec3,
}

impl BendingGeometric {
    /// Precomputes the contraction with `moments` (J, conjugate to (b₁₁, b₁₂, b₂₂)).
    pub fn new(jet: &SurfaceJet, forms: &Forms, moments: &Vector3<f64>) -> Self {
        let n = forms.n;
        let inv = 1.0 / forms.jacobian;
        let q = (Matrix3::identity() - n * n.transpose()) * inv;
        let r = jet.r2nd[0] * moments[0] + jet.r2nd[1] * moments[1] + jet.r2nd[2] * moments[2];
        let c = q * r;
        let (x1, x2) = (cross_matrix(&jet.r1), cross_matrix(&jet.r2));
        let (q1, q2) = (q * x1, q * x2);
        Self {
            moments: *moments,
            inv_jacobian: inv,
            beta: r.dot(&n),
            t11: x1.transpose() * q1,
            t12: x1.transpose() * q2,
            t21: x2.transpose() * q1,
            t22: x2.transpose() * q2,
            q_r1x: q1,
            q_r2x: q2,
            cx: cross_matrix(&c),
            c,
            kin_n: n,
        }
    }

    /// Per-function data: (Ñ_k, Q A_k, A_kᵀc, A_kᵀn).
    pub fn function_data(
        &self,
        kin: &BendingKinematics,
        nk: &TensorBasis,
    ) -> (f64, Matrix3<f64>, Vec3, Vec3) {
        let m = &self.moments;
        (
            m[0] * nk[DUU] + m[1] * nk[DUV] + m[2] * nk[DVV],
            self.q_r2x * nk[DU] - self.q_r1x * nk[DV],
            kin.a_transpose(nk, &self.c),
            kin.a_transpose(nk, &self.kin_n),
        )
    }

    /// The 3×3 block (k, l) from the two functions' bases and data.
    pub fn block(
        &self,
        nk: &TensorBasis,
        nl: &TensorBasis,
        dk: &(f64, Matrix3<f64>, Vec3, Vec3),
        dl: &(f64, Matrix3<f64>, Vec3, Vec3),
    ) -> Matrix3<f64> {
        let (k1, k2, l1, l2) = (nk[DU], nk[DV], nl[DU], nl[DV]);
        let aqa = self.t22 * (k1 * l1) - self.t21 * (k1 * l2) - self.t12 * (k2 * l1)
            + self.t11 * (k2 * l2);
        dl.1 * dk.0 + dk.1.transpose() * dl.0
            - (dk.2 * dl.3.transpose() + dk.3 * dl.2.transpose()) * self.inv_jacobian
            - aqa * (self.beta * self.inv_jacobian)
            + self.cx * (k1 * l2 - k2 * l1)
    }
}
