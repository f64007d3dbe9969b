//! Deciding 2-D vs 3-D by physics: the stability of the planar equilibrium.
//!
//! At a planar state (the coil in the xz-plane, gravity −z) the Hessian splits exactly into an
//! in-plane block (x, z coordinates) and an out-of-plane block (y coordinates and twist angles):
//! by the mirror symmetry y ↦ −y no energy term couples them. The planar state is stable
//! against buckling out of its plane exactly when the out-of-plane block is positive definite;
//! its smallest eigenvalue in the mass metric (a squared natural frequency, normalized by
//! EI/(ρA L⁴)) is a signed, continuous distance to the bifurcation. If the block is
//! indefinite, the solver switches branch along its lowest eigenvector and converges the 3-D
//! equilibrium (design.md §4.5).

use serde::{Deserialize, Serialize};
use slender_core::geometry::Vec3;
use slender_core::linalg::{smallest_eigenpair, BandLdlt, SymmetricBandMatrix};
use slender_core::rod::{Rod, RodState};

use crate::rod_model::{BenchmarkRod, RodModel};
use slender_core::solver::{EquilibriumSolver, SolveStatus, SolverParams};
use slender_core::ModelError;

use super::case::BendTwistCase;
use super::measures::{shape_measures, ShapeMeasures};

/// Snap budget of the second attempt at the planar ramp.
const PATIENT_SNAP_ITERATIONS: usize = 3000;

/// Largest displacement (units of L) of the perturbation along the unstable mode.
const SWITCH_AMPLITUDE: f64 = 1e-2;

/// What the stability route found at one (X, Y).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StabilityOutcome {
    /// The planar equilibrium converged.
    pub planar_converged: bool,
    /// Why not, if it did not.
    pub failure: String,
    /// Negative eigenvalues of the out-of-plane block (0: the planar state is stable).
    pub out_of_plane_negative: Option<usize>,
    /// Negative eigenvalues of the whole Hessian (in-plane folds count here too).
    pub total_negative: Option<usize>,
    /// Smallest out-of-plane eigenvalue in the mass metric / (EI/(ρA L⁴)): the signed distance
    /// to the bifurcation.
    pub lambda_out_normalized: Option<f64>,
    /// Newton iterations of the planar solve.
    pub iterations: usize,
    /// Measures of the buckled 3-D equilibrium, when the planar one is unstable and the
    /// branch switch converged.
    pub buckled: Option<ShapeMeasures>,
    /// The buckled equilibrium is stable (no negative eigenvalue at all).
    pub buckled_stable: Option<bool>,
    /// Energy of the buckled state minus that of the planar state (J); negative.
    pub buckled_energy_drop: Option<f64>,
}

impl StabilityOutcome {
    /// The decision: `Some(true)` for 3-D (planar state unstable out of plane), `Some(false)`
    /// for 2-D, `None` if the planar equilibrium did not converge (never classified).
    pub fn three_dimensional(&self) -> Option<bool> {
        if !self.planar_converged {
            return None;
        }
        self.out_of_plane_negative.map(|k| k > 0)
    }
}

/// The out-of-plane block of `hess` over the free DOFs `idx`, optionally scaled to the mass
/// metric.
fn block<P: BenchmarkRod>(
    rod: &P,
    hess: &SymmetricBandMatrix,
    idx: &[usize],
    mass_scaled: bool,
) -> SymmetricBandMatrix {
    let bw = P::OUT_OF_PLANE_BANDWIDTH;
    let m = idx.len();
    let mut b = SymmetricBandMatrix::new(m, bw);
    let scale: Vec<f64> = idx
        .iter()
        .map(|&i| {
            if mass_scaled {
                1.0 / rod.inertia_metric(i).sqrt()
            } else {
                1.0
            }
        })
        .collect();
    for r in 0..m {
        for c in r.saturating_sub(bw)..=r {
            let v = hess.get(idx[r], idx[c]);
            if v != 0.0 {
                b.add(r, c, v * scale[r] * scale[c]);
            }
        }
    }
    b
}

/// Converges the planar equilibrium of `case` under full gravity −z, reads the stability of
/// its out-of-plane block and, if unstable, switches to the 3-D branch.
pub fn decide_by_stability(
    case: &BendTwistCase,
    params: &SolverParams,
) -> Result<(StabilityOutcome, Vec<Vec3>), ModelError> {
    decide_by_stability_with(case, RodModel::Der, params)
}

/// As [`decide_by_stability`] with the rod formulation `model`.
pub fn decide_by_stability_with(
    case: &BendTwistCase,
    model: RodModel,
    params: &SolverParams,
) -> Result<(StabilityOutcome, Vec<Vec3>), ModelError> {
    crate::with_rod_model!(model, P => {
        let (out, state) = decide_with_state_for::<P>(case, model, params)?;
        Ok((out, P::positions(&state).to_vec()))
    })
}

/// As [`decide_by_stability`], returning the final state (the buckled one if the planar state
/// is unstable and the switch converged, else the planar one).
pub fn decide_with_state(
    case: &BendTwistCase,
    params: &SolverParams,
) -> Result<(StabilityOutcome, RodState), ModelError> {
    decide_with_state_for::<Rod>(case, RodModel::Der, params)
}

/// As [`decide_with_state`] for any rod formulation (`P` the type of `model`).
pub fn decide_with_state_for<P: BenchmarkRod>(
    case: &BendTwistCase,
    model: RodModel,
    params: &SolverParams,
) -> Result<(StabilityOutcome, P::State), ModelError> {
    let g = case.gravity();
    let gravity = Vec3::new(0.0, 0.0, -g);
    // The planar equilibrium is followed with the motion restricted to the plane, so that the
    // ramp never wanders near out-of-plane saddles; its stability is then read off the full
    // rod's Hessian at that state.
    let planar_rod = P::from_spec(&case.spec(gravity, Vec3::zeros(), Some(1))?.for_model(model))?;
    let start = planar_rod.rest().clone();
    let mut planar =
        EquilibriumSolver::new(&planar_rod, &start, *params).solve(&planar_rod, &start, 0.0, 1.0);
    if !planar.report.converged() {
        // Fine meshes of many-turn coils at very large Γ unwind through long in-plane snaps:
        // give them a larger minimization budget before declaring failure.
        let patient = SolverParams {
            snap_iterations: PATIENT_SNAP_ITERATIONS.max(params.snap_iterations),
            ..*params
        };
        let first = planar.report.iterations;
        planar = EquilibriumSolver::new(&planar_rod, &start, patient).solve(
            &planar_rod,
            &start,
            0.0,
            1.0,
        );
        planar.report.iterations += first;
    }
    let rod = P::from_spec(&case.spec(gravity, Vec3::zeros(), None)?.for_model(model))?;
    let switch_params = SolverParams {
        max_iterations: 10 * params.max_iterations,
        ..*params
    };
    let mut solver = EquilibriumSolver::new(&rod, &start, switch_params);
    let mut out = StabilityOutcome {
        planar_converged: planar.report.converged(),
        failure: match &planar.report.status {
            SolveStatus::Converged => String::new(),
            SolveStatus::NotConverged { reason } => reason.clone(),
        },
        out_of_plane_negative: None,
        total_negative: planar.report.inertia.map(|i| i.negative),
        lambda_out_normalized: None,
        iterations: planar.report.iterations,
        buckled: None,
        buckled_stable: None,
        buckled_energy_drop: None,
    };
    if !out.planar_converged {
        return Ok((out, planar.state));
    }
    let n = rod.n_free();
    let mut grad = vec![0.0; n];
    let mut abs = vec![0.0; n];
    let mut hess = rod.new_hessian();
    rod.assemble(&planar.state, 1.0, &mut grad, &mut hess, &mut abs);
    let idx = rod.out_of_plane_dofs(1);
    let mut ldlt = BandLdlt::new();
    let inertia = ldlt.factorize(&block(&rod, &hess, &idx, false), 0.0).ok();
    out.out_of_plane_negative = inertia.map(|i| i.negative + i.zero);
    let mode = smallest_eigenpair(&block(&rod, &hess, &idx, true), &mut ldlt, 1e-8).ok();
    out.lambda_out_normalized = mode.as_ref().map(|m| m.value / rod.eigenvalue_scale());
    if out.three_dimensional() != Some(true) {
        return Ok((out, planar.state));
    }
    let Some(mode) = mode else {
        return Ok((out, planar.state));
    };
    // Branch switching: the mode in the free DOFs (mass scaling undone), scaled so that the
    // largest displacement is SWITCH_AMPLITUDE·L; try both signs, keep the lower energy.
    let mut shape = vec![0.0; n];
    for (k, &i) in idx.iter().enumerate() {
        shape[i] = mode.vector[k] / rod.inertia_metric(i).sqrt();
    }
    let max_disp = idx
        .iter()
        .filter(|&&i| !rod.is_rotational(i))
        .map(|&i| shape[i].abs())
        .fold(0.0, f64::max);
    if max_disp > 0.0 {
        let s = SWITCH_AMPLITUDE * rod.rod_length() / max_disp;
        shape.iter_mut().for_each(|v| *v *= s);
    }
    let planar_energy = rod.energy(&planar.state, 1.0);
    let mut best: Option<(f64, P::State, bool)> = None;
    for sign in [1.0, -1.0] {
        let mut kicked = planar.state.clone();
        rod.displace(&planar.state, &shape, sign, &mut kicked);
        let sol = solver.solve(&rod, &kicked, 1.0, 1.0);
        out.iterations += sol.report.iterations;
        if sol.report.converged() {
            let e = rod.energy(&sol.state, 1.0);
            if best.as_ref().is_none_or(|b| e < b.0) {
                best = Some((e, sol.state.clone(), sol.report.stable() == Some(true)));
            }
        }
    }
    let state = match best {
        Some((e, state, stable)) => {
            out.buckled = Some(shape_measures(
                P::positions(&state),
                rod.element_lengths(),
                rod.rod_length(),
            ));
            out.buckled_stable = Some(stable);
            out.buckled_energy_drop = Some(e - planar_energy);
            state
        }
        None => planar.state,
    };
    Ok((out, state))
}
