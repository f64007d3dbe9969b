//! The stretching energy of a discrete elastic rod: E_s = ½ EA |ē| (|e|/|ē| − 1)² per edge.

use nalgebra::{Matrix3, SMatrix, SVector};

use crate::geometry::Vec3;

use super::frames::EdgeLength;

/// Stretching energy (J) of the edge from `x0` to `x1` with rest length `rest_length` (m)
/// and axial stiffness `ea` (N); adds the gradient over `[x0, x1]` and writes the Hessian
/// (every entry) when asked.
pub fn stretching_energy(
    x0: &Vec3,
    x1: &Vec3,
    rest_length: f64,
    ea: f64,
    grad: Option<&mut SVector<f64, 6>>,
    hess: Option<&mut SMatrix<f64, 6, 6>>,
) -> f64 {
    let (length, t) = EdgeLength::of(&(x1 - x0));
    stretching_energy_measured(length, &t, rest_length, ea, grad, hess)
}

/// [`stretching_energy`] of an edge already measured: its length and unit tangent `t`.
pub fn stretching_energy_measured(
    length: EdgeLength,
    t: &Vec3,
    rest_length: f64,
    ea: f64,
    grad: Option<&mut SVector<f64, 6>>,
    hess: Option<&mut SMatrix<f64, 6, 6>>,
) -> f64 {
    let (len, inv_len) = (length.length, length.inv_length);
    let strain = len / rest_length - 1.0;
    let energy = 0.5 * ea * rest_length * strain * strain;
    if let Some(g) = grad {
        let de = t * (ea * strain);
        g.fixed_rows_mut::<3>(0).sub_assign(&de);
        g.fixed_rows_mut::<3>(3).add_assign(&de);
    }
    if let Some(h) = hess {
        // ∂²E/∂e² = EA/|ē| t⊗t + EA ε (I − t⊗t)/|e|, with e = x₁ − x₀.
        let tt = t * t.transpose();
        let hee = tt * (ea / rest_length) + (Matrix3::identity() - tt) * (ea * strain * inv_len);
        h.fixed_view_mut::<3, 3>(0, 0).copy_from(&hee);
        h.fixed_view_mut::<3, 3>(3, 3).copy_from(&hee);
        h.fixed_view_mut::<3, 3>(0, 3).copy_from(&-hee);
        h.fixed_view_mut::<3, 3>(3, 0).copy_from(&-hee);
    }
    energy
}

use std::ops::{AddAssign, SubAssign};

/// Stretching of one edge: a term of the [`STRETCHING`](super::groups::STRETCHING) group on
/// the stencil [x_j (3), x_{j+1} (3)].
#[derive(Clone, Debug)]
pub struct StretchTerm {
    /// The edge j.
    pub(super) edge: usize,
    /// Free DOFs of x_j and x_{j+1}.
    pub(super) dofs: crate::assembly::Stencil<6>,
    /// Rest length |ē| (m).
    pub(super) rest_length: f64,
    /// EA (N).
    pub(super) ea: f64,
}

impl<'a> crate::assembly::StencilTerm<super::model::RodContext<'a>, 6> for StretchTerm {
    fn groups(&self) -> crate::assembly::TermSet {
        super::groups::STRETCHING.set()
    }

    fn stencil(&self) -> &crate::assembly::Stencil<6> {
        &self.dofs
    }

    const OVERWRITES_HESSIAN: bool = true;

    fn evaluate(
        &self,
        ctx: &super::model::RodContext<'a>,
        _selected: crate::assembly::TermSet,
        out: &mut crate::assembly::LocalDerivatives<'_, 6>,
    ) {
        // The edge as the frames measured it (they are adapted to the positions).
        let frames = &ctx.state.frames;
        let e = stretching_energy_measured(
            frames.lengths[self.edge],
            &frames.edges[self.edge].tangent,
            self.rest_length,
            self.ea,
            out.grad.as_deref_mut(),
            out.hess.as_deref_mut(),
        );
        out.add_energy(e);
    }
}
