//! Degrees of freedom of a rod and which of them supports remove.
//!
//! The full vector interleaves positions and edge angles, `[x₀, θ⁰, x₁, θ¹, …, x_N]`
//! (4N + 3 entries), so that every hinge touches 11 consecutive entries and the Hessian is
//! banded with half-bandwidth 10. Fixed entries are removed; removing rows and columns keeps
//! the band, so the free system is banded too.

/// Marks a stencil entry that is not a free DOF (fixed by a support, or a ghost edge's).
pub const FIXED: usize = usize::MAX;

/// Half-bandwidth of a rod Hessian in the interleaved ordering.
pub const ROD_HALF_BANDWIDTH: usize = 10;

/// Map from the full interleaved DOF vector to the free DOFs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DofMap {
    free_of_full: Vec<usize>,
    full_of_free: Vec<usize>,
}

impl DofMap {
    /// A map for `n_edges` edges with the vertices in `fixed_vertices` held in place and, if
    /// `planar_axis` is `Some(k)`, coordinate k of every vertex and every edge angle fixed
    /// (motion restricted to the plane ⊥ e_k).
    pub fn new(n_edges: usize, fixed_vertices: &[usize], planar_axis: Option<usize>) -> Self {
        let n_full = 4 * n_edges + 3;
        let mut fixed = vec![false; n_full];
        for &v in fixed_vertices {
            for k in 0..3 {
                fixed[4 * v + k] = true;
            }
        }
        if let Some(k) = planar_axis {
            for (i, f) in fixed.iter_mut().enumerate() {
                if i % 4 == 3 || i % 4 == k {
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
            free_of_full,
            full_of_free,
        }
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.full_of_free.len()
    }

    /// Free index of coordinate `k` of vertex `v`, or [`FIXED`].
    pub fn vertex(&self, v: usize, k: usize) -> usize {
        self.free_of_full[4 * v + k]
    }

    /// Free index of the angle of edge `j`, or [`FIXED`].
    pub fn theta(&self, j: usize) -> usize {
        self.free_of_full[4 * j + 3]
    }

    /// Full index of free DOF `i`.
    pub fn full_index(&self, i: usize) -> usize {
        self.full_of_free[i]
    }

    /// True if free DOF `i` is an edge angle (rad) rather than a coordinate (m).
    pub fn is_angle(&self, i: usize) -> bool {
        self.full_of_free[i] % 4 == 3
    }
}
