//! What a member reports at an equilibrium, whatever its formulation: material frames per
//! edge, curvature and twist at the vertices, axial strain per edge, the resultant of its
//! applied loads, and the generalized forces its supports supply.
//!
//! Conventions are the discrete elastic rod's (`rod/strains.rs`): (κ₁, κ₂) bend the
//! centerline along m₁ (resisted by EI₁) and m₂ (EI₂). A framed rod's Darboux vector K has
//! components about d₁, d₂, d₃; bending along m₁ is a rotation about m₂, so
//! (κ₁, κ₂, τ) = (K₂, −K₁, K₃).

use nalgebra::Vector3;

use crate::geometry::Vec3;
use crate::rod::{FullGradient, LoadResultant, SupportReaction};

use super::member::{Member, MemberState};

/// Curvature and twist at one vertex of a member.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VertexStrain {
    /// The member's vertex.
    pub vertex: usize,
    /// Material curvatures (κ₁, κ₂) (1/m).
    pub curvature: [f64; 2],
    /// Twist rate (rad/m).
    pub twist: f64,
    /// Rest value of `curvature` (1/m).
    pub rest_curvature: [f64; 2],
}

/// The generalized forces a member's supports supply, by formulation.
#[derive(Clone, Debug, PartialEq)]
pub enum HeldForces {
    /// ∂E/∂DOF of a discrete elastic rod on every vertex and edge angle (joints added by the
    /// structure).
    Der(FullGradient),
    /// The reaction (force, moment about the vertex) at every held vertex of a framed rod.
    Framed(Vec<SupportReaction>),
}

/// (κ₁, κ₂, τ) from a Darboux vector `k` about (d₁, d₂, d₃), and its rest value `k0`.
fn kirchhoff_strain(vertex: usize, k: Vector3<f64>, k0: Vector3<f64>) -> VertexStrain {
    VertexStrain {
        vertex,
        curvature: [k[1], -k[0]],
        twist: k[2],
        rest_curvature: [k0[1], -k0[0]],
    }
}

impl Member {
    /// Material frame (m₁, m₂, t) of every edge: the edge's own frame for the discrete elastic
    /// and Cosserat rods, the frame halfway along the element (slerp of its nodes') for the
    /// SE(3) beam.
    pub fn edge_frames(&self, state: &MemberState) -> Vec<[Vec3; 3]> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => {
                (0..r.n_edges()).map(|j| s.material_frame(j)).collect()
            }
            (Self::Cosserat(r), MemberState::Framed(s)) => {
                (0..r.n_edges()).map(|j| s.material_frame(j)).collect()
            }
            (Self::Se3(r), MemberState::Framed(s)) => (0..r.n_edges())
                .map(|j| {
                    let q = s.frames()[j].slerp(&s.frames()[j + 1], 0.5);
                    let m = q.to_rotation_matrix().into_inner();
                    [
                        m.column(0).into_owned(),
                        m.column(1).into_owned(),
                        m.column(2).into_owned(),
                    ]
                })
                .collect(),
            _ => unreachable!("member and state of different models"),
        }
    }

    /// Curvature and twist at the vertices where the formulation defines them: the hinges of
    /// a discrete elastic rod (not at free ends), the frame pairs of a Cosserat rod, and, for
    /// an SE(3) beam, every vertex as the mean of its elements' constant strains.
    pub fn vertex_strains(&self, state: &MemberState) -> Vec<VertexStrain> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r
                .hinge_strains(s)
                .into_iter()
                .map(|h| VertexStrain {
                    vertex: h.vertex,
                    curvature: h.curvature,
                    twist: h.twist,
                    rest_curvature: h.rest_curvature,
                })
                .collect(),
            (Self::Cosserat(r), MemberState::Framed(s)) => r
                .darboux_strains(s)
                .into_iter()
                .map(|d| kirchhoff_strain(d.vertex, d.darboux, d.rest))
                .collect(),
            (Self::Se3(r), MemberState::Framed(s)) => {
                let e = r.element_strains(s);
                let rest = |x: &crate::se3::ElementStrain| x.rest.fixed_rows::<3>(3).into_owned();
                (0..=e.len())
                    .map(|v| {
                        let (k, k0) = match (v.checked_sub(1).map(|j| &e[j]), e.get(v)) {
                            (Some(a), Some(b)) => {
                                ((a.darboux() + b.darboux()) * 0.5, (rest(a) + rest(b)) * 0.5)
                            }
                            (Some(a), None) => (a.darboux(), rest(a)),
                            (None, Some(b)) => (b.darboux(), rest(b)),
                            (None, None) => (Vector3::zeros(), Vector3::zeros()),
                        };
                        kirchhoff_strain(v, k, k0)
                    })
                    .collect()
            }
            _ => unreachable!("member and state of different models"),
        }
    }

    /// Axial strain of every edge: |e|/ℓ − 1 for the discrete elastic rod; the change of the
    /// axial component of the translation rate (Γ₃ − Γ₃⁰) for the framed rods.
    pub fn edge_strains(&self, state: &MemberState) -> Vec<f64> {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.edge_strains(s),
            (Self::Cosserat(r), MemberState::Framed(s)) => r
                .edge_strains(s)
                .into_iter()
                .map(|e| e.strain[2] - e.rest[2])
                .collect(),
            (Self::Se3(r), MemberState::Framed(s)) => r
                .element_strains(s)
                .into_iter()
                .map(|e| e.strain[2] - e.rest[2])
                .collect(),
            _ => unreachable!("member and state of different models"),
        }
    }

    /// Resultant of the applied loads at load factor `load` (force, and moment about the
    /// origin).
    pub fn applied_loads(&self, state: &MemberState, load: f64) -> LoadResultant {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => r.applied_loads(s, load),
            (Self::Cosserat(r), MemberState::Framed(s)) => r.core.applied_loads(s, load),
            (Self::Se3(r), MemberState::Framed(s)) => r.core.applied_loads(s, load),
            _ => unreachable!("member and state of different models"),
        }
    }

    /// The generalized forces the member's supports supply at load factor `load`.
    pub fn held_forces(&self, state: &MemberState, load: f64) -> HeldForces {
        match (self, state) {
            (Self::Der(r), MemberState::Der(s)) => HeldForces::Der(r.full_gradient(s, load)),
            (Self::Cosserat(r), MemberState::Framed(s)) => HeldForces::Framed(r.reactions(s, load)),
            (Self::Se3(r), MemberState::Framed(s)) => HeldForces::Framed(r.reactions(s, load)),
            _ => unreachable!("member and state of different models"),
        }
    }
}
