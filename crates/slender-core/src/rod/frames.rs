//! Time-parallel reference frames and the reference twist.
//!
//! Each edge carries a reference director a₁ ⊥ its tangent. When the rod moves, a₁ is
//! parallel-transported from the old tangent to the new one (Bergou et al. 2010); the twist
//! of the material frame relative to it is the edge angle θ. The angle between consecutive
//! reference frames, the reference twist, is updated *incrementally* so that it stays
//! continuous over many turns (no 2π jumps in coiled rods).
//!
//! Semantics (Panetta's ElasticRods makes the same point): the energy's gradient and Hessian
//! are exact only when the frames have just been transported to the current positions. A
//! [`ReferenceFrames`] value is therefore only ever created *adapted* to a set of positions,
//! and trial states of a line search get frames transported from the accepted state.

use crate::geometry::{parallel_transport, signed_angle, unit, Vec3};

pub use super::clamp::GhostEdge;

/// The reference frame of one edge: unit tangent and first reference director a₁ ⊥ tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeFrame {
    /// Unit tangent.
    pub tangent: Vec3,
    /// First reference director (unit, ⊥ tangent); a₂ = tangent × a₁.
    pub a1: Vec3,
}

impl EdgeFrame {
    /// The frame parallel-transported to the unit tangent `tangent`.
    pub fn transported_to(&self, tangent: &Vec3) -> Self {
        let a1 = parallel_transport(&self.a1, &self.tangent, tangent);
        // Re-orthonormalize: transport is exact in exact arithmetic only.
        let a1 = unit(&(a1 - tangent * tangent.dot(&a1)));
        Self {
            tangent: *tangent,
            a1,
        }
    }
}

/// The two edges a hinge joins: a real edge of the rod or a clamp's ghost edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeId {
    /// Edge j of the rod, from vertex j to j+1.
    Real(usize),
    /// The ghost edge inside the clamp at the start (before vertex 0).
    GhostStart,
    /// The ghost edge inside the clamp at the end (after the last vertex).
    GhostEnd,
}

/// Reference frames of all edges plus the reference twist of every hinge, adapted to one set
/// of positions.
#[derive(Debug, PartialEq)]
pub struct ReferenceFrames {
    /// One frame per real edge.
    pub(crate) edges: Vec<EdgeFrame>,
    /// Ghost edges of the start and end clamps, if any.
    pub(crate) ghost_start: Option<GhostEdge>,
    /// See `ghost_start`.
    pub(crate) ghost_end: Option<GhostEdge>,
    /// Reference twist (rad) of each hinge, in the rod's hinge order.
    pub(crate) ref_twist: Vec<f64>,
    /// Length |e| (m) and its reciprocal (1/m) of each real edge at the positions the frames
    /// are adapted to (the tangent is e·(1/|e|)): the energy terms of an edge and of the two
    /// hinges beside it read them instead of measuring the edge three times.
    pub(crate) lengths: Vec<EdgeLength>,
}

/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone).
impl Clone for ReferenceFrames {
    fn clone(&self) -> Self {
        Self {
            edges: self.edges.clone(),
            ghost_start: self.ghost_start,
            ghost_end: self.ghost_end,
            ref_twist: self.ref_twist.clone(),
            lengths: self.lengths.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.edges.clone_from(&source.edges);
        self.ghost_start = source.ghost_start;
        self.ghost_end = source.ghost_end;
        self.ref_twist.clone_from(&source.ref_twist);
        self.lengths.clone_from(&source.lengths);
    }
}

/// The length of an edge vector e and its reciprocal, as [`EdgeLength::of`] measures them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeLength {
    /// |e| (m).
    pub length: f64,
    /// 1/|e| (1/m).
    pub inv_length: f64,
}

impl EdgeLength {
    /// The length of `e` and the unit tangent e·(1/|e|).
    #[inline]
    pub fn of(e: &Vec3) -> (Self, Vec3) {
        let length = e.norm();
        let inv_length = 1.0 / length;
        (Self { length, inv_length }, e * inv_length)
    }

    /// The lengths of the edges of a polyline.
    pub(crate) fn of_polyline(positions: &[Vec3]) -> Vec<Self> {
        positions
            .windows(2)
            .map(|p| Self::of(&(p[1] - p[0])).0)
            .collect()
    }
}

impl ReferenceFrames {
    /// Frame of an edge.
    pub fn edge(&self, id: EdgeId) -> EdgeFrame {
        match id {
            EdgeId::Real(j) => self.edges[j],
            EdgeId::GhostStart => {
                self.ghost_start
                    .expect("hinge refers to a start clamp")
                    .frame
            }
            EdgeId::GhostEnd => self.ghost_end.expect("hinge refers to an end clamp").frame,
        }
    }

    /// Reference twist (rad) of hinge `k`.
    pub fn ref_twist(&self, k: usize) -> f64 {
        self.ref_twist[k]
    }

    /// Transports every real edge frame to the tangents of `positions` and updates the
    /// reference twists incrementally, writing into `out` (buffers reused).
    pub(crate) fn transport_into(
        &self,
        positions: &[Vec3],
        hinges: &[(EdgeId, EdgeId)],
        out: &mut ReferenceFrames,
    ) {
        out.edges.clear();
        out.lengths.clear();
        for (j, f) in self.edges.iter().enumerate() {
            let (length, t) = EdgeLength::of(&(positions[j + 1] - positions[j]));
            out.edges.push(f.transported_to(&t));
            out.lengths.push(length);
        }
        out.ghost_start = self.ghost_start;
        out.ghost_end = self.ghost_end;
        out.ref_twist.clear();
        for (k, &(l, r)) in hinges.iter().enumerate() {
            let twist = updated_ref_twist(&out.edge(l), &out.edge(r), self.ref_twist[k]);
            out.ref_twist.push(twist);
        }
    }
}

impl ReferenceFrames {
    /// As [`transport_into`](Self::transport_into), in place: each edge frame is transported
    /// to its new tangent and each reference twist continued from its previous value (both
    /// only need the new frames and the old twist).
    pub(crate) fn transport_in_place(&mut self, positions: &[Vec3], hinges: &[(EdgeId, EdgeId)]) {
        for (j, f) in self.edges.iter_mut().enumerate() {
            let (length, t) = EdgeLength::of(&(positions[j + 1] - positions[j]));
            *f = f.transported_to(&t);
            self.lengths[j] = length;
        }
        for (k, &(l, r)) in hinges.iter().enumerate() {
            self.ref_twist[k] = updated_ref_twist(&self.edge(l), &self.edge(r), self.ref_twist[k]);
        }
    }
}

/// Reference twist between frames `left` and `right`, continued from `previous`: the transport
/// of left's a₁ onto right's tangent, rotated by the previous twist, is compared with right's
/// a₁; the small signed difference is added. This never wraps as long as each update turns
/// the frames by less than π, which the solver's step cap guarantees.
pub(crate) fn updated_ref_twist(left: &EdgeFrame, right: &EdgeFrame, previous: f64) -> f64 {
    let u = parallel_transport(&left.a1, &left.tangent, &right.tangent);
    // The angle in (−π, π] plus the whole turns that bring it within π of `previous`: the
    // same as rotating u by `previous` and adding the small remainder, without the sine and
    // cosine of `previous`.
    let angle = signed_angle(&u, &right.a1, &right.tangent);
    let gap = previous - angle;
    if gap.abs() < std::f64::consts::PI {
        // No whole turn (what the rounding below gives, without its libm call).
        return angle;
    }
    let turns = (gap / std::f64::consts::TAU).round();
    angle + turns * std::f64::consts::TAU
}
