//! The Cosserat rod on the shared framed-rod problem ([`crate::framed::equilibrium`]): its
//! terms and how a step carries an edge's chord.

use crate::assembly::Assembler;
use crate::framed::{FramedCore, FramedModel, FramedState};
use crate::geometry::Vec3;
use crate::linalg::SymmetricMatrix;

use super::model::CosseratRod;
use super::COSSERAT_HALF_BANDWIDTH;

impl FramedModel for CosseratRod {
    const HALF_BANDWIDTH: usize = COSSERAT_HALF_BANDWIDTH;

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
        // Each chord is carried by its edge's frame: e ← exp(αω)(e + α(δe − ω×e)), so that the
        // edge strain Rᵀe/h changes exactly by α times its linearization.
        let core = &self.core;
        let x = &state.positions;
        let e = x[j + 1] - x[j];
        let de = core.vertex_step(dx, j + 1, alpha) - core.vertex_step(dx, j, alpha);
        let w = core.frame_step(dx, j, alpha);
        nalgebra::UnitQuaternion::from_scaled_axis(w) * (e + de - w.cross(&e))
    }
}
