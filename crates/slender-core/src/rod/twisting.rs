//! The twisting energy of a discrete elastic rod.
//!
//! The twist strain at a hinge is m = θᶠ − θᵉ + m_ref, where the reference twist m_ref is the
//! angle between the reference frames of the two edges (kept continuous by incremental
//! updates, see `frames.rs`). E_t = GJ (m − m̄)² / (2 l̄). Derivatives of m_ref with respect to
//! the edges follow Bergou et al. 2010 and DisMech (design.md §2.1).

use crate::geometry::cross_matrix;

use super::hinge::{scatter_gradient, EdgeHessian, HingeFrame, HingeMatrix, HingeVector};

/// Gradient of the twist strain over the hinge stencil, and optionally its Hessian.
pub fn twist_derivatives(h: &HingeFrame, hessian: Option<&mut HingeMatrix>) -> HingeVector {
    let [le, lf] = h.len;
    let kb = h.kb;
    let grad = scatter_gradient(&(kb / (2.0 * le)), &(kb / (2.0 * lf)), [-1.0, 1.0]);
    if let Some(out) = hessian {
        let [te, tf] = h.t;
        let se = te + h.t_tilde;
        let sf = tf + h.t_tilde;
        let hs = EdgeHessian {
            ee: -(kb * se.transpose() + se * kb.transpose()) / (4.0 * le * le),
            ff: -(kb * sf.transpose() + sf * kb.transpose()) / (4.0 * lf * lf),
            ef: (cross_matrix(&te) * (2.0 / h.chi) - kb * h.t_tilde.transpose()) / (2.0 * le * lf),
            ..Default::default()
        };
        *out = hs.scatter();
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
    /// Hessian when asked.
    pub fn energy(
        &self,
        h: &HingeFrame,
        twist: f64,
        grad: Option<&mut HingeVector>,
        hess: Option<&mut HingeMatrix>,
    ) -> f64 {
        let w = self.stiffness / self.voronoi_length;
        let dm = twist - self.rest_twist;
        let energy = 0.5 * w * dm * dm;
        if grad.is_none() && hess.is_none() {
            return energy;
        }
        let mut second = HingeMatrix::zeros();
        let want_hess = hess.is_some();
        let dtwist = twist_derivatives(h, want_hess.then_some(&mut second));
        if let Some(g) = grad {
            *g += dtwist * (w * dm);
        }
        if let Some(hm) = hess {
            *hm += dtwist * dtwist.transpose() * w + second * (w * dm);
        }
        energy
    }
}
