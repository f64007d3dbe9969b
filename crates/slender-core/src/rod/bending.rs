//! The bending energy of a discrete elastic rod.
//!
//! At each hinge the material curvatures are (Bergou et al. 2010, averaged material frame)
//! κ₁ = ½ κb·(m₂ᵉ + m₂ᶠ), κ₂ = −½ κb·(m₁ᵉ + m₁ᶠ), integrated (dimensionless) quantities. The
//! energy is E_b = (EI₁ (κ₁ − κ̄₁)² + EI₂ (κ₂ − κ̄₂)²) / (2 l̄) with the hinge's Voronoi length
//! l̄ (half the adjacent rest edges; half of the single real edge at a clamp). The closed-form
//! derivatives are those of Kaufman et al. 2014 / DisMech (design.md §2.1), verified here by
//! finite differences.

use nalgebra::Matrix3;

use crate::geometry::{cross_matrix, Vec3};

use super::hinge::{scatter_gradient, EdgeHessian, HingeFrame, HingeMatrix, HingeVector};

/// Material curvatures (κ₁, κ₂) of a hinge.
pub fn material_curvature(h: &HingeFrame) -> [f64; 2] {
    [
        0.5 * h.kb.dot(&(h.m2[0] + h.m2[1])),
        -0.5 * h.kb.dot(&(h.m1[0] + h.m1[1])),
    ]
}

/// Gradients of (κ₁, κ₂) over the hinge stencil; when `second` is given, adds
/// w₁ ∇²κ₁ + w₂ ∇²κ₂ (in edge space) into it.
pub fn material_curvature_derivatives(
    h: &HingeFrame,
    kappa: [f64; 2],
    second: Option<(&mut EdgeHessian, [f64; 2])>,
) -> [HingeVector; 2] {
    let [te, tf] = h.t;
    let [le, lf] = h.len;
    let d1 = (h.m1[0] + h.m1[1]) / h.chi;
    let d2 = (h.m2[0] + h.m2[1]) / h.chi;
    let tt = h.t_tilde;
    let kb = h.kb;

    let grad = [
        scatter_gradient(
            &((-kappa[0] * tt + tf.cross(&d2)) / le),
            &((-kappa[0] * tt - te.cross(&d2)) / lf),
            [-0.5 * kb.dot(&h.m1[0]), -0.5 * kb.dot(&h.m1[1])],
        ),
        scatter_gradient(
            &((-kappa[1] * tt - tf.cross(&d1)) / le),
            &((-kappa[1] * tt + te.cross(&d1)) / lf),
            [-0.5 * kb.dot(&h.m2[0]), -0.5 * kb.dot(&h.m2[1])],
        ),
    ];

    if let Some((out, weights)) = second {
        let id = Matrix3::identity();
        let tt_tt = tt * tt.transpose();
        let proj_e = id - te * te.transpose();
        let proj_f = id - tf * tf.transpose();
        let mixed = id + te * tf.transpose();
        let (ee, ff, eff) = (le * le, lf * lf, le * lf);
        // κ₁ uses d̃₂ and m₂ with sign +1; κ₂ uses d̃₁ and m₁ with the cross terms and director
        // terms flipped (sign −1).
        let spec: [(Vec3, [Vec3; 2], f64, [Vec3; 2]); 2] =
            [(d2, h.m2, 1.0, h.m1), (d1, h.m1, -1.0, h.m2)];
        for (k, (d, m, sign, m_dtheta)) in spec.into_iter().enumerate() {
            let kap = kappa[k];
            let tf_d = tf.cross(&d) * sign;
            let te_d = te.cross(&d) * sign;
            let tf_d_tt = tf_d * tt.transpose();
            let te_d_tt = te_d * tt.transpose();
            let kb_me = kb * m[0].transpose();
            let kb_mf = kb * m[1].transpose();
            let mut hs = EdgeHessian {
                ee: (tt_tt * (2.0 * kap) - tf_d_tt - tf_d_tt.transpose()) / ee
                    - proj_e * (kap / (h.chi * ee))
                    + (kb_me + kb_me.transpose()) * (sign / (4.0 * ee)),
                ff: (tt_tt * (2.0 * kap) + te_d_tt + te_d_tt.transpose()) / ff
                    - proj_f * (kap / (h.chi * ff))
                    + (kb_mf + kb_mf.transpose()) * (sign / (4.0 * ff)),
                ef: -mixed * (kap / (h.chi * eff))
                    + (tt_tt * (2.0 * kap) - tf_d_tt + te_d_tt.transpose()
                        - cross_matrix(&d) * sign)
                        / eff,
                ..Default::default()
            };
            // θ derivatives: ∂κ₁/∂θ = −½κb·m₁, ∂²κ₁/∂θ² = −½κb·m₂; ∂κ₂/∂θ = −½κb·m₂,
            // ∂²κ₂/∂θ² = +½κb·m₁.
            for j in 0..2 {
                let md = m_dtheta[j];
                hs.theta_theta[j] = -0.5 * sign * kb.dot(&m[j]);
                hs.e_theta[j] = (tt * (0.5 * kb.dot(&md)) - tf.cross(&md) / h.chi) / le;
                hs.f_theta[j] = (tt * (0.5 * kb.dot(&md)) + te.cross(&md) / h.chi) / lf;
            }
            out.add_scaled(&hs, weights[k]);
        }
    }
    grad
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
    /// Bending energy (J) of the hinge. Adds its gradient into `grad`; adds the Gauss–Newton
    /// part Σ w ∇κ∇κᵀ into the stencil matrix and the curvature part Σ w Δκ ∇²κ into the edge
    /// blocks of `hess` (the caller chains those to the stencil once for all terms).
    pub fn energy(
        &self,
        h: &HingeFrame,
        grad: Option<&mut HingeVector>,
        hess: Option<(&mut HingeMatrix, &mut EdgeHessian)>,
    ) -> f64 {
        let kappa = material_curvature(h);
        let dk = [kappa[0] - self.rest_kappa[0], kappa[1] - self.rest_kappa[1]];
        let w = [
            self.stiffness[0] / self.voronoi_length,
            self.stiffness[1] / self.voronoi_length,
        ];
        let energy = 0.5 * (w[0] * dk[0] * dk[0] + w[1] * dk[1] * dk[1]);
        if grad.is_none() && hess.is_none() {
            return energy;
        }
        let (hm, edge) = match hess {
            Some((hm, edge)) => (Some(hm), Some(edge)),
            None => (None, None),
        };
        let dkappa = material_curvature_derivatives(
            h,
            kappa,
            edge.map(|e| (e, [w[0] * dk[0], w[1] * dk[1]])),
        );
        if let Some(g) = grad {
            *g += dkappa[0] * (w[0] * dk[0]) + dkappa[1] * (w[1] * dk[1]);
        }
        if let Some(hm) = hm {
            for k in 0..2 {
                hm.ger(w[k], &dkappa[k], &dkappa[k], 1.0);
            }
        }
        energy
    }
}
