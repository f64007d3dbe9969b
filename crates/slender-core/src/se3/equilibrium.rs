//! The SE(3) beam on the shared framed-rod problem ([`crate::framed::equilibrium`]): its
//! elements and how a step carries an element's chord.

use crate::assembly::Assembler;
use crate::framed::{FramedCore, FramedModel, FramedState};
use crate::geometry::Vec3;
use crate::linalg::SymmetricMatrix;

use super::model::Se3Rod;
use super::SE3_HALF_BANDWIDTH;

impl FramedModel for Se3Rod {
    const HALF_BANDWIDTH: usize = SE3_HALF_BANDWIDTH;

    fn core(&self) -> &FramedCore {
        &self.core
    }

    fn assemble_terms<M: SymmetricMatrix>(
        &self,
        state: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.assemble_into(state, load, asm);
    }

    fn chord_after_step(&self, state: &FramedState, dx: &[f64], alpha: f64, j: usize) -> Vec3 {
        super::element::chord_after_step(&self.core, state, dx, alpha, j)
    }
}
