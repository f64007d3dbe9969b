//! The shell cantilever (seed §3, Fig. 2 and Fig. 4): a flat strip, length along x, width
//! along z, mid-surface in the xz-plane, clamped at x = 0 (exact director clamp), gravity −y
//! scaled to reach Γ_shell = ρhgL³/D. Measured: Δy/Δx between the centre of the clamp and the
//! centre of the free end (the strip's centre line).

use std::time::Instant;

use slender_core::geometry::Vec3;
use slender_core::rod::Grading;
use slender_core::shell::{rod_predictor, Shell, ShellBuilder};
use slender_core::solver::{EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::materials::ShellMaterialSet;

/// Parameters of one shell cantilever run.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ShellCantileverCase {
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
    /// Vertex positions of the returned state (m).
    pub positions: Vec<Vec3>,
    /// Faces (vertex triples), for pictures.
    pub faces: Vec<[usize; 3]>,
}

impl ShellCantileverCase {
    /// Elements across the width for a sweep: about square elements on the uniform mesh,
    /// n_W = round(n_L·w/L), and at least 2 (the 8 × 2 and 15 × 2 meshes validated in
    /// design.md §3.3), so that the centre line is a mesh line when n_W is even.
    pub fn default_width_elements(width_ratio: f64, n_length: usize) -> usize {
        ((width_ratio * n_length as f64).round() as usize).max(2)
    }

    /// Builds the clamped strip of this case.
    pub fn build(&self) -> Result<Shell, ModelError> {
        if !(self.gamma.is_finite() && self.gamma > 0.0) {
            return Err(ModelError::parameter("gamma", self.gamma, "finite and > 0"));
        }
        let properties = self.material.properties(self.width_ratio);
        let g = properties.gravity_for_gamma(self.gamma);
        ShellBuilder::new(properties)
            .elements(self.n_length, self.n_width)
            .grading(self.grading)
            .gravity(Vec3::new(0.0, -g, 0.0))
            .build()
    }

    /// Solves for the equilibrium under full gravity. With `use_rod_predictor`, Newton starts
    /// from the equivalent rod's equilibrium mapped onto the strip
    /// ([`slender_core::shell::rod_predictor`]),
    /// falling back to load stepping from the flat state if that fails; without it, the
    /// solver ramps gravity from the flat state with its own adaptive load steps.
    pub fn run_with(
        &self,
        params: &SolverParams,
        use_rod_predictor: bool,
    ) -> Result<ShellCantileverRun, ModelError> {
        params.validate()?;
        let shell = self.build()?;
        let start = shell.rest_state();
        let clock = Instant::now();
        let mut solver = EquilibriumSolver::new(&shell, &start, params.clone());
        let mut solution = None;
        if use_rod_predictor {
            if let Some(guess) = rod_predictor(&shell, 1.0, params)? {
                let s = solver.solve(&shell, &guess, 1.0, 1.0);
                if s.report.converged() {
                    solution = Some(s);
                }
            }
        }
        let solution = solution.unwrap_or_else(|| solver.solve(&shell, &start, 0.0, 1.0));
        let seconds = clock.elapsed().as_secs_f64();
        let ratio = if solution.report.converged() {
            centre_line_ratio(&shell, &solution.state.positions)
        } else {
            f64::NAN
        };
        Ok(ShellCantileverRun {
            case: *self,
            ratio,
            report: solution.report,
            seconds,
            positions: solution.state.positions,
            faces: shell.mesh().faces.clone(),
        })
    }
}

impl ShellCantileverCase {
    /// Solves with the rod predictor (the default, see [`Self::run_with`]).
    pub fn run(&self, params: &SolverParams) -> Result<ShellCantileverRun, ModelError> {
        self.run_with(params, true)
    }
}

/// Centre of the vertex column at station `i` (the mean of the two vertices symmetric about
/// z = 0 nearest the centre line; the middle vertex when n_W is even).
pub fn column_centre(shell: &Shell, positions: &[Vec3], i: usize) -> Vec3 {
    let mesh = shell.mesh();
    let nw = mesh.n_width;
    let (lo, hi) = (nw / 2, nw.div_ceil(2));
    (positions[mesh.vertex(i, lo)] + positions[mesh.vertex(i, hi)]) * 0.5
}

/// Δy/Δx between the centres of the clamp and of the free end, y measured downward.
pub fn centre_line_ratio(shell: &Shell, positions: &[Vec3]) -> f64 {
    let a = column_centre(shell, positions, 0);
    let b = column_centre(shell, positions, shell.mesh().n_length);
    (a.y - b.y) / (b.x - a.x)
}
