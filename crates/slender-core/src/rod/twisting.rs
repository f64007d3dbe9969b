//! The twisting energy of a discrete elastic rod.
//!
//! The twist strain at a hinge is m = θᶠ − θᵉ + m_ref, where the reference twist m_ref is the
//! angle between the reference frames of the two edges (kept continuous by incremental
//! updates, see `frames.rs`). E_t = GJ (m − m̄)² / (2 l̄). Derivatives of m_ref with respect to
//! the edges follow Bergou et al. 2010 and DisMech (design.md §2.1).

use crate::geometry::cross_matrix;

use super::hinge::{EdgeGradient, EdgeHessian, HingeFrame, HingeVector};

/// Edge-space gradient of the twist strain: ∂m/∂e = κb/(2|e|), ∂m/∂f = κb/(2|f|),
/// ∂m/∂θ = (−1, 1).
pub fn twist_derivatives(h: &HingeFrame) -> EdgeGradient {
    let [ie, if_] = h.inv_len;
    EdgeGradient {
        e: h.kb * (0.5 * ie),
        f: h.kb * (0.5 * if_),
        theta: [-1.0, 1.0],
    }
}

/// Adds `weight` ∇²m (the twist strain's own second derivatives, in edge space) into `out`.
pub fn add_weighted_twist_hessian(h: &HingeFrame, weight: f64, out: &mut EdgeHessian) {
    let [ie, if_] = h.inv_len;
    let [te, tf] = h.t;
    let kb = h.kb;
    let se = te + h.t_tilde;
    let sf = tf + h.t_tilde;
    let kb_se = kb * se.transpose();
    let kb_sf = kb * sf.transpose();
    out.ee -= (kb_se + kb_se.transpose()) * (0.25 * weight * ie * ie);
    out.ff -= (kb_sf + kb_sf.transpose()) * (0.25 * weight * if_ * if_);
    out.ef += (cross_matrix(&te) * (2.0 * h.inv_chi) - kb * h.t_tilde.transpose())
        * (0.5 * weight * ie * if_);
}

/// Torsional stiffness and rest data of one hinge.
#[derive(Clone, Copy, Debug)]
pub struct TwistingHinge {
    /// GJ (N m²).
    pub stiffness: f64,
    /// Rest twist m̄ (rad, integrated over the Voronoi cell).
    pub rest_twist: f64,
    /// Voronoi length l̄ (m).
    pub voronoi_length: f64,
}

impl TwistingHinge {
    /// Twisting energy (J) of the hinge with twist strain `twist` (rad); adds its gradient and
    /// Hessian as [`BendingHinge::energy`](super::bending::BendingHinge::energy) does.
    pub fn energy(
        &self,
        h: &HingeFrame,
        twist: f64,
        grad: Option<&mut HingeVector>,
        hess: Option<&mut EdgeHessian>,
    ) -> f64 {
        let w = self.stiffness / self.voronoi_length;
        let dm = twist - self.rest_twist;
        let energy = 0.5 * w * dm * dm;
        if grad.is_none() && hess.is_none() {
            return energy;
        }
        let dtwist = twist_derivatives(h);
        if let Some(g) = grad {
            dtwist.add_scaled_into(g, w * dm);
        }
        if let Some(edge) = hess {
            edge.add_outer(w, &dtwist);
            add_weighted_twist_hessian(h, w * dm, edge);
        }
        energy
    }
}
