//! One lateral-buckling strip: its planar equilibrium and stability at a given Γ_shell, the
//! critical Γ_c by bisection on the inertia, and the seed's protocol (rotate the clamp about x
//! by σ, ramp gravity in m_ls steps, rotate the clamp back, measure the free end's y), for
//! either shell model.

use slender_core::geometry::Vec3;
use slender_core::rod::Grading;
use slender_core::solver::{EquilibriumSolver, SolveReport, SolverParams};
use slender_core::ModelError;

use crate::materials::ShellMaterialSet;
use crate::numerics::{bisect, Bisection, NumericsError, Side};
use crate::shell_model::{ShellModel, Strip, StripModel, StripSpec};
use crate::with_strip;

/// A strip of the lateral-buckling benchmark.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LateralBucklingCase {
    /// Material set.
    pub material: ShellMaterialSet,
    /// Aspect ratio w/L (> 0).
    pub width_ratio: f64,
    /// Elements along the length.
    pub n_length: usize,
    /// Shell discretization.
    pub model: ShellModel,
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
    /// Newton iterations over all stages.
    pub iterations: usize,
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

/// Largest displacement of the branch-switching kick, relative to L.
const SWITCH_AMPLITUDE: f64 = 1e-2;

/// Consecutive shifted (indefinite) Newton iterations after which a protocol stage's load
/// step is halved (`SolverParams::indefinite_patience`). Measured on w/L = 0.5, n_L = 15 and
/// 30 (both shell models): a stage step that lands near the saddle of the planar branch
/// crawls on for the full 30 iterations, while its half steps converge in about 5; 5 saved
/// more iterations than 8, with the same end states.
const INDEFINITE_PATIENCE: usize = 5;

/// Newton iterations allowed from the kick to the buckled state.
const BRANCH_SWITCH_ITERATIONS: usize = 3000;

impl LateralBucklingCase {
    /// Elements across the width: square elements, as in the seed (at least 1).
    pub fn n_width(&self) -> usize {
        self.model
            .square_width_elements(self.width_ratio, self.n_length, 1)
    }

    /// The strip at Γ_shell = `gamma`, gravity −z (in its plane, along the width).
    pub fn build(&self, gamma: f64) -> Result<Strip, ModelError> {
        if !(gamma.is_finite() && gamma >= 0.0) {
            return Err(ModelError::parameter("gamma", gamma, "finite and >= 0"));
        }
        let p = self.material.properties(self.width_ratio);
        StripSpec {
            model: self.model,
            properties: p,
            n_length: self.n_length,
            n_width: self.n_width(),
            grading: Grading::Uniform,
            gravity: Vec3::new(0.0, 0.0, -p.gravity_for_gamma(gamma)),
        }
        .build()
    }

    /// The report of the planar equilibrium at Γ (gravity ramped from the flat strip; the
    /// loads have no out-of-plane component, so Newton stays on the planar branch even where
    /// it is unstable), whose inertia says whether it is stable.
    pub fn planar_report(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<SolveReport, ModelError> {
        let strip = self.build(gamma)?;
        Ok(with_strip!(&strip, s => {
            let flat = s.rest();
            let mut solver = EquilibriumSolver::new(s, &flat, *params);
            solver.solve(s, &flat, 0.0, 1.0).report
        }))
    }

    /// `Some(true)` if the planar state at Γ is unstable (a negative Hessian eigenvalue),
    /// `Some(false)` if stable, `None` if it did not converge or the inertia is unknown.
    pub fn planar_unstable(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<Option<bool>, ModelError> {
        Ok(self.planar_report(gamma, params)?.stable().map(|s| !s))
    }

    /// Γ_c by bisection (in log Γ, [`crate::numerics::bisect`]) on the sign of the inertia
    /// along the planar branch, within [lo, hi] (lo must be stable, hi unstable) to relative
    /// width `rel_tol`. `None` if the bracket is not valid or a probe does not converge; an
    /// error if `lo` or `hi` is not finite and `> 0` or `rel_tol` is not finite and `≥ 0`.
    pub fn critical_gamma(
        &self,
        lo: f64,
        hi: f64,
        rel_tol: f64,
        params: &SolverParams,
    ) -> Result<Option<f64>, ModelError> {
        // The inertia needs no eigenvalue.
        let params = SolverParams {
            compute_lambda_min: false,
            ..*params
        };
        // Checked before the end solves (the bisection would only see them after).
        for (name, v) in [("lo", lo), ("hi", hi)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ModelError::parameter(name, v, "finite and > 0"));
            }
        }
        if !(rel_tol.is_finite() && rel_tol >= 0.0) {
            return Err(ModelError::parameter("rel_tol", rel_tol, "finite and >= 0"));
        }
        if self.planar_unstable(lo, &params)? != Some(false)
            || self.planar_unstable(hi, &params)? != Some(true)
        {
            return Ok(None);
        }
        /// Why a probe ended the search.
        enum Stop {
            Failed(ModelError),
            NoVerdict,
        }
        let side = |gamma| match self.planar_unstable(gamma, &params) {
            Ok(Some(true)) => Ok(Side::High),
            Ok(Some(false)) => Ok(Side::Low),
            Ok(None) => Err(Stop::NoVerdict),
            Err(e) => Err(Stop::Failed(e)),
        };
        match bisect(side, lo, hi, Bisection::log(rel_tol)) {
            Ok(gamma_c) => Ok(Some(gamma_c)),
            Err(NumericsError::Evaluation(Stop::NoVerdict)) => Ok(None),
            Err(NumericsError::Evaluation(Stop::Failed(e))) => Err(e),
            Err(NumericsError::InvalidInput { name, value, range }) => {
                Err(ModelError::parameter(name, value, range))
            }
            // `bisect` reports neither (it takes the bracket as given and always stops).
            Err(NumericsError::NotBracketed { .. } | NumericsError::NoConvergence { .. }) => {
                Ok(None)
            }
        }
    }

    /// The stability route's branch switch at Γ (design.md §4.5): if the planar equilibrium is
    /// unstable, kick it along its lowest mode (largest displacement 1e-2·L, both signs) and
    /// re-equilibrate; returns the lower-energy result. `None` if the planar state is stable,
    /// did not converge, or no kicked solve converged.
    pub fn branch_switch(
        &self,
        gamma: f64,
        params: &SolverParams,
    ) -> Result<Option<BuckledState>, ModelError> {
        let strip = self.build(gamma)?;
        Ok(with_strip!(&strip, s => branch_switch(s, params)))
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
        let mut strip = self.build(gamma)?;
        Ok(with_strip!(&mut strip, s => protocol(s, sigma, load_steps, params)))
    }
}

fn branch_switch<S: StripModel>(shell: &S, params: &SolverParams) -> Option<BuckledState> {
    let flat = shell.rest();
    let params = SolverParams {
        compute_lambda_min: true,
        ..*params
    };
    let mut solver = EquilibriumSolver::new(shell, &flat, params);
    let planar = solver.solve(shell, &flat, 0.0, 1.0);
    let (true, Some(false), Some(mode)) = (
        planar.report.converged(),
        planar.report.stable(),
        planar.lowest_mode.as_ref(),
    ) else {
        return None;
    };
    let max_disp = (0..mode.shape.len())
        .filter(|&i| shell.is_displacement(i))
        .map(|i| mode.shape[i].abs())
        .fold(0.0, f64::max);
    if !(max_disp > 0.0) {
        return None;
    }
    let length = shell.length();
    let scale = SWITCH_AMPLITUDE * length / max_disp;
    let planar_energy = shell.energy(&planar.state, 1.0);
    let mut best: Option<BuckledState> = None;
    let mut kicked = planar.state.clone();
    // From the kick to the buckled state is a long way (|y_tip| grows from 1e-2·L to tenths
    // of L): allow a long minimization.
    solver.params.max_iterations = BRANCH_SWITCH_ITERATIONS.max(solver.params.max_iterations);
    for sign in [1.0, -1.0] {
        shell.displace(&planar.state, &mode.shape, sign * scale, &mut kicked);
        let s = solver.solve(shell, &kicked, 1.0, 1.0);
        if !s.report.converged() {
            continue;
        }
        let drop = shell.energy(&s.state, 1.0) - planar_energy;
        if best.as_ref().is_none_or(|b| drop < b.energy_drop) {
            best = Some(BuckledState {
                tip_deviation: shell.centre(&s.state, true).y / length,
                stable: s.report.stable(),
                energy_drop: drop,
            });
        }
    }
    best
}

fn protocol<S: StripModel>(
    shell: &mut S,
    sigma: f64,
    load_steps: usize,
    params: &SolverParams,
) -> ProtocolOutcome {
    // Only the last state's inertia is reported; the stages need no eigenvalue, and their
    // last iterate no Hessian: a stage's converged state is measured (residual and decrement)
    // by a gradient-only assembly after the full Newton step (`chord_final_check`; its
    // inertia would lag one step, and no stage reports one). The final re-equilibration
    // below measures the end state with its own Hessian.
    let params = SolverParams {
        compute_lambda_min: false,
        indefinite_patience: Some(INDEFINITE_PATIENCE),
        chord_final_check: true,
        ..*params
    };
    let mut state = shell.rest();
    shell.turn_rigidly(sigma, &mut state);
    shell.ramp_gravity();
    // One solve per stage, each starting from the last stage's equilibrium (measured: a
    // secant predictor across the stages, i.e. one continuation with the stages as steps,
    // takes two to three times more Newton iterations — its linear extrapolation of a
    // turning strip is a worse start than the last equilibrium or the rigidly turned one).
    let mut solver = EquilibriumSolver::new(&*shell, &state, params);
    let m = load_steps as f64;
    let mut iterations = 0;
    // The first stage that failed, if any: its report is the one returned.
    let mut failure: Option<SolveReport> = None;
    // Every stage after the first starts from the tangent predictor: the first Newton step
    // from the last equilibrium (gravity steps) or from the strip turned rigidly with its
    // clamp (clamp turns, whose Hessian is the last one turned with the strip), solved with
    // the last equilibrium's factorization (`chord_predictor`, `EquilibriumProblem::turn_free`),
    // which saves that step's Hessian assembly and factorization. The first stage has no
    // factorization yet.
    solver.params.chord_predictor = true;
    for k in 0..load_steps {
        let report = solver.solve_in_place(&*shell, &mut state, k as f64 / m, (k + 1) as f64 / m);
        iterations += report.iterations;
        if !report.converged() {
            failure.get_or_insert(report);
        }
    }
    // Rotating the clamp back, stage by stage: the clamp angle is the solver's continuation
    // parameter, so each stage gets adaptive steps, and each step's first guess turns the
    // strip rigidly with the clamp (the strips have no secant predictor on this path).
    for k in 1..=load_steps {
        let from = sigma * (1.0 - (k - 1) as f64 / m);
        let to = sigma * (1.0 - k as f64 / m);
        shell.rotate_clamp(from, to);
        let report = solver.solve_in_place(&*shell, &mut state, 0.0, 1.0);
        iterations += report.iterations;
        if !report.converged() {
            failure.get_or_insert(report);
            break;
        }
    }
    // Re-equilibrate with the clamp back at 0 (on a converged path this confirms the state in
    // one assembly and measures its residual and inertia).
    shell.ramp_gravity();
    solver.params.chord_final_check = false;
    let report = solver.solve_in_place(&*shell, &mut state, 1.0, 1.0);
    iterations += report.iterations;
    let converged = failure.is_none() && report.converged();
    ProtocolOutcome {
        tip_deviation: shell.centre(&state, true).y / shell.length(),
        converged,
        report: failure.unwrap_or(report),
        iterations,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::OMEGA_SHELL;

    /// Ramps gravity on the tilted strip in two solves (0 → ½ → 1), then turns the clamp back
    /// half way, the last two solves with or without the tangent (chord) predictor; returns
    /// their Newton iterations and the free end's centre (m) after each.
    fn gravity_then_turn<S: StripModel>(shell: &mut S, tangent: bool) -> [(usize, Vec3); 2] {
        let mut state = shell.rest();
        shell.turn_rigidly(0.2, &mut state);
        shell.ramp_gravity();
        let params = SolverParams {
            compute_lambda_min: false,
            ..SolverParams::default()
        };
        let mut solver = EquilibriumSolver::new(&*shell, &state, params);
        assert!(solver
            .solve_in_place(&*shell, &mut state, 0.0, 0.5)
            .converged());
        solver.params.chord_predictor = tangent;
        let report = solver.solve_in_place(&*shell, &mut state, 0.5, 1.0);
        assert!(report.converged(), "{report:?}");
        let gravity = (report.iterations, shell.centre(&state, true));
        shell.rotate_clamp(0.2, 0.1);
        let report = solver.solve_in_place(&*shell, &mut state, 0.0, 1.0);
        assert!(report.converged(), "{report:?}");
        [gravity, (report.iterations, shell.centre(&state, true))]
    }

    /// The tangent predictor of a gravity step (the first Newton step from the last
    /// equilibrium, solved with its factorization) and of a clamp turn (the same from the
    /// rigidly turned strip, with the factorization turned with it) saves that step's Newton
    /// iteration and lands on the same equilibrium, for both shell models (the regular runs
    /// of the lateral-buckling protocol, where it is used).
    #[test]
    fn the_tangent_predictor_saves_an_iteration_and_keeps_the_equilibrium() {
        for model in [ShellModel::Midedge, ShellModel::Bspline] {
            let case = LateralBucklingCase {
                material: OMEGA_SHELL,
                width_ratio: 0.5,
                n_length: 8,
                model,
            };
            let mut strip = case.build(17.0).unwrap();
            let (plain, tangent, length) = with_strip!(&mut strip, s => {
                let plain = gravity_then_turn(s, false);
                s.ramp_gravity();
                (plain, gravity_then_turn(s, true), s.length())
            });
            for (stage, ((p, end_p), (t, end_t))) in ["gravity", "turn"]
                .into_iter()
                .zip(plain.into_iter().zip(tangent))
            {
                assert!(
                    t < p,
                    "{model:?} {stage}: {t} iterations with the tangent predictor, {p} without"
                );
                // A lateral deflection of tenths of L: the predictor carried a large step.
                assert!(end_p.y.abs() > 0.05 * length, "{end_p:?}");
                assert!(
                    (end_t - end_p).norm() < 1e-7 * length,
                    "{model:?} {stage}: {end_t:?} vs {end_p:?}"
                );
            }
        }
    }
}
