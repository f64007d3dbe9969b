//! St-Venant–Kirchhoff membrane energy of one triangle (design.md §3.2):
//!
//!   E = Ā (h/4) [ ½λ (tr M)² + μ tr(M²) ],  M = ā⁻¹(a − ā),
//!
//! with a the first fundamental form in the edge basis e₁ = q₁ − q₀, e₂ = q₂ − q₀, ā its rest
//! value, Ā the rest area and λ, μ the 2-D (plane-stress) Lamé constants.
//! M/2 is the Green strain, so this is h[½λ(tr E)² + μ tr E²] per unit rest area.

use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector3};

use crate::geometry::Vec3;

/// Rest data of a face shared by the membrane and bending terms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceRest {
    /// Inverse of the rest first fundamental form ā (1/m²).
    pub abar_inv: Matrix2<f64>,
    /// Rest first fundamental form ā (m²), entries (ā₁₁, ā₁₂, ā₂₂).
    pub abar: Vector3<f64>,
    /// Rest area Ā (m²).
    pub area: f64,
}

impl FaceRest {
    /// Rest data of the triangle (q₀, q₁, q₂).
    pub fn new(q: [&Vec3; 3]) -> Self {
        let e1 = q[1] - q[0];
        let e2 = q[2] - q[0];
        let a = Matrix2::new(e1.dot(&e1), e1.dot(&e2), e1.dot(&e2), e2.dot(&e2));
        Self {
            abar_inv: a.try_inverse().unwrap_or_else(Matrix2::zeros),
            abar: Vector3::new(a[(0, 0)], a[(0, 1)], a[(1, 1)]),
            area: 0.5 * e1.cross(&e2).norm(),
        }
    }
}

/// Energy density coefficients of a quadratic form ½λ(tr P X)² + μ tr(PXPX) in the symmetric
/// 2×2 matrix X stored as x = (X₁₁, X₁₂, X₂₂), with P = ā⁻¹; scaled by `scale`.
///
/// Returns K (3×3) such that the form is ½ xᵀ K x: the form is quadratic, so its Hessian is
/// its gradient map applied to the unit vectors.
pub fn quadratic_form(p: &Matrix2<f64>, lambda: f64, mu: f64, scale: f64) -> Matrix3<f64> {
    let grad = |x: &Vector3<f64>| -> Vector3<f64> {
        let xm = Matrix2::new(x[0], x[1], x[1], x[2]);
        let tr = (p * xm).trace();
        // d/dX of the form, as a symmetric matrix S; the off-diagonal entry appears twice.
        let s = p * (lambda * tr) + p * xm * p * (2.0 * mu);
        Vector3::new(s[(0, 0)], 2.0 * s[(0, 1)], s[(1, 1)]) * scale
    };
    let mut k = Matrix3::zeros();
    for c in 0..3 {
        let mut unit = Vector3::zeros();
        unit[c] = 1.0;
        k.set_column(c, &grad(&unit));
    }
    // Symmetrize away round-off.
    (k + k.transpose()) * 0.5
}

/// Vertex-coefficient matrices of a₁₁, a₁₂, a₂₂: a_k = Σ_mn S_k[m][n] q_m·q_n (symmetric S_k).
const FFF_COEFFS: [[[f64; 3]; 3]; 3] = [
    [[1.0, -1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 0.0]],
    [[1.0, -0.5, -0.5], [-0.5, 0.0, 0.5], [-0.5, 0.5, 0.0]],
    [[1.0, 0.0, -1.0], [0.0, 0.0, 0.0], [-1.0, 0.0, 1.0]],
];

/// Membrane energy (J) of the face (q₀, q₁, q₂) with rest data `rest`, thickness `h` (m) and
/// 2-D Lamé constants `lambda`, `mu` (Pa). Adds the gradient (9: q₀, q₁, q₂) and Hessian to
/// `grad` and `hess` when given.
///
/// With a Newton-step remainder `remainder` (m², see [`super::mixed_update`]) the Hessian's
/// geometric stiffness uses the stress of the linearly updated form a − r (the
/// mixed-integration-point iteration); energy and gradient never depend on it.
#[allow(clippy::too_many_arguments)]
pub fn membrane_energy(
    q: [&Vec3; 3],
    rest: &FaceRest,
    h: f64,
    lambda: f64,
    mu: f64,
    remainder: Option<&Vector3<f64>>,
    grad: Option<&mut SVector<f64, 9>>,
    hess: Option<&mut SMatrix<f64, 9, 9>>,
) -> f64 {
    let e1 = q[1] - q[0];
    let e2 = q[2] - q[0];
    let d = Vector3::new(e1.dot(&e1), e1.dot(&e2), e2.dot(&e2)) - rest.abar;
    let k = quadratic_form(&rest.abar_inv, lambda, mu, rest.area * h / 4.0);
    let g_a = k * d;
    let energy = 0.5 * d.dot(&g_a);
    if grad.is_none() && hess.is_none() {
        return energy;
    }
    // ∇a_k: block m is 2 Σ_n S_k[m][n] q_n.
    let mut da = SMatrix::<f64, 9, 3>::zeros();
    for (kk, s) in FFF_COEFFS.iter().enumerate() {
        for (m, row) in s.iter().enumerate() {
            let mut v = Vec3::zeros();
            for (qn, c) in q.iter().zip(row) {
                v += *qn * (2.0 * c);
            }
            da.fixed_view_mut::<3, 1>(3 * m, kk).copy_from(&v);
        }
    }
    if let Some(g) = grad {
        *g += da * g_a;
    }
    if let Some(hm) = hess {
        *hm += da * k * da.transpose();
        let stress = match remainder {
            Some(r) => k * (d - r),
            None => g_a,
        };
        for (kk, s) in FFF_COEFFS.iter().enumerate() {
            for m in 0..3 {
                for n in 0..3 {
                    let c = 2.0 * s[m][n] * stress[kk];
                    if c != 0.0 {
                        for t in 0..3 {
                            hm[(3 * m + t, 3 * n + t)] += c;
                        }
                    }
                }
            }
        }
    }
    energy
}
