//! Support reactions and the resultant of the applied loads, for force and moment balance.
//!
//! The reaction at a support is the generalized force the support must supply to hold its
//! DOFs: the gradient of the total energy with respect to the support's rigid motion. A
//! support translates its fixed vertex (and a clamp's ghost edge with it), so its force is
//! ∂E/∂x_v summed over every term, fixed DOFs included. A clamp also rotates its ghost edge
//! about the vertex: its moment is Σ (x_ghost − x_v) × ∂E/∂x_ghost + t_ghost ∂E/∂θ_ghost
//! (a rotation about the tangent turns the ghost's material angle; one about a normal turns
//! its tangent, and parallel transport agrees with the rotation to first order).
//!
//! Because the discrete internal energy is invariant under rigid motions, at an equilibrium
//! Σ reactions + Σ applied loads = 0 in force and in moment; checking that balance tests the
//! solve and this bookkeeping without any reference to a closed form.

use nalgebra::{SMatrix, SVector};

use crate::geometry::Vec3;

use super::clamp;
use super::frames::EdgeId;
use super::hinge::{EdgeHessian, HingeFrame, HingeVector};
use super::model::Rod;
use super::moment::MOMENT_DOFS;
use super::state::RodState;
use super::stretching::stretching_energy;

/// What a support exerts on the rod at one fixed vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SupportReaction {
    /// The fixed vertex.
    pub vertex: usize,
    /// Force (N) the support applies to the rod.
    pub force: Vec3,
    /// Moment (N m) about the vertex the support applies to the rod (zero for a pin).
    pub moment: Vec3,
}

/// The generalized forces (∂E/∂DOF) of a rod's own terms on every vertex and edge angle, fixed
/// or not: the forces its supports must supply, before the joints of a structure are added.
#[derive(Clone, Debug, PartialEq)]
pub struct FullGradient {
    /// ∂E/∂x_v (N) of every vertex.
    pub vertices: Vec<Vec3>,
    /// ∂E/∂θ_j (N m) of every edge angle.
    pub thetas: Vec<f64>,
    /// Moments (N m) about the clamped vertex of the start and end clamps' ghost edges.
    pub ghost_moments: [Vec3; 2],
}

/// Resultant of the applied loads (gravity, point forces, point moments) in a state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoadResultant {
    /// Total applied force (N).
    pub force: Vec3,
    /// Total applied moment about the origin (N m).
    pub moment: Vec3,
}

impl Rod {
    /// ∂E/∂x_v (N) of the total energy at load factor `load` for every vertex, fixed or not,
    /// and the ghost-edge moments (N m) of the start and end clamps.
    fn full_position_gradient(&self, s: &RodState, load: f64) -> (Vec<Vec3>, [Vec3; 2]) {
        let g = self.full_gradient(s, load);
        (g.vertices, g.ghost_moments)
    }

    /// The generalized forces of the rod's own terms on every vertex and edge angle, fixed or
    /// not (see [`FullGradient`]).
    pub fn full_gradient(&self, s: &RodState, load: f64) -> FullGradient {
        let lambda = load;
        let load = self.load_path.load_factor(load);
        let n = self.n_edges();
        let mut g = vec![Vec3::zeros(); n + 1];
        let mut gt = vec![0.0; n];
        let mut ghost_moment = [Vec3::zeros(); 2];
        let ea = self.properties.stiffness.ea;
        let mut g6 = SVector::<f64, 6>::zeros();
        for (j, &rest_length) in self.rest_lengths.iter().enumerate() {
            g6.fill(0.0);
            stretching_energy(
                &s.positions[j],
                &s.positions[j + 1],
                rest_length,
                ea,
                Some(&mut g6),
                None,
            );
            g[j] += g6.fixed_rows::<3>(0);
            g[j + 1] += g6.fixed_rows::<3>(3);
        }
        let mut gh = HingeVector::zeros();
        for hinge in &self.hinges {
            let hs = self.hinge_state(s, hinge);
            let frame = HingeFrame::new(&hs);
            gh.fill(0.0);
            hinge
                .bending
                .energy(&frame, Some(&mut gh), None::<&mut EdgeHessian>);
            hinge
                .twisting
                .energy(&frame, hs.twist(), Some(&mut gh), None::<&mut EdgeHessian>);
            let slot = |a: usize| Vec3::new(gh[a], gh[a + 1], gh[a + 2]);
            let v = hinge.vertex;
            g[v] += slot(4);
            if let EdgeId::Real(j) = hinge.edges.0 {
                gt[j] += gh[3];
            }
            if let EdgeId::Real(j) = hinge.edges.1 {
                gt[j] += gh[7];
            }
            match hinge.edges.0 {
                EdgeId::Real(j) => g[j] += slot(0),
                _ => {
                    // The ghost vertex moves with the clamp.
                    g[v] += slot(0);
                    ghost_moment[0] += clamp::ghost_moment(
                        &hs.x[0],
                        &hs.x[1],
                        &slot(0),
                        &s.frames.edge(hinge.edges.0).tangent,
                        gh[3],
                    );
                }
            }
            match hinge.edges.1 {
                EdgeId::Real(j) => g[j + 1] += slot(8),
                _ => {
                    g[v] += slot(8);
                    ghost_moment[1] += clamp::ghost_moment(
                        &hs.x[2],
                        &hs.x[1],
                        &slot(8),
                        &s.frames.edge(hinge.edges.1).tangent,
                        gh[7],
                    );
                }
            }
        }
        for (v, (f, f0)) in self
            .nodal_forces
            .iter()
            .zip(&self.preload_forces)
            .enumerate()
        {
            g[v] -= f * load + f0 + self.load_transition(v, lambda);
        }
        let mut g7 = SVector::<f64, MOMENT_DOFS>::zeros();
        let mut h7 = SMatrix::<f64, MOMENT_DOFS, MOMENT_DOFS>::zeros();
        let n_moments = self.moments.len();
        for (i, (m, &angles)) in self.moments.iter().zip(&s.load_angles).enumerate() {
            let w = self.load_path.moment_factor(i, n_moments, load, lambda);
            let j = m.edge;
            let length = s.frames.lengths[j].length;
            m.potential(&s.material_frame(j), length, angles, w, &mut g7, &mut h7);
            g[j] += g7.fixed_rows::<3>(0);
            g[j + 1] += g7.fixed_rows::<3>(3);
            gt[j] += g7[6];
        }
        for (i, (f, now)) in self.followers.iter().zip(&s.followers).enumerate() {
            let j = f.edge;
            g[f.vertex] -= self.follower_force(i, now, load, lambda);
            let (c, tau) = self.follower_couple(i, now, load, lambda);
            g[j + 1] -= c;
            g[j] += c;
            gt[j] -= tau;
        }
        FullGradient {
            vertices: g,
            thetas: gt,
            ghost_moments: ghost_moment,
        }
    }

    /// Reactions of every support at load factor `load`, one per fixed vertex in increasing
    /// vertex order. Meaningful at an equilibrium (the free DOFs' residual is not included).
    pub fn reactions(&self, s: &RodState, load: f64) -> Vec<SupportReaction> {
        let (g, ghost) = self.full_position_gradient(s, load);
        let n = self.n_edges();
        self.fixed_vertices
            .iter()
            .map(|&v| {
                let mut moment = Vec3::zeros();
                if v == 0 && s.frames.ghost_start.is_some() {
                    moment += ghost[0];
                }
                if v == n && s.frames.ghost_end.is_some() {
                    moment += ghost[1];
                }
                SupportReaction {
                    vertex: v,
                    force: g[v],
                    moment,
                }
            })
            .collect()
    }

    /// Resultant of the applied loads at load factor `load` in state `s`: dead nodal forces
    /// (gravity, point forces) at their vertices, and point moments as they act in `s` (the
    /// couple on the edge's end vertices plus the torque about its tangent, −∂V/∂ψ of
    /// `moment.rs`).
    pub fn applied_loads(&self, s: &RodState, load: f64) -> LoadResultant {
        let lambda = load;
        let load = self.load_path.load_factor(load);
        let mut force = Vec3::zeros();
        let mut moment = Vec3::zeros();
        for (v, (f, f0)) in self
            .nodal_forces
            .iter()
            .zip(&self.preload_forces)
            .enumerate()
        {
            let f = f * load + f0 + self.load_transition(v, lambda);
            force += f;
            moment += s.positions[v].cross(&f);
        }
        for (i, (f, now)) in self.followers.iter().zip(&s.followers).enumerate() {
            let j = f.edge;
            let fv = self.follower_force(i, now, load, lambda);
            force += fv;
            moment += s.positions[f.vertex].cross(&fv);
            let e = s.positions[j + 1] - s.positions[j];
            let (c, tau) = self.follower_couple(i, now, load, lambda);
            moment += e.cross(&c);
            moment += s.frames.edges[j].tangent * tau;
        }
        let mut g7 = SVector::<f64, MOMENT_DOFS>::zeros();
        let mut h7 = SMatrix::<f64, MOMENT_DOFS, MOMENT_DOFS>::zeros();
        let n_moments = self.moments.len();
        for (i, (m, &angles)) in self.moments.iter().zip(&s.load_angles).enumerate() {
            let w = self.load_path.moment_factor(i, n_moments, load, lambda);
            let j = m.edge;
            let length = s.frames.lengths[j].length;
            // The couple of the forces −∂V/∂x on the edge's vertices plus the torque −∂V/∂θ
            // about its tangent: −∂V/∂ψ.
            let (_, dv) = m.potential(&s.material_frame(j), length, angles, w, &mut g7, &mut h7);
            moment -= dv;
        }
        LoadResultant { force, moment }
    }
}
