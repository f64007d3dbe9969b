//! The solver's parameters, with documented defaults (design.md §4.3, §4.4).

use serde::{Deserialize, Serialize};

use crate::error::ModelError;

/// Tolerances and limits of the Newton solver and of load stepping.
///
/// The convergence tests are scale-invariant: nothing here has units, so the same defaults
/// work for a 1 mm wire and a 10 m hose, for Γ = 10⁻³ and for Γ = 10⁴.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(default, deny_unknown_fields)]
pub struct SolverParams {
    /// Newton decrement test: converged when gᵀH⁻¹g ≤ `energy_tolerance`·|work of the loads|.
    /// Default 1e-12.
    pub energy_tolerance: f64,
    /// Force test: converged when the largest residual force ≤ `force_tolerance`·(largest
    /// external nodal force). Default 1e-8.
    pub force_tolerance: f64,
    /// Multiplier c of the round-off floor c·ε·Σ|element forces| under which a residual is
    /// noise. Default 50.
    pub roundoff_factor: f64,
    /// Newton iterations allowed per load step before the step is declared failed. Default 30.
    pub max_iterations: usize,
    /// Armijo sufficient-decrease constant c₁. Default 1e-4.
    pub armijo: f64,
    /// Backtracking halvings allowed per line search. Default 40.
    pub max_backtracks: usize,
    /// First load step as a fraction of the whole load change (1 = try it in one step).
    /// Default 1.
    pub initial_load_step: f64,
    /// Smallest load step fraction before load stepping gives up. Default 1e-6.
    pub min_load_step: f64,
    /// Newton iterations allowed per solve, over all its load steps, snap retries and branch
    /// switches, before it gives up and reports that it did not converge. Default 20000.
    ///
    /// Why a budget: halving down to `min_load_step` alone allows about 10⁶ load steps, so a
    /// badly conditioned problem (e.g. a contact barrier far too soft for its loads, whose
    /// load steps each converge slowly and never grow) could crawl towards its load for many
    /// minutes per edit instead of saying that it cannot get there. The default is about ten
    /// times the largest solve of `slender validate` (1504 iterations, 141 load steps).
    pub max_total_iterations: usize,
    /// Largest load step as a fraction of the whole load change: steps are doubled after fast
    /// convergence up to this. Default 1.
    pub max_load_step: f64,
    /// Load steps are doubled after a step that converged in at most this many iterations.
    /// Default 5.
    pub fast_iterations: usize,
    /// Whether to compute the smallest eigenvalue of the Hessian at the solution. Default true.
    pub compute_lambda_min: bool,
    /// Newton iterations allowed when a small failed load step is retried as a snap past a
    /// fold of the loading path. Default 300.
    pub snap_iterations: usize,
    /// Full Newton steps taken after convergence, each kept only if it lowers the residual,
    /// to bring the residual from the convergence tolerance down to round-off (reactions then
    /// balance the loads to round-off). `None`: the caller's default (0 for benchmarks, 3 for
    /// scenes).
    pub polish_iterations: Option<usize>,
    /// Follow the stable branch along the load path: when a load step crosses a bifurcation
    /// (its equilibrium turns unstable), the step is halved until the crossing is bracketed and
    /// the solver follows the unstable mode to the stable branch. Not part of the scene file:
    /// scenes set it from their `unstable` policy; benchmarks keep it off (they follow the
    /// symmetric branch on purpose).
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub follow_stable: bool,
    /// Correct the first predictor of a solve that starts where the previous one converged
    /// (a warm re-solve after a small change: an interactive drag) by a chord step with the
    /// previous equilibrium's factorization; it saves about one Newton iteration per edit.
    /// Not part of the scene file: scene sessions turn it on, and so does the lateral-buckling
    /// protocol for its gravity steps (the predictor changes where Newton starts, not the load
    /// path); other benchmarks keep it off.
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub chord_predictor: bool,
    /// Once an iterate's Newton decrement passes and only the force test fails, take its full
    /// Newton step and test convergence at the new point with a gradient-only assembly and the
    /// chord decrement (the step with the iterate's factorization), instead of assembling and
    /// factoring the Hessian there: one assembly of the Hessian and one factorization fewer per
    /// solve. If that full step lowered the residual a hundredfold but not yet below the target,
    /// a second chord step with the same factorization follows before a new Hessian is
    /// assembled. The inertia, λ_min and factorization reported are then those of the Hessian
    /// one or two below-tolerance steps before the returned state (where the stability analysis needs
    /// more — an eigenvalue in the null band — the state is measured again). Not part of the
    /// scene file: scene sessions turn it on, and so do the lateral-buckling protocol's stages
    /// (not its final re-equilibration, whose inertia is reported); other benchmarks keep it
    /// off.
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub chord_final_check: bool,
    /// A load step's Newton solve gives up after this many consecutive iterations on an
    /// indefinite Hessian (shifted steps), so that the continuation halves the step at once
    /// instead of after `max_iterations`: a step that lands near a saddle crawls away from it
    /// with shifted steps, where the half step converges in a few Newton iterations. Snap
    /// retries, branch switches and single solves (zero load span) are not limited. `None`
    /// (the default): no limit. Not part of the scene file: the lateral-buckling protocol
    /// sets it.
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub indefinite_patience: Option<usize>,
    /// Take a positive definite Newton step with room for a full step (and the chord
    /// predictor's step) at once and let the next iterate's assembly, which computes the
    /// energy anyway, decide on the sufficient decrease, instead of evaluating the energy at
    /// the trial point first: one energy evaluation fewer per iteration of a warm solve, whose
    /// full steps are nearly always accepted. A rejected step is undone and backtracked as
    /// before, and the rest of that solve checks first. Only for problems whose line-search
    /// merit is their energy ([`EquilibriumProblem::merit_is_energy`]). Not part of the scene
    /// file: scene sessions turn it on; benchmarks keep it off.
    ///
    /// [`EquilibriumProblem::merit_is_energy`]: super::problem::EquilibriumProblem::merit_is_energy
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub deferred_energy_check: bool,
    /// After a chord predictor, take the first Newton step with the Hessian of the problem's
    /// slowly varying term groups ([`EquilibriumProblem::lagged_hessian_groups`], a rod's
    /// bending and twisting) kept from the previous solve's last assembly and the other
    /// groups' Hessian fresh: a dragged cable's tension changes at once, its bending stiffness
    /// turns with it by the small angle of the drag, and the step is as good as Newton's at a
    /// fraction of the assembly. Its gradient is exact; a step that is not positive definite,
    /// or an iterate that converged there, is measured again in full, so every convergence and
    /// stability verdict rests on complete Hessians. Not part of the scene file: scene
    /// sessions turn it on; benchmarks keep it off.
    ///
    /// [`EquilibriumProblem::lagged_hessian_groups`]: super::problem::EquilibriumProblem::lagged_hessian_groups
    #[serde(skip)]
    #[cfg_attr(feature = "schema", schemars(skip))]
    pub lagged_first_step: bool,
}

impl Default for SolverParams {
    fn default() -> Self {
        Self {
            energy_tolerance: 1e-12,
            force_tolerance: 1e-8,
            roundoff_factor: 50.0,
            max_iterations: 30,
            armijo: 1e-4,
            max_backtracks: 40,
            initial_load_step: 1.0,
            min_load_step: 1e-6,
            max_total_iterations: 20_000,
            max_load_step: 1.0,
            fast_iterations: 5,
            compute_lambda_min: true,
            snap_iterations: 300,
            polish_iterations: None,
            follow_stable: false,
            chord_predictor: false,
            chord_final_check: false,
            indefinite_patience: None,
            deferred_energy_check: false,
            lagged_first_step: false,
        }
    }
}

impl SolverParams {
    /// Checks every field; errors name the field and the valid range.
    pub fn validate(&self) -> Result<(), ModelError> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(ModelError::parameter(name, v, "finite and > 0"))
            }
        };
        positive("energy_tolerance", self.energy_tolerance)?;
        positive("force_tolerance", self.force_tolerance)?;
        positive("roundoff_factor", self.roundoff_factor)?;
        positive("min_load_step", self.min_load_step)?;
        if !(self.armijo > 0.0 && self.armijo < 0.5) {
            return Err(ModelError::parameter("armijo", self.armijo, "in (0, 0.5)"));
        }
        if !(self.initial_load_step > 0.0 && self.initial_load_step <= 1.0) {
            return Err(ModelError::parameter(
                "initial_load_step",
                self.initial_load_step,
                "in (0, 1]",
            ));
        }
        if !(self.max_load_step > 0.0 && self.max_load_step <= 1.0) {
            return Err(ModelError::parameter(
                "max_load_step",
                self.max_load_step,
                "in (0, 1]",
            ));
        }
        if self.polish_iterations.is_some_and(|p| p > 100) {
            return Err(ModelError::parameter(
                "polish_iterations",
                self.polish_iterations.unwrap_or(0) as f64,
                "in 0..=100",
            ));
        }
        if self.indefinite_patience == Some(0) {
            return Err(ModelError::parameter("indefinite_patience", 0.0, ">= 1"));
        }
        if self.max_iterations == 0 {
            return Err(ModelError::parameter("max_iterations", 0.0, ">= 1"));
        }
        if self.max_total_iterations < self.max_iterations {
            return Err(ModelError::parameter(
                "max_total_iterations",
                self.max_total_iterations as f64,
                format!(">= max_iterations ({})", self.max_iterations),
            ));
        }
        Ok(())
    }
}
