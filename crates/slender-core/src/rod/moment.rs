//! Point moments on a rod, as conservative loads.
//!
//! A moment M on edge j is split at build time, against the rest tangent t̄, into
//! * a bending part M_b n̂ (n̂ ⊥ t̄): the potential −M_b α, where α is the angle, about the
//!   fixed axis n̂, of the edge's projection onto the plane ⊥ n̂, unwrapped continuously. This
//!   is an exact dead moment whenever the edge turns about n̂ (all planar problems, e.g. an end
//!   moment rolling a rod into a circle) and stays conservative otherwise; it is undefined only
//!   if the edge turns parallel to n̂;
//! * an axial part T t: the potential −T θ_j. With time-parallel reference frames the
//!   material frame turns about t by exactly δθ, so this is the exact work of a torque that
//!   follows the edge's tangent.

use nalgebra::{Matrix3, SMatrix, SVector};

use crate::geometry::{signed_angle, Vec3};

/// A moment load on one edge, split as described in the module docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MomentLoad {
    /// Edge the moment acts on.
    pub edge: usize,
    /// Fixed unit axis n̂ of the bending part (⊥ the rest tangent).
    pub axis: Vec3,
    /// Magnitude of the bending part (N m).
    pub bending: f64,
    /// Axial torque about the edge tangent (N m).
    pub axial: f64,
}

impl MomentLoad {
    /// Splits the moment `moment` (N m) on an edge with rest tangent `rest_tangent`.
    pub fn new(edge: usize, moment: Vec3, rest_tangent: &Vec3) -> Self {
        let axial = moment.dot(rest_tangent);
        let perp = moment - rest_tangent * axial;
        let bending = perp.norm();
        let axis = if bending > 0.0 {
            perp / bending
        } else {
            crate::geometry::any_orthogonal(rest_tangent)
        };
        Self {
            edge,
            axis,
            bending,
            axial,
        }
    }

    /// The edge vector projected onto the plane ⊥ n̂.
    fn projected(&self, e: &Vec3) -> Vec3 {
        e - self.axis * self.axis.dot(e)
    }

    /// The unwrapped angle α (rad) of edge vector `e_new`, continued from `alpha_old` at
    /// `e_old`.
    pub fn updated_angle(&self, e_old: &Vec3, e_new: &Vec3, alpha_old: f64) -> f64 {
        alpha_old + signed_angle(&self.projected(e_old), &self.projected(e_new), &self.axis)
    }

    /// ∂α/∂e and ∂²α/∂e² at edge vector `e`.
    pub fn angle_derivatives(&self, e: &Vec3) -> (Vec3, Matrix3<f64>) {
        let u = self.projected(e);
        let len2 = u.norm_squared();
        let w = self.axis.cross(&u);
        // α depends on e only through its projection u: ∂α/∂e = (n̂ × u)/|u|², and
        // ∂²α/∂e² = −(ŵ ûᵀ + û ŵᵀ)/|u|² with û = u/|u|, ŵ = n̂ × û.
        let grad = w / len2;
        let hess = -(w * u.transpose() + u * w.transpose()) / (len2 * len2);
        (grad, hess)
    }

    /// Potential of the bending part over the edge stencil [x_j, x_{j+1}] at load factor
    /// `load`, given the current angle; adds gradient and Hessian.
    pub fn bending_potential(
        &self,
        e: &Vec3,
        alpha: f64,
        load: f64,
        grad: &mut SVector<f64, 6>,
        hess: &mut SMatrix<f64, 6, 6>,
    ) -> f64 {
        let (g, h) = self.angle_derivatives(e);
        let s = -load * self.bending;
        grad.fixed_rows_mut::<3>(0).copy_from(&(-g * s));
        grad.fixed_rows_mut::<3>(3).copy_from(&(g * s));
        let hs = h * s;
        hess.fixed_view_mut::<3, 3>(0, 0).copy_from(&hs);
        hess.fixed_view_mut::<3, 3>(3, 3).copy_from(&hs);
        hess.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-hs));
        hess.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-hs));
        s * alpha
    }
}
