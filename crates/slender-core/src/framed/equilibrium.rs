//! A framed rod as an [`EquilibriumProblem`]: what the discrete Cosserat rod and the SE(3)
//! beam share (DOF layout, loads, load path, retraction, difference, mass metric) is written
//! once here; a model supplies its elastic terms and how a step carries an edge's chord.

use crate::assembly::{Assembler, TermGroup};
use crate::geometry::Vec3;
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};
use crate::solver::problem::{EquilibriumProblem, MassMetric};

use super::groups::ALL_GROUPS;
use super::{FramedCore, FramedState};

/// A rod formulation on [`FramedCore`] (the Cosserat rod, the SE(3) beam).
pub trait FramedModel {
    /// Half-bandwidth of its Hessian in the framed DOF layout.
    const HALF_BANDWIDTH: usize;

    /// The shared part: DOFs, supports, loads, masses, rest state, load path.
    fn core(&self) -> &FramedCore;

    /// Runs every elastic term, then the external loads, through `asm`.
    fn assemble_terms<M: SymmetricMatrix>(
        &self,
        state: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    );

    /// Edge `j`'s chord (m) after the step `alpha·dx` from `state`: how the model carries a
    /// chord with its frames so that its strain changes linearly along the step.
    fn chord_after_step(&self, state: &FramedState, dx: &[f64], alpha: f64, j: usize) -> Vec3;
}

impl<T: FramedModel> EquilibriumProblem for T {
    type State = FramedState;
    type Hessian = SymmetricBandMatrix;

    fn n_free(&self) -> usize {
        self.core().dofs.n_free()
    }

    fn new_hessian(&self) -> SymmetricBandMatrix {
        SymmetricBandMatrix::new(self.n_free(), T::HALF_BANDWIDTH)
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
        self.assemble_terms(state, load, asm);
    }

    fn difference(&self, a: &FramedState, b: &FramedState, out: &mut [f64]) {
        self.core().difference(a, b, out);
    }

    fn chart(&self, state: &FramedState, dx: &[f64], out: &mut FramedState) {
        self.core().displace_linear(state, dx, 1.0, out);
    }

    fn displace(&self, state: &FramedState, dx: &[f64], alpha: f64, out: &mut FramedState) {
        self.core().retract_with(state, dx, alpha, out, |j| {
            self.chord_after_step(state, dx, alpha, j)
        });
    }

    fn impose_load(&self, state: &mut FramedState, from: f64, to: f64, guess: bool) {
        self.core().impose_path(state, from, to, guess);
    }

    fn max_step(&self, state: &FramedState, dx: &[f64]) -> f64 {
        self.core().max_step(state, dx)
    }

    fn force_length(&self, i: usize) -> f64 {
        self.core().force_length(i)
    }

    fn dof_magnitude(&self, state: &FramedState, i: usize) -> f64 {
        self.core().dof_magnitude(state, i)
    }
}

impl<T: FramedModel> MassMetric for T {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.core().inertia_metric(i)
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.core().eigenvalue_scale()
    }
}

#[cfg(feature = "testing")]
impl<T: FramedModel> crate::testing::RigidMotion for T {
    fn rigidly_moved(
        &self,
        state: &FramedState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &Vec3,
    ) -> FramedState {
        state.rigidly_transformed(rotation, offset)
    }

    fn rest(&self) -> FramedState {
        self.core().rest.clone()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        super::groups::INTERNAL
    }
}
