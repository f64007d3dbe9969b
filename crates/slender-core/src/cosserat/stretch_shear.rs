//! Extension and shear of one edge of a discrete Cosserat rod: the strain Γ = Rᵀe/h of the
//! edge vector e = x_{j+1} − x_j in the edge's frame R, against its rest value, on the stencil
//! [x_j (3), ω_j (3), x_{j+1} (3)].
//!
//! With R ← exp([ω]×)R, Rᵀe ← Rᵀ(e − ω×e + ½ω×(ω×e) − ω×δe + …), so ∂Γ/∂x_{j+1} = Rᵀ/h,
//! ∂Γ/∂ω = Rᵀ[e]×/h, and for a weight f (in the frame, F = Rf in space) the contracted second
//! derivatives are (sym(F eᵀ) − (F·e) I)/h in (ω, ω) and ∓[F]×/h in (x_{j+1}/x_j, ω).

use nalgebra::{Matrix3, SMatrix, Vector3};

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::framed::full_stencil::FullStencil;
use crate::framed::groups::{component_mask, SHEAR, STRETCHING};
use crate::geometry::cross_matrix;

use super::model::CosseratContext;

/// Extension and shear of edge `edge`.
#[derive(Clone, Debug)]
pub struct StretchShearTerm {
    pub(crate) edge: usize,
    pub(crate) dofs: Stencil<9>,
    pub(crate) full: Stencil<9>,
    /// Rest length h (m).
    pub(crate) rest_length: f64,
    /// (κGA₁, κGA₂, EA) (N).
    pub(crate) stiffness: [f64; 3],
    /// Rest value of Rᵀe/h (1 along d₃ for a straight rest edge).
    pub(crate) rest_strain: Vector3<f64>,
}

impl StencilTerm<CosseratContext<'_>, 9> for StretchShearTerm {
    fn groups(&self) -> TermSet {
        SHEAR.set().with(STRETCHING.set())
    }

    fn stencil(&self) -> &Stencil<9> {
        &self.dofs
    }

    fn evaluate(
        &self,
        ctx: &CosseratContext<'_>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, 9>,
    ) {
        let s = ctx.state;
        let j = self.edge;
        let r = s.frames[j].to_rotation_matrix().into_inner();
        let e = s.positions[j + 1] - s.positions[j];
        let h = self.rest_length;
        let v = r.transpose() * e / h;
        let dv = v - self.rest_strain;
        let mask = component_mask(selected);
        let c = Vector3::new(
            self.stiffness[0] * mask[0],
            self.stiffness[1] * mask[1],
            self.stiffness[2] * mask[2],
        );
        out.add_energy(0.5 * h * (c[0] * dv[0] * dv[0] + c[1] * dv[1] * dv[1]));
        out.add_energy(0.5 * h * c[2] * dv[2] * dv[2]);
        if !out.wants_gradient() && !out.wants_hessian() {
            return;
        }
        // f = ∂E/∂Γ = h C (Γ − Γ̄) in the frame, F in space.
        let f = c.component_mul(&dv) * h;
        let big_f = r * f;
        if let Some(g) = out.grad.as_deref_mut() {
            let fh = big_f / h;
            g.fixed_rows_mut::<3>(0).copy_from(&(-fh));
            g.fixed_rows_mut::<3>(3).copy_from(&fh.cross(&e));
            g.fixed_rows_mut::<3>(6).copy_from(&fh);
        }
        if let Some(hm) = out.hess.as_deref_mut() {
            let a = r.transpose() / h;
            let b = r.transpose() * cross_matrix(&e) / h;
            let mut jac = SMatrix::<f64, 3, 9>::zeros();
            jac.fixed_view_mut::<3, 3>(0, 0).copy_from(&(-a));
            jac.fixed_view_mut::<3, 3>(0, 3).copy_from(&b);
            jac.fixed_view_mut::<3, 3>(0, 6).copy_from(&a);
            let kj = SMatrix::<f64, 3, 3>::from_diagonal(&(c * h)) * jac;
            *hm = jac.transpose() * kj;
            let ff = big_f * e.transpose();
            let ww = (ff + ff.transpose()) * (0.5 / h) - Matrix3::identity() * (big_f.dot(&e) / h);
            let xw = cross_matrix(&big_f) / h;
            let add = |hm: &mut SMatrix<f64, 9, 9>, r0: usize, c0: usize, m: &Matrix3<f64>| {
                let mut v = hm.fixed_view_mut::<3, 3>(r0, c0);
                v += m;
            };
            add(hm, 3, 3, &ww);
            add(hm, 0, 3, &xw);
            add(hm, 3, 0, &xw.transpose());
            add(hm, 6, 3, &(-xw));
            add(hm, 3, 6, &(-xw.transpose()));
        }
    }
}

impl FullStencil<9> for StretchShearTerm {
    fn full_stencil(&self) -> &Stencil<9> {
        &self.full
    }
}
