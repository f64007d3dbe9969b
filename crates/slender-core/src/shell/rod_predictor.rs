//! A start for Newton from the equivalent rod (design.md §3.3, remedy 2).
//!
//! From the flat state, Newton steps move a shell's vertices normal to the surface and stretch
//! the stiff membrane at second order, so each step is valid only over about a thickness and a
//! large-deflection solve takes hundreds of iterations. A discrete elastic rod has no such
//! limit (its update preserves edge lengths). For a strip bending about its width, the rod
//! with the plate's bending stiffness D·w, stretching E·h·w and mass ρ·h·w per length, with
//! nodes at the shell's stations, gives a shape from which the shell converges in a few
//! iterations to its *own* equilibrium (the predictor changes the start, not the answer).

use crate::geometry::Vec3;
use crate::rod::{RestCurve, RodBuilder, RodProperties, SectionStiffness};
use crate::solver::{EquilibriumSolver, SolverParams};
use crate::ModelError;

use super::model::Shell;
use super::state::ShellState;

/// The equilibrium of the equivalent rod under the shell's gravity at load factor `load`,
/// mapped onto the strip: every vertex column is placed across the rod's vertex along z (the
/// width direction, which stays horizontal when the strip bends in the xy-plane, as in the
/// cantilever). `None` if the rod does not converge. The clamp must not be rotated.
pub fn rod_predictor(
    shell: &Shell,
    load: f64,
    params: &SolverParams,
) -> Result<Option<ShellState>, ModelError> {
    let p = shell.properties();
    let dw = p.bending_stiffness() * p.width;
    let mesh = shell.mesh();
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: p.length,
        },
        RodProperties {
            stiffness: SectionStiffness {
                ea: p.young * p.thickness * p.width,
                ei1: dw,
                ei2: dw,
                gj: p.young / (2.0 * (1.0 + p.poisson)) * p.width * p.thickness.powi(3) / 3.0,
            },
            linear_density: p.density * p.thickness * p.width,
        },
    )
    .elements(mesh.n_length)
    .grading(shell.grading())
    .first_director(Vec3::z())
    .clamp_start()
    .gravity(shell.gravity() * load)
    .build()?;
    let start = rod.rest_state().clone();
    let mut solver = EquilibriumSolver::new(&rod, &start, *params);
    let solution = solver.solve(&rod, &start, 0.0, 1.0);
    if !solution.report.converged() {
        return Ok(None);
    }
    let mut state = shell.rest_state();
    for (i, c) in solution.state.positions().iter().enumerate().skip(1) {
        for j in 0..=mesh.n_width {
            let v = mesh.vertex(i, j);
            state.positions[v] = c + Vec3::new(0.0, 0.0, mesh.rest_positions[v].z);
        }
    }
    Ok(Some(state))
}
