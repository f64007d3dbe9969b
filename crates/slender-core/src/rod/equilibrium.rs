//! The rod as an [`EquilibriumProblem`]: what the Newton solver sees, including step caps,
//! scales and the mass metric.

use crate::linalg::SymmetricBandMatrix;
use crate::solver::problem::{AssemblyInfo, EquilibriumProblem};

use super::dofs::ROD_HALF_BANDWIDTH;
use super::model::{Rod, Terms};
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
}

impl EquilibriumProblem for Rod {
    type State = RodState;

    fn n_free(&self) -> usize {
        self.dofs.n_free()
    }

    type Hessian = SymmetricBandMatrix;

    fn new_hessian(&self) -> SymmetricBandMatrix {
        SymmetricBandMatrix::new(self.n_free(), ROD_HALF_BANDWIDTH)
    }

    fn energy(&self, state: &RodState, load: f64) -> f64 {
        self.energy_terms(state, load, Terms::ALL)
    }

    fn assemble(
        &self,
        state: &RodState,
        load: f64,
        grad: &mut [f64],
        hess: &mut SymmetricBandMatrix,
        abs_grad: &mut [f64],
    ) -> AssemblyInfo {
        self.assemble_terms(
            state,
            load,
            Terms::ALL,
            Some(grad),
            Some(hess),
            Some(abs_grad),
        )
    }

    fn dof_values(&self, state: &RodState, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            let f = self.dofs.full_index(i);
            *o = if f % 4 == 3 {
                state.thetas[f / 4]
            } else {
                state.positions[f / 4][f % 4]
            };
        }
    }

    fn displace(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.retract(state, dx, alpha, out);
    }

    fn max_step(&self, state: &RodState, dx: &[f64]) -> f64 {
        let (turn, change) = self.max_edge_rotation(state, dx);
        let theta = (0..dx.len())
            .filter(|&i| self.dofs.is_angle(i))
            .map(|i| dx[i].abs())
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
