//! The SE(3) beam as an [`EquilibriumProblem`]: the same Newton solver, load stepping and
//! stability analysis as the discrete elastic rod.

use crate::assembly::{Assembler, TermGroup};
use crate::framed::groups::ALL_GROUPS;
use crate::framed::FramedState;
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use crate::solver::problem::{EquilibriumProblem, MassMetric};

use super::model::Se3Rod;
use super::SE3_HALF_BANDWIDTH;

impl EquilibriumProblem for Se3Rod {
    type State = FramedState;
    type Hessian = SymmetricBandMatrix;

    fn n_free(&self) -> usize {
        self.core.dofs.n_free()
    }

    fn new_hessian(&self) -> SymmetricBandMatrix {
        SymmetricBandMatrix::new(self.n_free(), SE3_HALF_BANDWIDTH)
    }

    fn term_groups(&self) -> &[TermGroup] {
        &ALL_GROUPS
    }

    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.assemble_into(state, load, asm);
    }

    fn difference(&self, a: &FramedState, b: &FramedState, out: &mut [f64]) {
        self.core.difference(a, b, out);
    }

    fn chart(&self, state: &FramedState, dx: &[f64], out: &mut FramedState) {
        self.core.displace_linear(state, dx, 1.0, out);
    }

    fn displace(&self, state: &FramedState, dx: &[f64], alpha: f64, out: &mut FramedState) {
        let core = &self.core;
        core.retract_with(state, dx, alpha, out, |j| {
            super::element::chord_after_step(core, state, dx, alpha, j)
        });
    }

    fn impose_load(&self, state: &mut FramedState, from: f64, to: f64, guess: bool) {
        self.core.impose_path(state, from, to, guess);
    }

    fn max_step(&self, state: &FramedState, dx: &[f64]) -> f64 {
        self.core.max_step(state, dx)
    }

    fn force_length(&self, i: usize) -> f64 {
        self.core.force_length(i)
    }

    fn dof_magnitude(&self, state: &FramedState, i: usize) -> f64 {
        self.core.dof_magnitude(state, i)
    }
}

impl MassMetric for Se3Rod {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.core.inertia_metric(i)
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.core.eigenvalue_scale()
    }
}

#[cfg(feature = "testing")]
impl crate::testing::RigidMotion for Se3Rod {
    fn rigidly_moved(
        &self,
        state: &FramedState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &crate::geometry::Vec3,
    ) -> FramedState {
        state.rigidly_transformed(rotation, offset)
    }

    fn rest(&self) -> FramedState {
        self.core.rest.clone()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        crate::framed::groups::INTERNAL
    }
}
