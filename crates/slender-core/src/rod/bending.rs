//! The bending energy of a discrete elastic rod.
//!
//! At each hinge the material curvatures are (Bergou et al. 2010, averaged material frame)
//! κ₁ = ½ κb·(m₂ᵉ + m₂ᶠ), κ₂ = −½ κb·(m₁ᵉ + m₁ᶠ), integrated (dimensionless) quantities. The
//! energy is E_b = (EI₁ (κ₁ − κ̄₁)² + EI₂ (κ₂ − κ̄₂)²) / (2 l̄) with the hinge's Voronoi length
//! l̄ (half the adjacent rest edges; half of the single real edge at a clamp). The closed-form
//! derivatives are those of Kaufman et al. 2014 / DisMech (design.md §2.1), verified here by
//! finite differences.

use nalgebra::Matrix3;

use crate::geometry::cross_matrix;

use super::hinge::{EdgeGradient, EdgeHessian, HingeFrame, HingeVector};

/// Material curvatures (κ₁, κ₂) of a hinge.
pub fn material_curvature(h: &HingeFrame) -> [f64; 2] {
    [
        0.5 * h.kb.dot(&(h.m2[0] + h.m2[1])),
        -0.5 * h.kb.dot(&(h.m1[0] + h.m1[1])),
    ]
}

/// Edge-space gradients of (κ₁, κ₂).
///
/// κ₁ = ½ κb·(m₂ᵉ + m₂ᶠ), κ₂ = −½ κb·(m₁ᵉ + m₁ᶠ): with d̃ᵢ = (mᵢᵉ + mᵢᶠ)/χ,
/// ∂κ₁/∂e = (−κ₁ t̃ + t_f × d̃₂)/|e|, ∂κ₁/∂f = (−κ₁ t̃ − t_e × d̃₂)/|f|, ∂κ₁/∂θ = −½ κb·m₁,
/// and κ₂ likewise with d̃₁, m₂ and the cross terms' signs flipped.
pub fn material_curvature_derivatives(h: &HingeFrame, kappa: [f64; 2]) -> [EdgeGradient; 2] {
    let [te, tf] = h.t;
    let [ie, if_] = h.inv_len;
    let d1 = (h.m1[0] + h.m1[1]) * h.inv_chi;
    let d2 = (h.m2[0] + h.m2[1]) * h.inv_chi;
    let tt = h.t_tilde;
    let kb = h.kb;
    [
        EdgeGradient {
            e: (tf.cross(&d2) - tt * kappa[0]) * ie,
            f: (-tt * kappa[0] - te.cross(&d2)) * if_,
            theta: [-0.5 * kb.dot(&h.m1[0]), -0.5 * kb.dot(&h.m1[1])],
        },
        EdgeGradient {
            e: (-tt * kappa[1] - tf.cross(&d1)) * ie,
            f: (te.cross(&d1) - tt * kappa[1]) * if_,
            theta: [-0.5 * kb.dot(&h.m2[0]), -0.5 * kb.dot(&h.m2[1])],
        },
    ]
}

/// The weighted sum w₁ ∇κ₁ + w₂ ∇κ₂ in edge space, without the two gradients: the formulas of
/// [`material_curvature_derivatives`] are linear in (κ, d̃, m), so the sum is one evaluation at
/// the weighted combinations.
pub fn weighted_curvature_gradient(h: &HingeFrame, kappa: [f64; 2], w: [f64; 2]) -> EdgeGradient {
    let [te, tf] = h.t;
    let [ie, if_] = h.inv_len;
    let a = w[0] * kappa[0] + w[1] * kappa[1];
    let d = ((h.m2[0] + h.m2[1]) * w[0] - (h.m1[0] + h.m1[1]) * w[1]) * h.inv_chi;
    let tt = h.t_tilde;
    let half_kb = h.kb * 0.5;
    let p = [
        h.m1[0] * w[0] + h.m2[0] * w[1],
        h.m1[1] * w[0] + h.m2[1] * w[1],
    ];
    EdgeGradient {
        e: (tf.cross(&d) - tt * a) * ie,
        f: (-tt * a - te.cross(&d)) * if_,
        theta: [-half_kb.dot(&p[0]), -half_kb.dot(&p[1])],
    }
}

/// Adds w₁ ∇²κ₁ + w₂ ∇²κ₂ (the curvatures' own second derivatives, in edge space) into `out`.
///
/// Each ∇²κₖ (Kaufman et al. 2014 / DisMech) is linear in κₖ, its director sum d̃ and its
/// directors, so the weighted sum is one evaluation at A = Σ wₖ κₖ, D = Σ sₖ wₖ d̃ₖ,
/// Mⱼ = Σ sₖ wₖ mₖʲ and Pⱼ = Σ wₖ ∂mₖʲ/∂θ (s = +1 for κ₁ with d̃₂, m₂; −1 for κ₂ with d̃₁, m₁).
pub fn add_weighted_curvature_hessian(
    h: &HingeFrame,
    kappa: [f64; 2],
    w: [f64; 2],
    out: &mut EdgeHessian,
) {
    let [te, tf] = h.t;
    let [ie, if_] = h.inv_len;
    let tt = h.t_tilde;
    let kb = h.kb;
    let a = w[0] * kappa[0] + w[1] * kappa[1];
    let d = ((h.m2[0] + h.m2[1]) * w[0] - (h.m1[0] + h.m1[1]) * w[1]) * h.inv_chi;
    let m = [
        h.m2[0] * w[0] - h.m1[0] * w[1],
        h.m2[1] * w[0] - h.m1[1] * w[1],
    ];
    let p = [
        h.m1[0] * w[0] + h.m2[0] * w[1],
        h.m1[1] * w[0] + h.m2[1] * w[1],
    ];
    let id = Matrix3::identity();
    let tt_tt = tt * tt.transpose() * (2.0 * a);
    let tf_d_tt = tf.cross(&d) * tt.transpose();
    let te_d_tt = te.cross(&d) * tt.transpose();
    let kb_me = kb * m[0].transpose();
    let kb_mf = kb * m[1].transpose();
    // Each block carries one factor 1/(|e|²), 1/(|f|²) or 1/(|e||f|), applied once.
    let a_chi = a * h.inv_chi;
    out.ee += ((tt_tt - tf_d_tt - tf_d_tt.transpose()) - (id - te * te.transpose()) * a_chi
        + (kb_me + kb_me.transpose()) * 0.25)
        * (ie * ie);
    out.ff += ((tt_tt + te_d_tt + te_d_tt.transpose()) - (id - tf * tf.transpose()) * a_chi
        + (kb_mf + kb_mf.transpose()) * 0.25)
        * (if_ * if_);
    out.ef += ((tt_tt - tf_d_tt + te_d_tt.transpose() - cross_matrix(&d))
        - (id + te * tf.transpose()) * a_chi)
        * (ie * if_);
    // θ derivatives: ∂²κ₁/∂θ² = −½κb·m₂, ∂²κ₂/∂θ² = +½κb·m₁; the mixed ones with e and f
    // through ∂m/∂θ (m₁ for κ₁, m₂ for κ₂).
    for j in 0..2 {
        out.theta_theta[j] += -0.5 * kb.dot(&m[j]);
        let half = 0.5 * kb.dot(&p[j]);
        let pj = p[j] * h.inv_chi;
        out.e_theta[j] += (tt * half - tf.cross(&pj)) * ie;
        out.f_theta[j] += (tt * half + te.cross(&pj)) * if_;
    }
}

/// Bending stiffnesses and rest data of one hinge.
#[derive(Clone, Copy, Debug)]
pub struct BendingHinge {
    /// EI₁, EI₂ (N m²).
    pub stiffness: [f64; 2],
    /// Rest material curvatures κ̄₁, κ̄₂ (dimensionless, integrated).
    pub rest_kappa: [f64; 2],
    /// Voronoi length l̄ (m).
    pub voronoi_length: f64,
}

impl BendingHinge {
    /// Bending energy (J) of the hinge. Adds its gradient into `grad` and its whole Hessian —
    /// the Gauss–Newton part Σ w ∇κ∇κᵀ and the curvature part Σ w Δκ ∇²κ — into the edge-space
    /// `hess` (the caller chains it to the stencil once for all terms).
    pub fn energy(
        &self,
        h: &HingeFrame,
        grad: Option<&mut HingeVector>,
        hess: Option<&mut EdgeHessian>,
    ) -> f64 {
        let kappa = material_curvature(h);
        let dk = [kappa[0] - self.rest_kappa[0], kappa[1] - self.rest_kappa[1]];
        let w = [
            self.stiffness[0] / self.voronoi_length,
            self.stiffness[1] / self.voronoi_length,
        ];
        let energy = 0.5 * (w[0] * dk[0] * dk[0] + w[1] * dk[1] * dk[1]);
        let force = [w[0] * dk[0], w[1] * dk[1]];
        match hess {
            None => {
                if let Some(g) = grad {
                    weighted_curvature_gradient(h, kappa, force).add_scaled_into(g, 1.0);
                }
            }
            Some(edge) => {
                let dkappa = material_curvature_derivatives(h, kappa);
                if let Some(g) = grad {
                    dkappa[0].add_scaled_into(g, force[0]);
                    dkappa[1].add_scaled_into(g, force[1]);
                }
                edge.add_outer(w[0], &dkappa[0]);
                edge.add_outer(w[1], &dkappa[1]);
                add_weighted_curvature_hessian(h, kappa, force, edge);
            }
        }
        energy
    }
}
