//! Support reactions and the resultant of the applied loads of a rod with material frames.
//!
//! As for the discrete elastic rod (`rod/reactions.rs`): the reaction at a support is the
//! gradient of the total energy with respect to the support's held DOFs — its vertex
//! position (force) and the frame its clamp holds (moment about the vertex, since a rotation
//! of the support about its vertex turns that frame and moves no position). By rigid-motion
//! invariance of the internal energy, at an equilibrium the reactions balance the applied
//! loads in force and moment.

use crate::geometry::Vec3;
use crate::rod::{LoadResultant, SupportReaction};

use super::core::FramedCore;
use super::layout::FramedDofs;
use super::state::FramedState;

impl FramedCore {
    /// Reactions, one per held vertex in increasing order, from the gradient `g` of the total
    /// energy over the full DOF vector followed by the clamp-frame slots
    /// ([`FramedDofs::clamp_frame_slots`]).
    pub(crate) fn reactions_from_gradient(&self, g: &[f64]) -> Vec<SupportReaction> {
        let n = self.n_edges();
        let vec_at = |slots: [usize; 3]| Vec3::new(g[slots[0]], g[slots[1]], g[slots[2]]);
        self.fixed_vertices
            .iter()
            .map(|&v| {
                let mut moment = Vec3::zeros();
                if self.fixed_frames.contains(&v) {
                    moment += vec_at(FramedDofs::full_frame_slots(v));
                }
                for (end, at) in [(0, 0), (1, n)] {
                    if v == at && self.rest.clamp_frames[end].is_some() {
                        moment += vec_at(self.dofs.clamp_frame_slots(end));
                    }
                }
                SupportReaction {
                    vertex: v,
                    force: vec_at(FramedDofs::full_vertex_slots(v)),
                    moment,
                }
            })
            .collect()
    }

    /// Resultant of the applied loads at load factor `load` in state `s`: dead nodal forces at
    /// their vertices (moment about the origin) and the moments the point-moment potentials
    /// exert in `s`.
    pub fn applied_loads(&self, s: &FramedState, load: f64) -> LoadResultant {
        let factor = self.load_path.load_factor(load);
        let mut force = Vec3::zeros();
        let mut moment = Vec3::zeros();
        for v in 0..self.nodal_forces.len() {
            let f = self.nodal_force(v, load);
            force += f;
            moment += s.positions[v].cross(&f);
        }
        let mut g = Vec3::zeros();
        let mut h = nalgebra::Matrix3::zeros();
        let n_moments = self.moments.len();
        for (i, (m, &angles)) in self.moments.iter().zip(&s.moment_angles).enumerate() {
            let w = self.load_path.moment_factor(i, n_moments, factor, load);
            m.potential(&s.frames[m.frame], angles, w, &mut g, &mut h);
            moment -= g;
        }
        LoadResultant { force, moment }
    }
}
