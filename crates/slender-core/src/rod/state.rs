//! The state of a rod: positions, edge angles and the reference frames adapted to them.

use crate::geometry::Vec3;

use super::frames::{EdgeFrame, GhostEdge, ReferenceFrames};

/// Positions, edge angles and adapted reference frames of a rod.
#[derive(Debug, PartialEq)]
pub struct RodState {
    pub(super) positions: Vec<Vec3>,
    pub(super) thetas: Vec<f64>,
    pub(super) frames: ReferenceFrames,
    /// Unwrapped twist angles (rad) of each moment load's edge frame about its two fixed axes
    /// (see `moment.rs`).
    pub(super) load_angles: Vec<[f64; 2]>,
    /// Current dead-load stand-ins of the follower loads (see `follower.rs`).
    pub(super) followers: Vec<super::follower::FollowerState>,
}

/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone): the
/// solvers copy states into their workspaces on every re-solve.
impl Clone for RodState {
    fn clone(&self) -> Self {
        Self {
            positions: self.positions.clone(),
            thetas: self.thetas.clone(),
            frames: self.frames.clone(),
            load_angles: self.load_angles.clone(),
            followers: self.followers.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.positions.clone_from(&source.positions);
        self.thetas.clone_from(&source.thetas);
        self.frames.clone_from(&source.frames);
        self.load_angles.clone_from(&source.load_angles);
        self.followers.clone_from(&source.followers);
    }
}

impl RodState {
    /// Vertex positions (m), from the start to the end of the rod.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Edge material angles θ (rad) relative to the reference frames.
    pub fn thetas(&self) -> &[f64] {
        &self.thetas
    }

    /// Reference frames adapted to [`Self::positions`].
    pub fn frames(&self) -> &ReferenceFrames {
        &self.frames
    }

    /// This state moved rigidly: x ↦ R x + c for every vertex, frames (and clamp frames)
    /// rotated by R. Angles and reference twists are unchanged, so internal energy is too.
    pub fn rigidly_transformed(&self, rotation: &nalgebra::Rotation3<f64>, offset: &Vec3) -> Self {
        let rot = |f: &EdgeFrame| EdgeFrame {
            tangent: rotation * f.tangent,
            a1: rotation * f.a1,
        };
        let ghost = |g: &Option<GhostEdge>| {
            g.map(|g| GhostEdge {
                frame: rot(&g.frame),
                ..g
            })
        };
        Self {
            positions: self
                .positions
                .iter()
                .map(|x| rotation * x + offset)
                .collect(),
            thetas: self.thetas.clone(),
            frames: ReferenceFrames {
                edges: self.frames.edges.iter().map(rot).collect(),
                ghost_start: ghost(&self.frames.ghost_start),
                ghost_end: ghost(&self.frames.ghost_end),
                ref_twist: self.frames.ref_twist.clone(),
                lengths: self.frames.lengths.clone(),
            },
            load_angles: self.load_angles.clone(),
            followers: self
                .followers
                .iter()
                .map(|f| super::follower::FollowerState {
                    force: rotation * f.force,
                    couple: rotation * f.couple,
                    torque: f.torque,
                    transition: rotation * f.transition,
                    transition_couple: rotation * f.transition_couple,
                    transition_torque: f.transition_torque,
                })
                .collect(),
        }
    }

    /// Moves vertex `v` by `d` (m) without adapting the frames (see [`Rod::refresh_frames`]
    /// (super::Rod::refresh_frames)).
    pub(crate) fn translate_vertex(&mut self, v: usize, d: Vec3) {
        self.positions[v] += d;
    }

    /// Turns the material frame of edge `j` about its tangent by `angle` (rad).
    pub(crate) fn turn_edge(&mut self, j: usize, angle: f64) {
        self.thetas[j] += angle;
    }

    /// Material frame (m₁, m₂, t) of edge `j`.
    pub fn material_frame(&self, j: usize) -> [Vec3; 3] {
        let f = self.frames.edges[j];
        let a2 = f.tangent.cross(&f.a1);
        let (s, c) = crate::geometry::sin_cos(self.thetas[j]);
        [f.a1 * c + a2 * s, a2 * c - f.a1 * s, f.tangent]
    }
}
