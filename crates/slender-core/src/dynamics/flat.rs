//! Which models the inertial term is exact for.

use crate::rod::Rod;
use crate::solver::EquilibriumProblem;
use crate::structure::Structure;

/// A model whose DOFs are plain coordinates in its chart: `difference(chart(b, d), b) = d`
/// exactly (positions, and the discrete elastic rod's edge angles, measured from frames
/// transported with the positions). The inertial term ‖y ⊖ xₙ − τ vₙ‖²_M/(2τ²) then has the
/// exact gradient M(y ⊖ xₙ − τ vₙ)/τ² and Hessian M/τ² in the chart the model's derivatives
/// are taken in, so Newton converges quadratically on the incremental potential.
///
/// On a rotation group the difference is a log map whose derivative is not the identity away
/// from xₙ; a framed model needs that derivative (dexp⁻¹) in the inertial term before it can
/// be stepped here, which is why only flat models are accepted.
pub trait FlatDofs: EquilibriumProblem {
    /// True if every DOF is flat in the sense above.
    fn has_flat_dofs(&self) -> bool;
}

impl FlatDofs for Rod {
    fn has_flat_dofs(&self) -> bool {
        true
    }
}

impl FlatDofs for Structure {
    /// A structure is flat when all its members are discrete elastic rods.
    fn has_flat_dofs(&self) -> bool {
        self.members()
            .iter()
            .all(|m| matches!(m, crate::structure::Member::Der(_)))
    }
}
