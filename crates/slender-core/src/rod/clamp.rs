//! The rod's clamp: a fixed *ghost edge* inside the clamp and a hinge with *half* a Voronoi
//! cell at the clamped vertex (design.md §0, §2.5).
//!
//! A clamp holds its vertex and the material frame of the rod's end. That frame is carried by a
//! ghost edge: an edge beyond the end, along the clamp's tangent, with the clamp's reference
//! frame and a fixed material angle. The clamped vertex gets a hinge between the ghost edge and
//! the first real edge, with the Voronoi length of half the real edge: the usual full cell
//! makes the clamp too soft (first order, +43 % at N = 5) and clamping the whole first edge too
//! stiff (−36 %); the half cell is second-order accurate. When a clamp moves (support motion),
//! its ghost edge turns with it.

use nalgebra::Rotation3;

use crate::geometry::{parallel_transport, Vec3};

use super::frames::{EdgeFrame, EdgeId};
use super::model::Rod;
use super::state::RodState;

/// A clamp's ghost edge: fixed frame, fixed material angle, length of the adjacent real edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GhostEdge {
    /// Its reference frame (the clamp's orientation).
    pub frame: EdgeFrame,
    /// Its material angle (rad), fixed.
    pub theta: f64,
    /// Its length (m); only the direction enters the energy, the length sets the stencil.
    pub length: f64,
}

impl GhostEdge {
    /// The ghost edge of a clamp whose tangent is `tangent`, next to the real edge with frame
    /// `edge` and rest length `length`: its reference director is the edge's, transported to
    /// the clamp tangent; `theta` is the material angle the clamp holds.
    pub(super) fn new(tangent: Vec3, edge: EdgeFrame, length: f64, theta: f64) -> Self {
        Self {
            frame: EdgeFrame {
                tangent,
                a1: parallel_transport(&edge.a1, &edge.tangent, &tangent).normalize(),
            },
            theta,
            length,
        }
    }

    /// The ghost edge turned with its clamp by `r`.
    pub(super) fn turned(&self, r: &Rotation3<f64>) -> Self {
        Self {
            frame: EdgeFrame {
                tangent: r * self.frame.tangent,
                a1: r * self.frame.a1,
            },
            ..*self
        }
    }
}

/// A clamp hinge: its vertex, left and right edges, and Voronoi length (m).
pub(super) type ClampHinge = (usize, EdgeId, EdgeId, f64);

/// The clamp hinges of a rod of `rest_lengths` with clamps at the start and/or end:
/// (vertex, left edge, right edge, Voronoi length) with half the adjacent real edge.
pub(super) fn clamp_hinges(
    rest_lengths: &[f64],
    start: bool,
    end: bool,
) -> (Option<ClampHinge>, Option<ClampHinge>) {
    let n = rest_lengths.len();
    (
        start.then(|| {
            (
                0,
                EdgeId::GhostStart,
                EdgeId::Real(0),
                0.5 * rest_lengths[0],
            )
        }),
        end.then(|| {
            (
                n,
                EdgeId::Real(n - 1),
                EdgeId::GhostEnd,
                0.5 * rest_lengths[n - 1],
            )
        }),
    )
}

impl Rod {
    /// The outer point and material angle of a hinge's ghost edge at vertex `v` (`end` false:
    /// the start clamp, before the vertex; true: the end clamp, after it).
    pub(super) fn ghost_point(&self, s: &RodState, v: usize, end: bool) -> (Vec3, f64) {
        if end {
            let g = s.frames.ghost_end.expect("end clamp");
            (s.positions[v] + g.frame.tangent * g.length, g.theta)
        } else {
            let g = s.frames.ghost_start.expect("start clamp");
            (s.positions[v] - g.frame.tangent * g.length, g.theta)
        }
    }

    /// Turns the ghost edges of the clamps among `vertices` by `r` (a moving support).
    pub(super) fn turn_clamps(&self, s: &mut RodState, vertices: &[usize], r: &Rotation3<f64>) {
        let n = self.n_edges();
        if vertices.contains(&0) {
            if let Some(g) = s.frames.ghost_start.as_mut() {
                *g = g.turned(r);
            }
        }
        if vertices.contains(&n) {
            if let Some(g) = s.frames.ghost_end.as_mut() {
                *g = g.turned(r);
            }
        }
    }
}

/// The moment (N m) about the clamped vertex of a clamp hinge's generalized forces on its ghost
/// edge: the ghost's outer point `x_ghost` (force `f_ghost` = ∂E/∂x_ghost) turns about the
/// vertex `x_v`, and a rotation about the ghost's tangent turns its material angle (generalized
/// force `m_theta` = ∂E/∂θ_ghost).
pub(super) fn ghost_moment(
    x_ghost: &Vec3,
    x_v: &Vec3,
    f_ghost: &Vec3,
    tangent: &Vec3,
    m_theta: f64,
) -> Vec3 {
    (x_ghost - x_v).cross(f_ghost) + tangent * m_theta
}
