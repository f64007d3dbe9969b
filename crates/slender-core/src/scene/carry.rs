//! Carrying a framed rod's equilibrium (Cosserat rod, SE(3) beam) over to the recompiled
//! scene after a support was added or removed — the framed counterpart of
//! [`RodSnapshot`](crate::rod::RodSnapshot) for the discrete elastic rod.
//!
//! The whole rod's positions and frames are stitched from its parts, mapped to the new mesh
//! (a vertex inserted for a support given by arc length lies on an old element: its position
//! is interpolated, a Cosserat edge takes the frame of the old edge it lies on, an SE(3) node
//! the slerp of its old element's node frames) and cut into the new parts. Clamped frames keep
//! their current orientation, so a moved clamp stays where the user put it.

use nalgebra::UnitQuaternion;

use crate::geometry::Vec3;
use crate::structure::{Member, MemberState, StructureState};

use super::compile::CompiledScene;

/// Where a framed rod's frames sit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FrameSites {
    /// One frame per edge (Cosserat).
    Edges,
    /// One frame per node (SE(3)).
    Nodes,
}

/// A framed rod's shape over its whole length.
#[derive(Clone, Debug)]
pub(super) struct FramedSnapshot {
    /// Vertex positions (m) of the whole rod.
    pub(super) positions: Vec<Vec3>,
    frames: Vec<UnitQuaternion<f64>>,
    sites: FrameSites,
    /// The clamp frame held at each vertex (Cosserat clamps), if any.
    clamp_frames: Vec<Option<UnitQuaternion<f64>>>,
}

impl FramedSnapshot {
    /// The current shape of rod `r` of `scene` from the structures' states, or `None` if it is
    /// a discrete elastic rod.
    pub(super) fn of_rod(
        scene: &CompiledScene,
        states: &[&StructureState],
        r: usize,
    ) -> Option<Self> {
        let rod = &scene.rods[r];
        let n = rod.n_edges;
        let first = &rod.parts[0];
        let sites = match &scene.structures[first.structure].members()[first.member] {
            Member::Der(_) => return None,
            Member::Cosserat(_) => FrameSites::Edges,
            Member::Se3(_) => FrameSites::Nodes,
        };
        let n_frames = if sites == FrameSites::Edges { n } else { n + 1 };
        let mut out = Self {
            positions: vec![Vec3::zeros(); n + 1],
            frames: vec![UnitQuaternion::identity(); n_frames],
            sites,
            clamp_frames: vec![None; n + 1],
        };
        for part in &rod.parts {
            let MemberState::Framed(s) = &states[part.structure].members[part.member] else {
                unreachable!("a framed rod's parts are framed");
            };
            let a = part.first_vertex;
            out.positions[a..a + part.n_vertices].copy_from_slice(&s.positions);
            out.frames[a..a + s.frames.len()].copy_from_slice(&s.frames);
            if let Some(c) = s.clamp_frames[0] {
                out.clamp_frames[a] = Some(c);
            }
            if let Some(c) = s.clamp_frames[1] {
                out.clamp_frames[a + part.n_vertices - 1] = Some(c);
            }
        }
        Some(out)
    }

    /// The shape on a mesh with nodes `new` (rest arc lengths) from one on nodes `old`.
    pub(super) fn remesh(&self, old: &[f64], new: &[f64]) -> Self {
        if old == new {
            return self.clone();
        }
        let element_of = |s: f64| -> (usize, f64) {
            let j = old
                .partition_point(|&x| x <= s)
                .saturating_sub(1)
                .min(old.len() - 2);
            (j, (s - old[j]) / (old[j + 1] - old[j]))
        };
        let positions = new
            .iter()
            .map(|&s| {
                let (j, u) = element_of(s);
                self.positions[j] * (1.0 - u) + self.positions[j + 1] * u
            })
            .collect();
        let frames = match self.sites {
            FrameSites::Edges => new
                .windows(2)
                .map(|w| self.frames[element_of(0.5 * (w[0] + w[1])).0])
                .collect(),
            FrameSites::Nodes => new
                .iter()
                .map(|&s| {
                    let (j, u) = element_of(s);
                    self.frames[j].slerp(&self.frames[j + 1], u)
                })
                .collect(),
        };
        let clamp_frames = new
            .iter()
            .map(|s| {
                old.iter()
                    .position(|x| x == s)
                    .and_then(|v| self.clamp_frames[v])
            })
            .collect();
        Self {
            positions,
            frames,
            sites: self.sites,
            clamp_frames,
        }
    }

    /// The state of `member`, the part of the rod from vertex `a` to vertex `b`.
    pub(super) fn state_for(&self, member: &Member, a: usize, b: usize) -> MemberState {
        let core = member.as_framed().expect("a framed member");
        let frames = match self.sites {
            FrameSites::Edges => self.frames[a..b].to_vec(),
            FrameSites::Nodes => self.frames[a..=b].to_vec(),
        };
        let rest = core.rest_state();
        let clamp_frames = [
            rest.clamp_frames[0].map(|q| self.clamp_frames[a].unwrap_or(q)),
            rest.clamp_frames[1].map(|q| self.clamp_frames[b].unwrap_or(q)),
        ];
        MemberState::Framed(core.carried_state(
            self.positions[a..=b].to_vec(),
            frames,
            clamp_frames,
        ))
    }
}
