//! Strain measures of a rod state for output: curvature and twist at the hinges, axial strain
//! of the edges.

use super::bending::material_curvature;
use super::hinge::HingeFrame;
use super::model::Rod;
use super::state::RodState;

/// Bending and twist at one hinge (a vertex with an edge, or a clamp's ghost edge, on each
/// side), as rates per unit rest length of its Voronoi cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HingeStrain {
    /// The hinge's vertex.
    pub vertex: usize,
    /// Material curvatures (κ₁, κ₂) = (κb·m₂, −κb·m₁) per unit length (1/m): κ₁ bends the
    /// centerline along m₁ and is resisted by EI₁, κ₂ along m₂ by EI₂ (see `bending.rs`).
    pub curvature: [f64; 2],
    /// Twist rate of the material frame (rad/m).
    pub twist: f64,
    /// Rest values of `curvature` (1/m).
    pub rest_curvature: [f64; 2],
    /// Rest value of `twist` (rad/m).
    pub rest_twist: f64,
}

impl Rod {
    /// Curvature and twist at every hinge of `s`, in hinge order (increasing vertex).
    pub fn hinge_strains(&self, s: &RodState) -> Vec<HingeStrain> {
        self.hinges
            .iter()
            .map(|hinge| {
                let hs = self.hinge_state(s, hinge);
                let kappa = material_curvature(&HingeFrame::new(&hs));
                let l = hinge.bending.voronoi_length;
                HingeStrain {
                    vertex: hinge.vertex,
                    curvature: [kappa[0] / l, kappa[1] / l],
                    twist: hs.twist() / l,
                    rest_curvature: [
                        hinge.bending.rest_kappa[0] / l,
                        hinge.bending.rest_kappa[1] / l,
                    ],
                    rest_twist: hinge.twisting.rest_twist / l,
                }
            })
            .collect()
    }

    /// Axial strain |e_j|/l̄_j − 1 of every edge.
    pub fn edge_strains(&self, s: &RodState) -> Vec<f64> {
        self.rest_lengths
            .iter()
            .enumerate()
            .map(|(j, &l)| (s.positions[j + 1] - s.positions[j]).norm() / l - 1.0)
            .collect()
    }
}
