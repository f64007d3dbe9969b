//! A deformed rod described by what is invariant of its discretization choices: positions,
//! the material director m₁ of every edge, and the twist strain of every hinge. It carries an
//! equilibrium from one rod model to another with the same vertices — parts of a cable that a
//! removed interior clamp merges, or a vertex inserted for a new clip — without a jump in
//! energy (reference directors and angles are re-chosen so that every material frame and
//! every twist, including whole turns, stays what it was).

use crate::geometry::{rotate_about_axis, Vec3};

use super::clamp::GhostEdge;
use super::frames::{EdgeFrame, EdgeId};
use super::model::Rod;
use super::state::RodState;

/// A clamp's hold on a rod end: the material frame of its ghost edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClampHold {
    /// The ghost edge's tangent.
    pub tangent: Vec3,
    /// The ghost edge's material director m₁.
    pub m1: Vec3,
    /// Twist strain (rad) of the clamp hinge.
    pub twist: f64,
}

/// A deformed rod, independent of its reference frames.
#[derive(Clone, Debug, PartialEq)]
pub struct RodSnapshot {
    /// Vertex positions (m).
    pub positions: Vec<Vec3>,
    /// Material director m₁ of every edge.
    pub m1: Vec<Vec3>,
    /// Twist strain m = θᶠ − θᵉ + m_ref (rad) of the hinge at every vertex 1..n−1 (index
    /// v − 1); whole turns included.
    pub twists: Vec<f64>,
    /// The clamps' holds at the start and end, if clamped.
    pub clamps: [Option<ClampHold>; 2],
    /// Unwrapped twist angles (rad) of the moment loads about their two axes.
    pub load_angles: Vec<[f64; 2]>,
}

impl Rod {
    /// The snapshot of `s`.
    pub fn snapshot(&self, s: &RodState) -> RodSnapshot {
        let n = self.n_edges();
        let m1 = (0..n).map(|j| s.material_frame(j)[0]).collect();
        let mut twists = vec![0.0; n.saturating_sub(1)];
        let mut clamps = [None, None];
        for h in &self.hinges {
            let hs = self.hinge_state(s, h);
            match h.edges {
                (EdgeId::GhostStart, _) => {
                    let g = s.frames.ghost_start.expect("start clamp");
                    clamps[0] = Some(ClampHold {
                        tangent: g.frame.tangent,
                        m1: ghost_m1(&g),
                        twist: hs.twist(),
                    })
                }
                (_, EdgeId::GhostEnd) => {
                    let g = s.frames.ghost_end.expect("end clamp");
                    clamps[1] = Some(ClampHold {
                        tangent: g.frame.tangent,
                        m1: ghost_m1(&g),
                        twist: hs.twist(),
                    })
                }
                _ => twists[h.vertex - 1] = hs.twist(),
            }
        }
        RodSnapshot {
            positions: s.positions.clone(),
            m1,
            twists,
            clamps,
            load_angles: s.load_angles.clone(),
        }
    }

    /// A state of this rod with the snapshot's shape: every reference director is the edge's
    /// material director (so every θ is 0) and every reference twist is the snapshot's twist
    /// strain. Clamp holds missing from the snapshot are taken from the rod's rest state.
    /// The snapshot must have this rod's vertex count.
    pub fn state_from_snapshot(&self, snap: &RodSnapshot) -> RodState {
        let n = self.n_edges();
        assert_eq!(snap.positions.len(), n + 1, "snapshot of another mesh");
        let edges: Vec<EdgeFrame> = (0..n)
            .map(|j| {
                let t = (snap.positions[j + 1] - snap.positions[j]).normalize();
                let m = snap.m1[j];
                EdgeFrame {
                    tangent: t,
                    a1: (m - t * t.dot(&m)).normalize(),
                }
            })
            .collect();
        let ghost = |g: Option<GhostEdge>, hold: Option<ClampHold>| -> Option<GhostEdge> {
            let g = g?;
            Some(match hold {
                Some(h) => GhostEdge {
                    frame: EdgeFrame {
                        tangent: h.tangent,
                        a1: h.m1,
                    },
                    theta: 0.0,
                    length: g.length,
                },
                None => GhostEdge {
                    frame: EdgeFrame {
                        tangent: g.frame.tangent,
                        a1: ghost_m1(&g),
                    },
                    theta: 0.0,
                    length: g.length,
                },
            })
        };
        let rest = &self.rest;
        let mut state = RodState {
            positions: snap.positions.clone(),
            thetas: vec![0.0; n],
            frames: super::frames::ReferenceFrames {
                edges,
                ghost_start: ghost(rest.frames.ghost_start, snap.clamps[0]),
                ghost_end: ghost(rest.frames.ghost_end, snap.clamps[1]),
                ref_twist: vec![0.0; self.hinges.len()],
                lengths: super::frames::EdgeLength::of_polyline(&snap.positions),
            },
            load_angles: if snap.load_angles.len() == self.moments.len() {
                snap.load_angles.clone()
            } else {
                rest.load_angles.clone()
            },
            followers: Vec::new(),
        };
        for (k, h) in self.hinges.iter().enumerate() {
            // With θ = 0 on both sides the twist strain is the reference twist.
            state.frames.ref_twist[k] =
                match h.edges {
                    (EdgeId::GhostStart, _) => snap.clamps[0]
                        .map_or_else(|| self.fresh_twist(&state, h.edges), |c| c.twist),
                    (_, EdgeId::GhostEnd) => snap.clamps[1]
                        .map_or_else(|| self.fresh_twist(&state, h.edges), |c| c.twist),
                    _ => snap.twists[h.vertex - 1],
                };
        }
        state.followers = self.follower_loads(&state).collect();
        state
    }

    /// The reference twist between two edges of `s` measured afresh (|twist| < π).
    fn fresh_twist(&self, s: &RodState, (l, r): (EdgeId, EdgeId)) -> f64 {
        super::frames::updated_ref_twist(&s.frames.edge(l), &s.frames.edge(r), 0.0)
    }
}

/// The material director m₁ of a ghost edge.
fn ghost_m1(g: &GhostEdge) -> Vec3 {
    rotate_about_axis(&g.frame.a1, &g.frame.tangent, g.theta)
}

impl RodSnapshot {
    /// The snapshot of vertices `a..=b` (a part of the rod between interior clamps); the
    /// clamps of the part are taken from `holds` when given.
    pub fn slice(&self, a: usize, b: usize, holds: [Option<ClampHold>; 2]) -> RodSnapshot {
        RodSnapshot {
            positions: self.positions[a..=b].to_vec(),
            m1: self.m1[a..b].to_vec(),
            twists: if b > a + 1 {
                self.twists[a..b - 1].to_vec()
            } else {
                Vec::new()
            },
            clamps: holds,
            load_angles: Vec::new(),
        }
    }
}
