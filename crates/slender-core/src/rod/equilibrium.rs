//! The rod as an [`EquilibriumProblem`]: what the Newton solver sees, including step caps,
//! scales and the mass metric.

use crate::assembly::{Assembler, TermGroup};
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use crate::solver::problem::{EquilibriumProblem, MassMetric};

use super::dofs::ROD_HALF_BANDWIDTH;
use super::groups::ALL_GROUPS;
use super::model::Rod;
use super::state::RodState;

/// Largest rotation (rad) of an edge direction allowed in one Newton step.
const MAX_EDGE_TURN: f64 = std::f64::consts::FRAC_PI_4;
/// Largest change of an edge angle θ (rad) allowed in one Newton step.
const MAX_THETA_STEP: f64 = std::f64::consts::FRAC_PI_2;
/// Largest relative change of an edge vector allowed in one Newton step.
const MAX_EDGE_CHANGE: f64 = 0.5;

impl Rod {
    /// Half-bandwidth of the Hessian in the free ordering.
    pub fn half_bandwidth(&self) -> usize {
        ROD_HALF_BANDWIDTH
    }

    /// Value of free DOF `i` of `state` (m or rad).
    pub fn dof_value(&self, state: &RodState, i: usize) -> f64 {
        let f = self.dofs.full_index(i);
        if f % 4 == 3 {
            state.thetas[f / 4]
        } else {
            state.positions[f / 4][f % 4]
        }
    }

    /// Values of the free DOFs of `state` (m or rad) into `out`.
    pub fn dof_values(&self, state: &RodState, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dof_value(state, i);
        }
    }
}

impl EquilibriumProblem for Rod {
    type State = RodState;
    type Hessian = SymmetricBandMatrix;

    fn n_free(&self) -> usize {
        self.dofs.n_free()
    }

    fn new_hessian(&self) -> SymmetricBandMatrix {
        SymmetricBandMatrix::new(self.n_free(), ROD_HALF_BANDWIDTH)
    }

    fn term_groups(&self) -> &[TermGroup] {
        &ALL_GROUPS
    }

    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &RodState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.assemble_into(state, load, asm);
    }

    fn difference(&self, a: &RodState, b: &RodState, out: &mut [f64]) {
        // Coordinates and edge angles are plain numbers (the angles are measured from frames
        // transported along with the positions), so the difference is a subtraction.
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.dof_value(a, i) - self.dof_value(b, i);
        }
    }

    fn chart(&self, state: &RodState, dx: &[f64], out: &mut RodState) {
        self.displace_linear(state, dx, 1.0, out);
    }

    fn displace(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.retract(state, dx, alpha, out);
    }

    fn impose_load(&self, state: &mut RodState, from: f64, to: f64, guess: bool) {
        self.impose_path(state, from, to, guess);
    }

    fn refresh_loads(&self, state: &mut RodState) -> f64 {
        self.refresh_followers(state)
    }

    fn has_lagged_loads(&self) -> bool {
        self.has_follower_loads()
    }

    fn lagged_loads(&self, state: &RodState, out: &mut Vec<f64>) {
        out.clear();
        self.append_lagged_loads(state, out);
    }

    fn set_lagged_loads(&self, state: &mut RodState, values: &[f64]) {
        self.take_lagged_loads(state, values);
    }

    fn merit_is_energy(&self) -> bool {
        // No `merit` override: the line search measures the energy itself.
        true
    }

    fn max_step(&self, state: &RodState, dx: &[f64]) -> f64 {
        self.max_step_by(state, |i| dx[i])
    }

    fn force_length(&self, i: usize) -> f64 {
        if self.dofs.is_angle(i) {
            self.length
        } else {
            1.0
        }
    }

    fn dof_magnitude(&self, state: &RodState, i: usize) -> f64 {
        let f = self.dofs.full_index(i);
        if f % 4 == 3 {
            state.thetas[f / 4].abs().max(std::f64::consts::PI)
        } else {
            state.positions[f / 4].amax().max(self.length)
        }
    }

    fn dof_scales(&self, state: &RodState, force_length: &mut [f64], magnitude: &mut [f64]) {
        self.dof_scales_each(state, |i, l, m| {
            force_length[i] = l;
            magnitude[i] = m;
        });
    }
}

impl Rod {
    /// Calls `f(i, force_length, dof_magnitude)` for every free DOF i, in order (the values of
    /// [`EquilibriumProblem::force_length`] and [`EquilibriumProblem::dof_magnitude`]).
    pub fn dof_scales_each(&self, state: &RodState, mut f: impl FnMut(usize, f64, f64)) {
        // A vertex's coordinates share one magnitude: measured once per vertex (the free DOFs
        // of a vertex are consecutive).
        let mut vertex = usize::MAX;
        let mut magnitude = 0.0;
        for i in 0..self.dofs.n_free() {
            let full = self.dofs.full_index(i);
            if full % 4 == 3 {
                let m = state.thetas[full / 4].abs().max(std::f64::consts::PI);
                f(i, self.length, m);
            } else {
                if full / 4 != vertex {
                    vertex = full / 4;
                    magnitude = state.positions[vertex].amax().max(self.length);
                }
                f(i, 1.0, magnitude);
            }
        }
    }
}

impl Rod {
    /// The step cap of [`EquilibriumProblem::max_step`] with the step of DOF `i` given by
    /// `dx(i)`.
    pub fn max_step_by(&self, state: &RodState, dx: impl Fn(usize) -> f64 + Copy) -> f64 {
        let (turn, change) = self.max_edge_rotation(state, dx);
        let theta = (0..self.n_edges())
            .map(|j| self.dofs.theta(j))
            .filter(|&i| i != super::dofs::FIXED)
            .map(|i| dx(i).abs())
            .fold(0.0, f64::max);
        let mut alpha: f64 = 1.0;
        if turn > MAX_EDGE_TURN {
            alpha = alpha.min(MAX_EDGE_TURN / turn);
        }
        if change > MAX_EDGE_CHANGE {
            alpha = alpha.min(MAX_EDGE_CHANGE / change);
        }
        if theta > MAX_THETA_STEP {
            alpha = alpha.min(MAX_THETA_STEP / theta);
        }
        alpha
    }
}

impl MassMetric for Rod {
    fn inertia_metric(&self, i: usize) -> f64 {
        let f = self.dofs.full_index(i);
        if f % 4 == 3 {
            let j = f / 4;
            self.properties.linear_density
                * self.properties.stiffness.gyration_radius_sq()
                * self.rest_lengths[j]
        } else {
            self.vertex_masses[f / 4]
        }
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.properties.stiffness.ei_min() / (self.properties.linear_density * self.length.powi(4))
    }
}

#[cfg(feature = "testing")]
impl crate::testing::RigidMotion for Rod {
    fn rigidly_moved(
        &self,
        state: &RodState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &crate::geometry::Vec3,
    ) -> RodState {
        state.rigidly_transformed(rotation, offset)
    }

    fn rest(&self) -> RodState {
        self.rest.clone()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        super::groups::INTERNAL
    }
}
