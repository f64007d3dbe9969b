//! Running a model's terms on the full DOF vector (free and held DOFs), for support
//! reactions: a term's generalized force on a held DOF is what the support must supply.

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};

/// A term that also knows the full-vector index of each of its slots.
pub trait FullStencil<const D: usize> {
    /// Full-vector index of each slot (held DOFs included).
    fn full_stencil(&self) -> &Stencil<D>;
}

/// `T` evaluated on its full stencil.
pub struct OnFullStencil<'t, T>(pub &'t T);

impl<C: ?Sized, T: StencilTerm<C, D> + FullStencil<D>, const D: usize> StencilTerm<C, D>
    for OnFullStencil<'_, T>
{
    fn groups(&self) -> TermSet {
        self.0.groups()
    }

    fn stencil(&self) -> &Stencil<D> {
        self.0.full_stencil()
    }

    const OVERWRITES_HESSIAN: bool = T::OVERWRITES_HESSIAN;

    fn evaluate(&self, ctx: &C, selected: TermSet, out: &mut LocalDerivatives<'_, D>) {
        self.0.evaluate(ctx, selected, out);
    }
}
