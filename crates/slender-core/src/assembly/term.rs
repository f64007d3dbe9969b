//! Energy terms on local stencils, and the named groups a model's terms belong to.

use nalgebra::{SMatrix, SVector};

use super::stencil::Stencil;

/// One named group of terms of a model (e.g. a rod's "bending"): a bit in a [`TermSet`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TermGroup {
    /// Bit index (0..32), unique within the model.
    pub bit: u8,
    /// Name shown in test messages ("stretching", "membrane", …).
    pub name: &'static str,
}

impl TermGroup {
    /// The set holding only this group.
    pub const fn set(self) -> TermSet {
        TermSet(1 << self.bit)
    }
}

/// A set of term groups (a bit mask): what an assembly includes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TermSet(pub u32);

impl TermSet {
    /// Every group.
    pub const ALL: Self = Self(u32::MAX);
    /// No group.
    pub const NONE: Self = Self(0);

    /// True if `group` is in the set.
    pub const fn contains(self, group: TermGroup) -> bool {
        self.0 & (1 << group.bit) != 0
    }

    /// True if the two sets share a group.
    pub const fn intersects(self, other: TermSet) -> bool {
        self.0 & other.0 != 0
    }

    /// The union.
    pub const fn with(self, other: TermSet) -> Self {
        Self(self.0 | other.0)
    }

    /// This set without `other`'s groups.
    pub const fn without(self, other: TermSet) -> Self {
        Self(self.0 & !other.0)
    }
}

/// What one term evaluation writes: energy, its round-off scale and, when requested, the
/// stencil gradient and Hessian (accumulated: a term covering several groups adds each part).
pub struct LocalDerivatives<'a, const D: usize> {
    /// Energy (J), summed over the selected parts.
    pub energy: f64,
    /// Σ |part energy| (J): the scale of round-off in `energy`.
    pub magnitude: f64,
    /// ∂E/∂slot, if requested.
    pub grad: Option<&'a mut SVector<f64, D>>,
    /// ∂²E/∂slot², if requested (the full symmetric matrix).
    pub hess: Option<&'a mut SMatrix<f64, D, D>>,
}

impl<const D: usize> LocalDerivatives<'_, D> {
    /// Adds one part's energy (J) and its magnitude.
    pub fn add_energy(&mut self, e: f64) {
        self.energy += e;
        self.magnitude += e.abs();
    }

    /// True if the gradient is requested.
    pub fn wants_gradient(&self) -> bool {
        self.grad.is_some()
    }

    /// True if the Hessian is requested.
    pub fn wants_hessian(&self) -> bool {
        self.hess.is_some()
    }
}

/// An energy term on a stencil of `D` DOF slots, evaluated in a model-specific context `C`
/// (the model and the state it is evaluated at).
///
/// The gradient and Hessian are exact derivatives of the energy with respect to the slots in
/// the model's chart at the state (see [`EquilibriumProblem::chart`]
/// (crate::solver::EquilibriumProblem::chart)); every implementation is checked against
/// finite differences by [`crate::testing`]'s derivative checker.
pub trait StencilTerm<C: ?Sized, const D: usize> {
    /// The groups this term contributes to (usually one; a rod hinge is bending and twisting).
    fn groups(&self) -> TermSet;

    /// The global free DOF of each slot.
    fn stencil(&self) -> &Stencil<D>;

    /// True if [`evaluate`](Self::evaluate) *writes* every entry of `out.hess` (when it is
    /// requested) instead of adding to it: the assembler then does not zero the local Hessian
    /// before the call (for a rod hinge, 121 entries per term per assembly).
    const OVERWRITES_HESSIAN: bool = false;

    /// Adds the energy of the parts in `selected` (and their derivatives, if requested) to
    /// `out`. `out.grad` arrives zeroed for this term, and so does `out.hess` unless
    /// [`OVERWRITES_HESSIAN`](Self::OVERWRITES_HESSIAN) is set.
    fn evaluate(&self, ctx: &C, selected: TermSet, out: &mut LocalDerivatives<'_, D>);
}
