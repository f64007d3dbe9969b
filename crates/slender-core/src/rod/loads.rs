//! The external loads of a rod as terms of the [`EXTERNAL`](super::groups::EXTERNAL) group:
//! dead nodal forces (gravity lumped on the vertices, point forces, a preload) and point
//! moments (conservative, see `moment.rs`).

use nalgebra::{SMatrix, SVector};

use crate::assembly::Assembler;
use crate::linalg::SymmetricMatrix;

use super::model::Rod;
use super::moment::MOMENT_DOFS;
use super::state::RodState;

impl Rod {
    /// Adds the external loads at load factor `load`.
    pub(super) fn assemble_loads<M: SymmetricMatrix>(
        &self,
        s: &RodState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let lambda = load;
        let load = self.load_path.load_factor(load);
        // Dead loads: V = −λ Σ f_v·x_v, measured from the rest positions so that the energy
        // scale is the work done, not an arbitrary datum.
        for (v, (f, f0)) in self
            .nodal_forces
            .iter()
            .zip(&self.preload_forces)
            .enumerate()
        {
            let f = f * load + f0 + self.load_transition(v, lambda);
            let du = s.positions[v] - self.rest.positions[v];
            asm.load(f.dot(&du), f.amax());
            for k in 0..3 {
                asm.generalized_force(self.dofs.vertex(v, k), f[k]);
            }
        }
        // Follower loads, frozen in the state (see `follower.rs`): dead forces on the vertex,
        // a couple on the edge's vertices and a torque on its angle.
        for (i, (f, now)) in self.followers.iter().zip(&s.followers).enumerate() {
            let (v, j) = (f.vertex, f.edge);
            let du = s.positions[v] - self.rest.positions[v];
            let de = (s.positions[j + 1] - s.positions[j])
                - (self.rest.positions[j + 1] - self.rest.positions[j]);
            let dtheta = s.thetas[j] - self.rest.thetas[j];
            let fv = self.follower_force(i, now, load, lambda);
            let (c, tau) = self.follower_couple(i, now, load, lambda);
            asm.load(
                fv.dot(&du) + c.dot(&de) + tau * dtheta,
                fv.amax().max(c.amax()).max(tau.abs() / self.length),
            );
            for k in 0..3 {
                asm.generalized_force(self.dofs.vertex(v, k), fv[k]);
                asm.generalized_force(self.dofs.vertex(j + 1, k), c[k]);
                asm.generalized_force(self.dofs.vertex(j, k), -c[k]);
            }
            asm.generalized_force(self.dofs.theta(j), tau);
        }
        let mut g7 = SVector::<f64, MOMENT_DOFS>::zeros();
        let mut h7 = SMatrix::<f64, MOMENT_DOFS, MOMENT_DOFS>::zeros();
        let n_moments = self.moments.len();
        for (i, (m, &angles)) in self.moments.iter().zip(&s.load_angles).enumerate() {
            // The moment's own factor: λ and 1 − λ on the new and old values of an edit.
            let w = self.load_path.moment_factor(i, n_moments, load, lambda);
            let j = m.edge;
            let length = s.frames.lengths[j].length;
            let (v, _) = m.potential(&s.material_frame(j), length, angles, w, &mut g7, &mut h7);
            let [mb, mt] = m.magnitudes();
            asm.load(-v, w * (mb + mt.abs()) / self.length);
            asm.local(&self.moment_dofs(j), 0.0, 0.0, &g7, &h7);
        }
    }
}
