//! The external loads of a rod with material frames as terms of the `EXTERNAL` group: dead
//! nodal forces (gravity lumped on the vertices, point forces, a preload) and point moments
//! (conservative, see `moment.rs`).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::Assembler;
use crate::linalg::SymmetricMatrix;

use super::core::FramedCore;
use super::layout::FramedDofs;
use super::state::FramedState;

impl FramedCore {
    /// Adds the external loads at load factor `load`, on the free DOFs or (with `full`) on the
    /// full DOF vector (for reactions).
    pub(crate) fn assemble_loads<M: SymmetricMatrix>(
        &self,
        s: &FramedState,
        load: f64,
        asm: &mut Assembler<'_, M>,
        full: bool,
    ) {
        let factor = self.load_path.load_factor(load);
        // V = −Σ f_v·(x_v − x̄_v): measured from rest so that the energy scale is the work.
        for v in 0..self.nodal_forces.len() {
            let f = self.nodal_force(v, load);
            let du = s.positions[v] - self.rest.positions[v];
            asm.load(f.dot(&du), f.amax());
            let slots = if full {
                FramedDofs::full_vertex_slots(v)
            } else {
                self.dofs.vertex_slots(v)
            };
            for (k, &i) in slots.iter().enumerate() {
                asm.generalized_force(i, f[k]);
            }
        }
        let mut g = Vector3::zeros();
        let mut h = Matrix3::zeros();
        let n_moments = self.moments.len();
        for (i, (m, &angles)) in self.moments.iter().zip(&s.moment_angles).enumerate() {
            // The moment's own factor: λ and 1 − λ on the new and old values of an edit.
            let w = self.load_path.moment_factor(i, n_moments, factor, load);
            let j = m.frame;
            let v = m.potential(&s.frames[j], angles, w, &mut g, &mut h);
            let size = w * (m.magnitudes[0].abs() + m.magnitudes[1].abs()) / self.length;
            asm.load(-v, size);
            let slots = if full {
                FramedDofs::full_frame_slots(j)
            } else {
                self.dofs.frame_slots(j)
            };
            let g3: SVector<f64, 3> = g;
            let h3: SMatrix<f64, 3, 3> = h;
            asm.local(&slots, 0.0, 0.0, &g3, &h3);
        }
    }
}
