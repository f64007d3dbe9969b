//! What the Newton solver needs from a Hessian and its factorization, whatever the storage:
//! assemble entries, factor H + σI as LDLᵀ without pivoting (whose pivot signs are the
//! inertia, by Sylvester's law), and solve. Rods use the banded storage, shells the sparse one.

use thiserror::Error;

/// A symmetric matrix with a fixed storage pattern that can be assembled and factored.
pub trait SymmetricMatrix: Clone + std::fmt::Debug {
    /// Its LDLᵀ factorization workspace.
    type Factor: SymmetricFactor<Self> + Clone + std::fmt::Debug + Default;

    /// Dimension n.
    fn dim(&self) -> usize;

    /// Sets every stored entry to zero, keeping the pattern.
    fn set_zero(&mut self);

    /// Adds `v` to entry (i, j) and, by symmetry, to (j, i) (once on the diagonal). Entries
    /// outside the pattern are a programmer error (debug builds panic; release builds poison
    /// the matrix with NaN so that the next factorization fails).
    fn add(&mut self, i: usize, j: usize, v: f64);

    /// Adds a term's local Hessian block: for every pair of slots b ≤ a of `dofs` that are
    /// not [`FIXED`](crate::assembly::FIXED), `value(a, b)` to entry (dofs[a], dofs[b]) — twice
    /// when two different slots name the same DOF (the pair (a, b) and its mirror (b, a) both
    /// land on that diagonal). Storages override it to dispatch once per block instead of once
    /// per entry; the additions happen in the same order either way (same bits).
    #[inline]
    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        lower_block_entries(dofs, value, |i, j, v| self.add(i, j, v));
    }

    /// [`Self::add_lower_block`] for term `term` of a
    /// [`ScatterPlan`](crate::linalg::sparse::ScatterPlan); storages without plans (or given
    /// a plan of another pattern) scatter as usual.
    #[inline]
    fn add_lower_block_planned<const D: usize>(
        &mut self,
        plan: &crate::linalg::sparse::ScatterPlan,
        term: usize,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        let _ = (plan, term);
        self.add_lower_block(dofs, value);
    }

    /// Diagonal entry a_ii.
    fn diagonal(&self, i: usize) -> f64;

    /// The whole diagonal into `out` (length n).
    fn diagonal_into(&self, out: &mut [f64]) {
        for (i, d) in out.iter_mut().enumerate() {
            *d = self.diagonal(i);
        }
    }

    /// max |a_ii| (0 for the empty matrix).
    fn max_abs_diagonal(&self) -> f64 {
        (0..self.dim()).fold(0.0, |m, i| m.max(self.diagonal(i).abs()))
    }

    /// y = A x.
    fn mul_vec(&self, x: &[f64], y: &mut [f64]);

    /// Gershgorin bounds (lower, upper) on the eigenvalues; (0, 0) for the empty matrix.
    fn gershgorin_bounds(&self) -> (f64, f64);

    /// [`Self::gershgorin_bounds`] with the row radii summed in `radius` (resized, and reused
    /// between calls so that a repeated bound allocates nothing). Storages without such a
    /// variant allocate as `gershgorin_bounds` does.
    fn gershgorin_bounds_in(&self, radius: &mut Vec<f64>) -> (f64, f64) {
        let _ = radius;
        self.gershgorin_bounds()
    }

    /// Index of a row (or column) holding a NaN or infinite stored entry, if any.
    fn first_non_finite(&self) -> Option<usize>;

    /// `out` = S A S with S = diag(`s`) (same pattern; `out` is reshaped if needed).
    fn congruence_scaled(&self, s: &[f64], out: &mut Self);

    /// Adds `other`'s stored entries to this matrix's when both have the same storage
    /// pattern (e.g. one is a clone of the other) and returns true; returns false, changing
    /// nothing, when they do not or the storage cannot tell.
    fn add_same_pattern(&mut self, _other: &Self) -> bool {
        false
    }
}

/// An LDLᵀ factorization (no pivoting) of A + σI for a matrix type `M`.
pub trait SymmetricFactor<M> {
    /// Factors A + shift·I and returns its inertia. Errors: an exactly zero pivot
    /// ([`FactorError::ZeroPivot`]) or a non-finite value ([`FactorError::NonFinite`]).
    fn factorize(&mut self, a: &M, shift: f64) -> Result<Inertia, FactorError>;

    /// b ← (A + σI)⁻¹ b with the last successful factorization.
    fn try_solve_in_place(&self, b: &mut [f64]) -> Result<(), FactorError>;

    /// As [`try_solve_in_place`](Self::try_solve_in_place); a missing factorization or a
    /// length mismatch is a programmer error (debug builds panic, release builds return NaN).
    fn solve_in_place(&self, b: &mut [f64]) {
        if let Err(e) = self.try_solve_in_place(b) {
            debug_assert!(false, "solve_in_place: {e}");
            b.fill(f64::NAN);
        }
    }

    /// [`solve_in_place`](Self::solve_in_place) for each of `K` right-hand sides, with the
    /// same results. Factors whose solves are bound by the latency of one long dependency
    /// chain (the band's substitutions) override it to run the `K` chains side by side.
    fn solve_block_in_place<const K: usize>(&self, bs: [&mut [f64]; K]) {
        for b in bs {
            self.solve_in_place(b);
        }
    }
}

/// Counts of negative, (numerically) zero and positive eigenvalues of a symmetric matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
pub struct Inertia {
    /// Number of negative eigenvalues.
    pub negative: usize,
    /// Number of eigenvalues indistinguishable from zero at working precision.
    pub zero: usize,
    /// Number of positive eigenvalues.
    pub positive: usize,
}

impl Inertia {
    /// negative + zero + positive, the matrix dimension.
    pub fn total(&self) -> usize {
        self.negative + self.zero + self.positive
    }

    /// True if all eigenvalues are (numerically) positive.
    pub fn is_positive_definite(&self) -> bool {
        self.negative == 0 && self.zero == 0
    }

    /// The inertia read off LDLᵀ pivots, each with the scale of the terms it was computed
    /// from: d_k is counted zero when |d_k| ≤ `rtol`·scale_k, its rounding error. The scale of
    /// pivot k is |a_kk + σ| + Σ_j |l_kj|²|d_j| (the k-th diagonal entry of |L||D||Lᵀ|, the
    /// backward-error bound of LDLᵀ); a per-row test keeps small but certain pivots of graded
    /// matrices (a soft lateral mode among stiff stretching rows) from being lost in a tolerance
    /// set by the largest entry. Err(k): pivot k is not finite. One counting for every storage.
    pub fn from_pivots(
        pivots: impl IntoIterator<Item = (f64, f64)>,
        rtol: f64,
    ) -> Result<Inertia, usize> {
        let mut inertia = Inertia::default();
        for (k, (d, scale)) in pivots.into_iter().enumerate() {
            if !d.is_finite() {
                return Err(k);
            }
            if d.abs() <= rtol * scale {
                inertia.zero += 1;
            } else if d < 0.0 {
                inertia.negative += 1;
            } else {
                inertia.positive += 1;
            }
        }
        Ok(inertia)
    }
}

/// Why a factorization or solve failed.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FactorError {
    /// Pivot `index` is exactly zero: the matrix is singular or needs pivoting.
    #[error("zero pivot at index {index}: matrix is singular or needs pivoting")]
    ZeroPivot {
        /// Row of the zero pivot.
        index: usize,
    },
    /// A NaN or infinity appeared in row `index` (in the input, the shift, or by overflow).
    #[error("non-finite value in row {index} of the factorization")]
    NonFinite {
        /// Row where the non-finite value was detected.
        index: usize,
    },
    /// A vector's length does not match the factored matrix.
    #[error("dimension mismatch: expected length {expected}, found {found}")]
    DimensionMismatch {
        /// The factored dimension n.
        expected: usize,
        /// The length supplied.
        found: usize,
    },
    /// No successful factorization is available to solve with.
    #[error("no valid factorization: factorize() has not succeeded")]
    NotFactored,
    /// The operation needs a matrix of dimension at least 1.
    #[error("the matrix is empty")]
    EmptyMatrix,
    /// The symbolic analysis (ordering, elimination tree) of a sparse matrix failed.
    #[error("symbolic analysis of the sparse matrix failed: {reason}")]
    Analysis {
        /// What the sparse library reported.
        reason: String,
    },
}

/// Visits the lower triangle of a stencil block (slot pairs b ≤ a, [`FIXED`] slots skipped)
/// in the order every storage adds it: `add(i, j, v)` for DOFs i, j, with the value doubled
/// where two different slots name the same DOF (the pair and its mirror both land there).
///
/// [`FIXED`]: crate::assembly::FIXED
#[inline]
pub(crate) fn lower_block_entries<const D: usize>(
    dofs: &[usize; D],
    value: impl Fn(usize, usize) -> f64,
    mut add: impl FnMut(usize, usize, f64),
) {
    for (a, &i) in dofs.iter().enumerate() {
        if i == crate::assembly::FIXED {
            continue;
        }
        for (b, &j) in dofs.iter().enumerate().take(a + 1) {
            if j == crate::assembly::FIXED {
                continue;
            }
            let v = value(a, b);
            add(i, j, if i == j && a != b { 2.0 * v } else { v });
        }
    }
}
