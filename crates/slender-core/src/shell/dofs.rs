//! Numbering of the shell's degrees of freedom.
//!
//! Full DOFs: x, y, z of every vertex (3v + c), then one angle per edge (3·n_v + e). Free DOFs
//! leave out the clamped vertices and clamp edges, and are ordered by their station along the
//! length so that the Hessian of a strip is banded (every stencil spans four stations).

/// Maps between full and free DOF indices.
#[derive(Clone, Debug, PartialEq)]
pub struct ShellDofs {
    n_vertices: usize,
    /// Free index of each full DOF, or `None` if fixed by the clamp.
    free_of_full: Vec<Option<usize>>,
    /// Full index of each free DOF.
    full_of_free: Vec<usize>,
}

impl ShellDofs {
    /// Numbering for `n_vertices` vertices and `n_edges` edges; `fixed[k]` says whether full
    /// DOF k is fixed; `key[k]` orders the free DOFs (stable sort).
    pub fn new(n_vertices: usize, fixed: &[bool], key: &[usize]) -> Self {
        let mut full_of_free: Vec<usize> = (0..fixed.len()).filter(|&k| !fixed[k]).collect();
        full_of_free.sort_by_key(|&k| key[k]);
        let mut free_of_full = vec![None; fixed.len()];
        for (i, &k) in full_of_free.iter().enumerate() {
            free_of_full[k] = Some(i);
        }
        Self {
            n_vertices,
            free_of_full,
            full_of_free,
        }
    }

    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.full_of_free.len()
    }

    /// Free index of coordinate `c` of vertex `v`.
    pub fn vertex(&self, v: usize, c: usize) -> Option<usize> {
        self.free_of_full[3 * v + c]
    }

    /// Free index of the angle of edge `e`.
    pub fn edge(&self, e: usize) -> Option<usize> {
        self.free_of_full[3 * self.n_vertices + e]
    }

    /// Full index of free DOF `i`.
    pub fn full(&self, i: usize) -> usize {
        self.full_of_free[i]
    }

    /// True if free DOF `i` is an edge angle.
    pub fn is_angle(&self, i: usize) -> bool {
        self.full_of_free[i] >= 3 * self.n_vertices
    }

    /// Vertex and coordinate of a full position DOF, or the edge of a full angle DOF.
    pub fn split(&self, full: usize) -> DofKind {
        if full < 3 * self.n_vertices {
            DofKind::Position(full / 3, full % 3)
        } else {
            DofKind::Angle(full - 3 * self.n_vertices)
        }
    }
}

/// What a full DOF is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DofKind {
    /// Vertex, coordinate.
    Position(usize, usize),
    /// Edge.
    Angle(usize),
}
