//! The shell cantilever (seed §3, Fig. 2 and Fig. 4): a flat strip, length along x, width
//! along z, mid-surface in the xz-plane, clamped at x = 0 (exact director clamp), gravity −y
//! scaled to reach Γ_shell = ρhgL³/D. Measured: Δy/Δx between the centre of the clamp and the
//! centre of the free end (the strip's centre line).

use std::time::Instant;

use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, RodBuilder, RodProperties, SectionStiffness};
use slender_core::shell::{Shell, ShellBuilder, ShellState};
use slender_core::solver::{EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::materials::ShellMaterialSet;

/// Parameters of one shell cantilever run.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    /// The seed's default for an aspect ratio: n_W = 2 elements across for w/L ≤ 0.2 (the
    /// design's validated 15 × 2, 30 × 2 meshes), else about square elements at mid-length.
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

    /// Solves for the equilibrium under full gravity. With `rod_predictor`, Newton starts
    /// from the equivalent rod's equilibrium mapped onto the strip (see [`rod_predictor`]),
    /// falling back to load stepping from the flat state if that fails; without it, the
    /// solver ramps gravity from the flat state with its own adaptive load steps.
    pub fn run_with(
        &self,
        params: &SolverParams,
        rod_predictor: bool,
    ) -> Result<ShellCantileverRun, ModelError> {
        params.validate()?;
        let shell = self.build()?;
        let start = shell.rest_state();
        let clock = Instant::now();
        let mut solver = EquilibriumSolver::new(&shell, &start, params.clone());
        let mut solution = None;
        if rod_predictor {
            if let Some(guess) = self.rod_predictor(&shell, params)? {
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

    /// Start for Newton: the equilibrium of the equivalent rod (bending stiffness D·w,
    /// stretching E·h·w, mass ρ·h·w per length, nodes at the shell's stations), with every
    /// vertex column placed across the rod's vertex along z (the strip bends in the xy-plane).
    ///
    /// Why: from the flat state, Newton steps move the shell's vertices normal to the
    /// surface and stretch the stiff membrane at second order, so each step is valid only
    /// over about a thickness and a solve takes hundreds of iterations (design.md §3.3). The
    /// rod's edge-preserving update has no such limit; from its shape the shell converges in
    /// a few iterations to its own equilibrium. `None` if the rod does not converge.
    pub fn rod_predictor(
        &self,
        shell: &Shell,
        params: &SolverParams,
    ) -> Result<Option<ShellState>, ModelError> {
        let p = shell.properties();
        let dw = p.bending_stiffness() * p.width;
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
        .elements(self.n_length)
        .grading(self.grading)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(shell.gravity())
        .build()?;
        let start = rod.rest_state().clone();
        let mut solver = EquilibriumSolver::new(&rod, &start, params.clone());
        let solution = solver.solve(&rod, &start, 0.0, 1.0);
        if !solution.report.converged() {
            return Ok(None);
        }
        let centre = solution.state.positions();
        let mesh = shell.mesh();
        let mut state = shell.rest_state();
        for (i, c) in centre.iter().enumerate().skip(1) {
            for j in 0..=mesh.n_width {
                let v = mesh.vertex(i, j);
                let z = mesh.rest_positions[v].z;
                state.positions[v] = c + Vec3::new(0.0, 0.0, z);
            }
        }
        Ok(Some(state))
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
