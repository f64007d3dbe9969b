//! The twisting energy of a discrete elastic rod.
//!
//! The twist strain at a hinge is m = θᶠ − θᵉ + m_ref, where the reference twist m_ref is the
//! angle between the reference frames of the two edges (kept continuous by incremental
//! updates, see `frames.rs`). E_t = GJ (m − m̄)² / (2 l̄). Derivatives of m_ref with respect to
//! the edges follow Bergou et al. 2010 and DisMech (design.md §2.1).

use crate::geometry::cross_matrix;

use super::hinge::{scatter_gradient, EdgeHessian, HingeFrame, HingeMatrix, HingeVector};

/// Gradient of the twist strain over the hinge stencil; when `second` is given, adds
/// w ∇²m (in edge space) into it.
pub fn twist_derivatives(h: &HingeFrame, second: Option<(&mut EdgeHessian, f64)>) -> HingeVector {
    let [le, lf] = h.len;
    let kb = h.kb;
    let grad = scatter_gradient(&(kb / (2.0 * le)), &(kb / (2.0 * lf)), [-1.0, 1.0]);
    if let Some((out, weight)) = second {
        let [te, tf] = h.t;
        let se = te + h.t_tilde;
        let sf = tf + h.t_tilde;
        let hs = EdgeHessian {
            ee: -(kb * se.transpose() + se * kb.transpose()) / (4.0 * le * le),
            ff: -(kb * sf.transpose() + sf * kb.transpose()) / (4.0 * lf * lf),
            ef: (cross_matrix(&te) * (2.0 / h.chi) - kb * h.t_tilde.transpose()) / (2.0 * le * lf),
            ..Default::default()
        };
        out.add_scaled(&hs, weight);
    }
    grad
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
        hess: Option<(&mut HingeMatrix, &mut EdgeHessian)>,
    ) -> f64 {
        let w = self.stiffness / self.voronoi_length;
        let dm = twist - self.rest_twist;
        let energy = 0.5 * w * dm * dm;
        if grad.is_none() && hess.is_none() {
            return energy;
        }
        let (hm, edge) = match hess {
            Some((hm, edge)) => (Some(hm), Some(edge)),
            None => (None, None),
        };
        let dtwist = twist_derivatives(h, edge.map(|e| (e, w * dm)));
        if let Some(g) = grad {
            *g += dtwist * (w * dm);
        }
        if let Some(hm) = hm {
            hm.ger(w, &dtwist, &dtwist, 1.0);
        }
        energy
    }
}
