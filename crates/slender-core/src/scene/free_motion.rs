//! Detecting a free rigid-body motion of a rod from its stiffness at rest.

use crate::rod::{Rod, RodState};
use crate::solver::{EquilibriumSolver, SolverParams};

use super::error::SceneError;

/// Rejects a rod whose stiffness matrix at rest is singular: some motion (a rigid rotation
/// about the line through its pins, a spin about its own axis between clips…) costs no energy.
pub fn check_no_free_motion(
    path: &str,
    seg_path: &str,
    rod: &Rod,
    params: &SolverParams,
) -> Result<(), SceneError> {
    let rest: RodState = rod.rest_state().clone();
    // Overflowing inputs (e.g. a length of 1e308) can leave a finite scene with a non-finite
    // mesh; nothing can be solved on it.
    if rest.positions().iter().flatten().any(|c| !c.is_finite())
        || rod
            .rest_lengths()
            .iter()
            .any(|l| !(l.is_finite() && *l > 0.0))
    {
        return Err(SceneError::new(
            path,
            format!("{seg_path}: the mesh has non-finite coordinates; check lengths, radii and points for overflow"),
        ));
    }
    let p = SolverParams {
        compute_lambda_min: true,
        ..params.clone()
    };
    let mut solver = EquilibriumSolver::new(rod, &rest, p);
    let sol = solver.solve(rod, &rest, 0.0, 0.0);
    let singular = match (sol.report.inertia, sol.report.lambda_min_normalized) {
        (Some(i), _) if i.zero > 0 || i.negative > 0 => true,
        (_, Some(l)) => !(l > 1e-9),
        _ => false,
    };
    if singular {
        return Err(SceneError::new(
            format!("{path}.supports"),
            format!(
                "{seg_path} has a free rigid-body motion (its stiffness at rest is singular, λ_min/(EI/ρAL⁴) = {:.3e}): hold it so that it can neither translate, rotate nor spin about its own axis, e.g. with a clamp",
                sol.report.lambda_min_normalized.unwrap_or(0.0)
            ),
        ));
    }
    Ok(())
}
