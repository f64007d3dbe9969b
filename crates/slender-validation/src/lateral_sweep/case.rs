//! One lateral-buckling strip: its planar equilibrium and stability at a given Γ_shell, the
//! critical Γ_c by bisection on the inertia, and the seed's protocol (rotate the clamp about x
//! by σ, ramp gravity in m_ls steps, rotate the clamp back, measure the free end's y).

use slender_core::geometry::Vec3;
use slender_core::rod::Grading;
use slender_core::shell::{LoadPath, Shell, ShellBuilder, ShellState};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::cantilever::shell_case::column_centre;
use crate::materials::ShellMaterialSet;

/// A strip of the lateral-buckling benchmark.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LateralBucklingCase {
    /// Material set.
    pub material: ShellMaterialSet,
    /// Aspect ratio w/L (> 0).
    pub width_ratio: f64,
    /// Elements along the length.
    pub n_length: usize,
}

/// What the seed's protocol ended with.
#[derive(Clone, Debug)]
pub struct ProtocolOutcome {
    /// y of the centre of the free end divided by L (signed).
    pub tip_deviation: f64,
    /// Whether every stage converged.
    pub converged: bool,
    /// Report of the first stage that failed, else of the final re-equilibration.
    pub report: SolveReport,
}

/// The buckled state the stability route's branch switch lands on.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BuckledState {
    /// y of the free end's centre / L (signed).
    pub tip_deviation: f64,
    /// Whether the buckled equilibrium is stable (no negative Hessian eigenvalue).
    pub stable: Option<bool>,
    /// Its energy minus the planar state's (J; negative: the buckled state is preferred).
    pub energy_drop: f64,
}

/// Largest vertex displacement of the branch-switching kick, relative to L.
const SWITCH_AMPLITUDE: f64 = 1e-2;

/// Newton iterations allowed from the kick to the buckled state.
const BRANCH_SWITCH_ITERATIONS: usize = 3000;

impl LateralBucklingCase {
    /// Elements across the width: square elements, as in the seed (at least 1).
    pub fn n_width(&self) -> usize {
        ((self.width_ratio * self.n_length as f64).round() as usize).max(1)
    }

    /// The strip at Γ_shell = `gamma`, gravity −z (in its plane, along the width).
    pub fn build(&self, gamma: f64) -> Result<Shell, ModelError> {
        if !(gamma.is_finite() && gamma >= 0.0) {
            return Err(ModelError::parameter("gamma", gamma, "finite and >= 0"));
        }
        let p = self.material.properties(self.width_ratio);
        ShellBuilder::new(p)
            .elements(self.n_length, self.n_width())
            .grading(Grading::Uniform)
            .gravity(Vec3::new(0.0, 0.0, -p.gravity_for_gamma(gamma)))
            .build()
    }

    /// The planar equilibrium at Γ (gravity ramped from the flat strip; the loads have no
    /// out-of-plane component, so Newton stays on the planar branch even where it is
    /// unstable) and its report, whose inertia says whether it is stable.
    pub fn planar_state(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<(ShellState, SolveReport), ModelError> {
        let shell = self.build(gamma)?;
        let flat = shell.rest_state();
        let mut solver = EquilibriumSolver::new(&shell, &flat, params.clone());
        let s = solver.solve(&shell, &flat, 0.0, 1.0);
        Ok((s.state, s.report))
    }

    /// `Some(true)` if the planar state at Γ is unstable (a negative Hessian eigenvalue),
    /// `Some(false)` if stable, `None` if it did not converge or the inertia is unknown.
    pub fn planar_unstable(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<Option<bool>, ModelError> {
        let (_, report) = self.planar_state(gamma, params)?;
        Ok(report.stable().map(|s| !s))
    }

    /// Γ_c by bisection (in log Γ) on the sign of the inertia along the planar branch, within
    /// [lo, hi] (lo must be stable, hi unstable) to relative width `rel_tol`. `None` if the
    /// bracket is not valid or a probe does not converge.
    pub fn critical_gamma(
        &self,
        lo: f64,
        hi: f64,
        rel_tol: f64,
        params: &SolverParams,
    ) -> Result<Option<f64>, ModelError> {
        let (mut lo, mut hi) = (lo, hi);
        if self.planar_unstable(lo, params)? != Some(false)
            || self.planar_unstable(hi, params)? != Some(true)
        {
            return Ok(None);
        }
        while hi / lo - 1.0 > rel_tol {
            let mid = (lo * hi).sqrt();
            match self.planar_unstable(mid, params)? {
                Some(true) => hi = mid,
                Some(false) => lo = mid,
                None => return Ok(None),
            }
        }
        Ok(Some((lo * hi).sqrt()))
    }

    /// The stability route's branch switch at Γ (design.md §4.5): if the planar equilibrium is
    /// unstable, kick it along its lowest mode (largest vertex displacement 1e-2·L, both
    /// signs) and re-equilibrate; returns the lower-energy result. `None` if the planar state
    /// is stable, did not converge, or no kicked solve converged.
    pub fn branch_switch(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<Option<BuckledState>, ModelError> {
        let shell = self.build(gamma)?;
        let flat = shell.rest_state();
        let params = SolverParams {
            compute_lambda_min: true,
            ..params.clone()
        };
        let mut solver = EquilibriumSolver::new(&shell, &flat, params);
        let planar = solver.solve(&shell, &flat, 0.0, 1.0);
        let (true, Some(false), Some(mode)) = (
            planar.report.converged(),
            planar.report.stable(),
            planar.lowest_mode.as_ref(),
        ) else {
            return Ok(None);
        };
        let dofs = shell.dofs();
        let max_disp = (0..mode.shape.len())
            .filter(|&i| !dofs.is_angle(i))
            .map(|i| mode.shape[i].abs())
            .fold(0.0, f64::max);
        if !(max_disp > 0.0) {
            return Ok(None);
        }
        let scale = SWITCH_AMPLITUDE * shell.properties().length / max_disp;
        let planar_energy = shell.energy(&planar.state, 1.0);
        let mut best: Option<BuckledState> = None;
        let mut kicked = planar.state.clone();
        // From the kick to the buckled state is a long way (|y_tip| grows from 1e-2·L to tenths
        // of L) in steps of about a thickness: a long minimization (≈ 340 iterations measured
        // at n_L = 8, w/L = 0.1, 1.2 Γ_c).
        solver.params.max_iterations = BRANCH_SWITCH_ITERATIONS.max(solver.params.max_iterations);
        for sign in [1.0, -1.0] {
            shell.displace(&planar.state, &mode.shape, sign * scale, &mut kicked);
            let s = solver.solve(&shell, &kicked, 1.0, 1.0);
            if !s.report.converged() {
                continue;
            }
            let drop = shell.energy(&s.state, 1.0) - planar_energy;
            if best.as_ref().is_none_or(|b| drop < b.energy_drop) {
                let end = column_centre(&shell, &s.state.positions, shell.mesh().n_length);
                best = Some(BuckledState {
                    tip_deviation: end.y / shell.properties().length,
                    stable: s.report.stable(),
                    energy_drop: drop,
                });
            }
        }
        Ok(best)
    }

    /// The seed's protocol at Γ: rotate the clamp about x by `sigma` (rad; the unloaded strip
    /// turns rigidly with it), ramp gravity to its full value in `load_steps` steps, rotate the
    /// clamp back in as many steps, and re-equilibrate. Returns the y of the free end's centre.
    pub fn protocol(
        &self,
        gamma: f64,
        sigma: f64,
        load_steps: usize,
        params: &SolverParams,
    ) -> Result<ProtocolOutcome, ModelError> {
        if load_steps == 0 {
            return Err(ModelError::structure(
                "load_steps",
                "got 0; need at least 1",
            ));
        }
        let mut shell = self.build(gamma)?;
        let mut state = shell.rest_state();
        let rotation = nalgebra::Rotation3::from_axis_angle(&Vec3::x_axis(), sigma);
        for p in state.positions.iter_mut() {
            *p = rotation * *p;
        }
        shell.set_clamp_rotation(sigma, &mut state);
        let mut solver = EquilibriumSolver::new(&shell, &state, params.clone());
        let m = load_steps as f64;
        // The first stage that failed, if any: its report is the one returned.
        let mut failure: Option<SolveReport> = None;
        for k in 0..load_steps {
            let s = solver.solve(&shell, &state, k as f64 / m, (k + 1) as f64 / m);
            state = s.state;
            if !s.report.converged() {
                failure.get_or_insert(s.report);
            }
        }
        // Rotating the clamp back, stage by stage: the clamp angle is the solver's continuation
        // parameter (LoadPath::ClampRotation), so each stage gets adaptive steps and the
        // secant predictor like the gravity ramp.
        for k in 1..=load_steps {
            let from = sigma * (1.0 - (k - 1) as f64 / m);
            let to = sigma * (1.0 - k as f64 / m);
            shell.set_load_path(LoadPath::ClampRotation { from, to });
            let s = solver.solve(&shell, &state, 0.0, 1.0);
            state = s.state;
            shell.set_load_path(LoadPath::Gravity);
            shell.set_clamp_rotation(to, &mut state);
            if !s.report.converged() {
                failure.get_or_insert(s.report);
                break;
            }
        }
        // Re-equilibrate with the clamp back at 0 (on a converged path this confirms the state
        // in one assembly and measures its residual and inertia).
        shell.set_clamp_rotation(0.0, &mut state);
        let s = solver.solve(&shell, &state, 1.0, 1.0);
        state = s.state;
        let converged = failure.is_none() && s.report.converged();
        let report = failure.unwrap_or(s.report);
        let end = column_centre(&shell, &state.positions, shell.mesh().n_length);
        Ok(ProtocolOutcome {
            tip_deviation: end.y / shell.properties().length,
            converged,
            report,
        })
    }
}
