//! The state of a rod with material frames: vertex positions, frame orientations, the frames
//! its clamps hold, and the unwrapped angles of its moment loads.

use nalgebra::{Rotation3, UnitQuaternion};

use crate::geometry::Vec3;

/// Positions and frames of a discrete Cosserat rod or an SE(3) beam.
///
/// Frame j is a unit quaternion p_j, the rotation R_j = [d₁ d₂ d₃] whose columns are the
/// material directors (d₃ the section normal; d₁, d₂ the directions of `ei1`'s and `ei2`'s
/// bending). It sits on edge j of a Cosserat rod and on node j of an SE(3) beam.
#[derive(Debug, PartialEq)]
pub struct FramedState {
    pub(crate) positions: Vec<Vec3>,
    pub(crate) frames: Vec<UnitQuaternion<f64>>,
    /// Frames held by the clamps at s = 0 and s = L when they are not frame slots (the
    /// Cosserat rod's clamp frames); `None` otherwise.
    pub(crate) clamp_frames: [Option<UnitQuaternion<f64>>; 2],
    /// Unwrapped twist angles (rad) of each moment load about its two fixed axes.
    pub(crate) moment_angles: Vec<[f64; 2]>,
}

/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone): the
/// solvers copy states into their workspaces on every re-solve.
impl Clone for FramedState {
    fn clone(&self) -> Self {
        Self {
            positions: self.positions.clone(),
            frames: self.frames.clone(),
            clamp_frames: self.clamp_frames,
            moment_angles: self.moment_angles.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.positions.clone_from(&source.positions);
        self.frames.clone_from(&source.frames);
        self.clamp_frames = source.clamp_frames;
        self.moment_angles.clone_from(&source.moment_angles);
    }
}

impl FramedState {
    /// Vertex positions (m), from the start to the end of the rod.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Frame orientations (edges for a Cosserat rod, nodes for an SE(3) beam).
    pub fn frames(&self) -> &[UnitQuaternion<f64>] {
        &self.frames
    }

    /// Material directors (d₁, d₂, d₃) of frame `j`.
    pub fn material_frame(&self, j: usize) -> [Vec3; 3] {
        let r = self.frames[j].to_rotation_matrix();
        let m = r.matrix();
        [
            m.column(0).into_owned(),
            m.column(1).into_owned(),
            m.column(2).into_owned(),
        ]
    }

    /// The frame a clamp holds at end `end` (0: s = 0, 1: s = L), for models whose clamps hold
    /// frames outside the frame slots (Cosserat rods); `None` otherwise.
    pub fn clamp_frame(&self, end: usize) -> Option<UnitQuaternion<f64>> {
        self.clamp_frames[end]
    }

    /// This state moved rigidly: x ↦ R x + c for every vertex, every frame (and clamp frame)
    /// rotated by R. The internal energy does not change.
    pub fn rigidly_transformed(&self, rotation: &Rotation3<f64>, offset: &Vec3) -> Self {
        let q = UnitQuaternion::from_rotation_matrix(rotation);
        Self {
            positions: self
                .positions
                .iter()
                .map(|x| rotation * x + offset)
                .collect(),
            frames: self.frames.iter().map(|p| q * p).collect(),
            clamp_frames: self.clamp_frames.map(|c| c.map(|p| q * p)),
            moment_angles: self.moment_angles.clone(),
        }
    }
}
