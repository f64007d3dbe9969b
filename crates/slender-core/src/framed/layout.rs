//! Degrees of freedom of a rod with material frames, and which of them supports remove.
//!
//! Vertex positions x_v and frame rotations (spatial rotation-vector increments ω_j) are
//! interleaved, `[x₀, ω₀, x₁, ω₁, …]`: x_v occupies full indices 6v…6v+2 and ω_j 6j+3…6j+5.
//! A discrete Cosserat rod has one frame per edge (N frames, 6N + 3 entries), an SE(3) beam one
//! per node (N + 1 frames, 6N + 6 entries). Every term then touches a short run of consecutive
//! entries, and removing fixed rows and columns keeps the band.

use crate::assembly::FIXED;

/// Map from the full interleaved DOF vector to the free DOFs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FramedDofs {
    n_vertices: usize,
    n_frames: usize,
    free_of_full: Vec<usize>,
    full_of_free: Vec<usize>,
}

/// What one DOF moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DofSlot {
    /// Coordinate `k` of vertex `v` (m).
    Position {
        /// Vertex.
        v: usize,
        /// Coordinate 0, 1, 2.
        k: usize,
    },
    /// Component `k` of the spatial rotation increment of frame `j` (rad).
    Rotation {
        /// Frame slot.
        j: usize,
        /// Component 0, 1, 2.
        k: usize,
    },
}

impl FramedDofs {
    /// A map for `n_vertices` vertices and `n_frames` frames, with the positions of
    /// `fixed_vertices` and the rotations of `fixed_frames` held and, if `planar_axis` is
    /// `Some(k)`, coordinate k of every vertex and every rotation component but k held
    /// (motion in the plane ⊥ e_k, rotations about e_k only).
    pub fn new(
        n_vertices: usize,
        n_frames: usize,
        fixed_vertices: &[usize],
        fixed_frames: &[usize],
        planar_axis: Option<usize>,
    ) -> Self {
        let n_full = Self::full_length(n_vertices, n_frames);
        let mut fixed = vec![false; n_full];
        for &v in fixed_vertices {
            fixed[6 * v..6 * v + 3].fill(true);
        }
        for &j in fixed_frames {
            fixed[6 * j + 3..6 * j + 6].fill(true);
        }
        if let Some(axis) = planar_axis {
            for (i, f) in fixed.iter_mut().enumerate() {
                let k = i % 6;
                if (k < 3 && k == axis) || (k >= 3 && k - 3 != axis) {
                    *f = true;
                }
            }
        }
        let mut free_of_full = vec![FIXED; n_full];
        let mut full_of_free = Vec::with_capacity(n_full);
        for (i, &is_fixed) in fixed.iter().enumerate() {
            if !is_fixed {
                free_of_full[i] = full_of_free.len();
                full_of_free.push(i);
            }
        }
        Self {
            n_vertices,
            n_frames,
            free_of_full,
            full_of_free,
        }
    }

    fn full_length(n_vertices: usize, n_frames: usize) -> usize {
        (6 * n_vertices - 3).max(6 * n_frames)
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.full_of_free.len()
    }

    /// Length of the full vector (free and fixed).
    pub fn n_full(&self) -> usize {
        self.free_of_full.len()
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.n_vertices
    }

    /// Number of frames.
    pub fn n_frames(&self) -> usize {
        self.n_frames
    }

    /// Free index of coordinate `k` of vertex `v`, or [`FIXED`].
    pub fn vertex(&self, v: usize, k: usize) -> usize {
        self.free_of_full[6 * v + k]
    }

    /// Free index of rotation component `k` of frame `j`, or [`FIXED`].
    pub fn frame(&self, j: usize, k: usize) -> usize {
        self.free_of_full[6 * j + 3 + k]
    }

    /// Full index of free DOF `i`.
    pub fn full_index(&self, i: usize) -> usize {
        self.full_of_free[i]
    }

    /// What free DOF `i` moves.
    pub fn slot(&self, i: usize) -> DofSlot {
        let f = self.full_of_free[i];
        let (node, k) = (f / 6, f % 6);
        if k < 3 {
            DofSlot::Position { v: node, k }
        } else {
            DofSlot::Rotation { j: node, k: k - 3 }
        }
    }

    /// True if free DOF `i` is a rotation component (rad) rather than a coordinate (m).
    pub fn is_rotation(&self, i: usize) -> bool {
        self.full_of_free[i] % 6 >= 3
    }

    /// Free indices of the position of vertex `v`.
    pub fn vertex_slots(&self, v: usize) -> [usize; 3] {
        [self.vertex(v, 0), self.vertex(v, 1), self.vertex(v, 2)]
    }

    /// Free indices of the rotation of frame `j`.
    pub fn frame_slots(&self, j: usize) -> [usize; 3] {
        [self.frame(j, 0), self.frame(j, 1), self.frame(j, 2)]
    }

    /// Full indices of the position of vertex `v`.
    pub fn full_vertex_slots(v: usize) -> [usize; 3] {
        [6 * v, 6 * v + 1, 6 * v + 2]
    }

    /// Full indices of the rotation of frame `j`.
    pub fn full_frame_slots(j: usize) -> [usize; 3] {
        [6 * j + 3, 6 * j + 4, 6 * j + 5]
    }

    /// Indices, past the full vector, given to the rotation of the clamp frame at end `end`
    /// (0: s = 0, 1: s = L) of a model whose clamps hold frames outside the frame slots; used
    /// to compute the clamps' reaction moments.
    pub fn clamp_frame_slots(&self, end: usize) -> [usize; 3] {
        let b = self.n_full() + 3 * end;
        [b, b + 1, b + 2]
    }
}
