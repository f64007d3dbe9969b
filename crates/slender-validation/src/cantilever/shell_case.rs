//! The shell cantilever (seed §3, Fig. 2 and Fig. 4): a flat strip, length along x, width
//! along z, mid-surface in the xz-plane, clamped at x = 0 (exact clamp), gravity −y scaled to
//! reach Γ_shell = ρhgL³/D, for either shell model. Measured: Δy/Δx between the centre of
//! the clamp and the centre of the free end (the strip's centre line).

use std::time::Instant;

use slender_core::geometry::Vec3;
use slender_core::rod::Grading;
use slender_core::shell::{rod_predictor, Shell};
use slender_core::solver::{EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::materials::ShellMaterialSet;
use crate::shell_model::{ShellModel, Strip, StripModel, StripSpec};

/// Parameters of one shell cantilever run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ShellCantileverCase {
    /// Shell discretization.
    pub model: ShellModel,
    /// Material and geometry set.
    pub material: ShellMaterialSet,
    /// Aspect ratio w/L (> 0).
    pub width_ratio: f64,
    /// Elements along the length n_L.
    pub n_length: usize,
    /// Elements across the width n_W.
    pub n_width: usize,
    /// Stations along the length (power grading toward the clamp, or uniform).
    pub grading: Grading,
    /// Gravito-bending parameter Γ_shell (> 0).
    pub gamma: f64,
}

/// What a shell cantilever run measured.
#[derive(Clone, Debug)]
pub struct ShellCantileverRun {
    /// The case.
    pub case: ShellCantileverCase,
    /// Δy/Δx of the centre line's end points (NaN if not converged).
    pub ratio: f64,
    /// Solver report.
    pub report: SolveReport,
    /// Wall time of the solve (s), build excluded.
    pub seconds: f64,
    /// Surface points of the returned state (m): the mid-edge shell's vertices, or a
    /// tessellation of the B-spline surface.
    pub positions: Vec<Vec3>,
    /// Triangles over `positions`, for pictures.
    pub faces: Vec<[usize; 3]>,
}

impl ShellCantileverCase {
    /// Elements across the width for a sweep: about square elements on the uniform mesh,
    /// n_W = round(n_L·w/L), at least 2 for the mid-edge shell (the 8 × 2 and 15 × 2 meshes
    /// validated in design.md §3.3; the centre line is a mesh line when n_W is even) and at
    /// least 1 for the B-spline shell.
    pub fn default_width_elements(model: ShellModel, width_ratio: f64, n_length: usize) -> usize {
        model.square_width_elements(width_ratio, n_length, 2)
    }

    /// Builds the clamped strip of this case.
    pub fn build(&self) -> Result<Strip, ModelError> {
        if !(self.gamma.is_finite() && self.gamma > 0.0) {
            return Err(ModelError::parameter("gamma", self.gamma, "finite and > 0"));
        }
        let properties = self.material.properties(self.width_ratio);
        let g = properties.gravity_for_gamma(self.gamma);
        StripSpec {
            model: self.model,
            properties,
            n_length: self.n_length,
            n_width: self.n_width,
            grading: self.grading,
            gravity: Vec3::new(0.0, -g, 0.0),
        }
        .build()
    }

    /// Solves for the equilibrium under full gravity. The mid-edge shell with
    /// `use_rod_predictor` starts Newton from the equivalent rod's equilibrium mapped onto the
    /// strip ([`slender_core::shell::rod_predictor`]), falling back to load stepping from the
    /// flat state if that fails; otherwise (and always for the B-spline shell, whose
    /// mixed-integration-point Newton takes full gravity from the flat strip in a few dozen
    /// iterations) the solver ramps gravity from the flat state with its own adaptive steps.
    pub fn run_with(
        &self,
        params: &SolverParams,
        use_rod_predictor: bool,
    ) -> Result<ShellCantileverRun, ModelError> {
        params.validate()?;
        let strip = self.build()?;
        let clock = Instant::now();
        let (report, ratio, (positions, faces)) = match &strip {
            Strip::Midedge(shell) => {
                let (report, state) = solve_midedge(shell, params, use_rod_predictor)?;
                (
                    report,
                    centre_line_ratio(shell, &state),
                    shell.surface(&state),
                )
            }
            Strip::Bspline(shell) => {
                let start = shell.rest();
                let mut solver = EquilibriumSolver::new(shell, &start, *params);
                let s = solver.solve(shell, &start, 0.0, 1.0);
                (
                    s.report,
                    centre_line_ratio(shell, &s.state),
                    shell.surface(&s.state),
                )
            }
        };
        let seconds = clock.elapsed().as_secs_f64();
        Ok(ShellCantileverRun {
            case: *self,
            ratio: if report.converged() { ratio } else { f64::NAN },
            report,
            seconds,
            positions,
            faces,
        })
    }

    /// Solves with the rod predictor for the mid-edge shell (the default, see
    /// [`Self::run_with`]).
    pub fn run(&self, params: &SolverParams) -> Result<ShellCantileverRun, ModelError> {
        self.run_with(params, true)
    }
}

fn solve_midedge(
    shell: &Shell,
    params: &SolverParams,
    use_rod_predictor: bool,
) -> Result<(SolveReport, slender_core::shell::ShellState), ModelError> {
    let start = shell.rest_state();
    let mut solver = EquilibriumSolver::new(shell, &start, *params);
    if use_rod_predictor {
        if let Some(guess) = rod_predictor(shell, 1.0, params)? {
            let s = solver.solve(shell, &guess, 1.0, 1.0);
            if s.report.converged() {
                return Ok((s.report, s.state));
            }
        }
    }
    let s = solver.solve(shell, &start, 0.0, 1.0);
    Ok((s.report, s.state))
}

/// Δy/Δx between the centres of the clamp and of the free end, y measured downward.
pub fn centre_line_ratio<S: StripModel>(shell: &S, state: &S::State) -> f64 {
    let a = shell.centre(state, false);
    let b = shell.centre(state, true);
    (a.y - b.y) / (b.x - a.x)
}
