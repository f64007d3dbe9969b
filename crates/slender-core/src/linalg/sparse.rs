//! Sparse symmetric matrices with a fixed pattern, and their LDLᵀ factorization by faer with
//! one symbolic analysis (AMD ordering, elimination tree) reused for every numeric
//! factorization (design.md §4.1).
//!
//! Why sparse: a shell's Hessian couples each face with its three neighbours; ordered along a
//! strip it is banded, but its band grows with the elements across the width (and a general
//! mesh has no band at all), while a fill-reducing ordering keeps the factor nearly as sparse
//! as the matrix. The LDLᵀ without pivoting (simplicial or supernodal, as faer judges the
//! fill) keeps D explicit, so the inertia is read off its pivots exactly as for the banded
//! factorization.

use std::sync::Arc;

use crate::scratch::Scratch;
use faer::dyn_stack::MemStack;
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky,
    SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use std::mem::MaybeUninit;

use super::symmetric::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};

/// Pivots with |dᵢ| ≤ ε·(largest column count)·max|A + σI| count as numerically zero.
const ZERO_PIVOT_RTOL: f64 = f64::EPSILON;

/// The upper triangle of a symmetric pattern in compressed-column form (rows sorted).
#[derive(Debug, PartialEq, Eq)]
pub struct SparsityPattern {
    n: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Position of the diagonal entry of each column.
    diag: Vec<usize>,
    max_col_count: usize,
}

/// A symmetric n×n matrix storing the upper triangle of a fixed pattern (which always
/// includes the diagonal). Cloning shares the pattern.
#[derive(Clone, Debug, PartialEq)]
pub struct SparseSymmetricMatrix {
    pattern: Arc<SparsityPattern>,
    values: Vec<f64>,
}

/// Where the lower-triangle entries of each term's stencil block sit in the values of one
/// sparsity pattern, found once for a model's fixed terms so that every assembly scatters
/// without searching the columns (see [`SymmetricMatrix::add_lower_block_planned`]).
#[derive(Clone, Debug)]
pub struct ScatterPlan {
    pattern: Arc<SparsityPattern>,
    /// Per term, the value index of entry (a, b ≤ a) at a(a+1)/2 + b ([`NOWHERE`] for a
    /// fixed slot); empty for a term the plan does not cover (a repeated DOF, an entry
    /// outside the pattern), which takes the searching scatter.
    positions: Vec<Vec<u32>>,
}

/// A [`ScatterPlan`] entry of a fixed slot.
const NOWHERE: u32 = u32::MAX;

impl SparseSymmetricMatrix {
    /// The zero matrix whose pattern holds the diagonal and every pair (i, j) listed (either
    /// order; duplicates are merged). Indices must be < n.
    pub fn from_pattern(n: usize, entries: impl IntoIterator<Item = (usize, usize)>) -> Self {
        let mut columns: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        for (i, j) in entries {
            let (r, c) = if i <= j { (i, j) } else { (j, i) };
            assert!(c < n, "entry ({i}, {j}) outside a {n}×{n} pattern");
            columns[c].push(r);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut diag = Vec::with_capacity(n);
        let mut max_col_count = 0;
        col_ptr.push(0);
        for (j, rows) in columns.iter_mut().enumerate() {
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend_from_slice(rows);
            diag.push(row_idx.len() - 1);
            debug_assert_eq!(row_idx[row_idx.len() - 1], j);
            max_col_count = max_col_count.max(rows.len());
            col_ptr.push(row_idx.len());
        }
        let nnz = row_idx.len();
        Self {
            pattern: Arc::new(SparsityPattern {
                n,
                col_ptr,
                row_idx,
                diag,
                max_col_count,
            }),
            values: vec![0.0; nnz],
        }
    }

    /// The [`ScatterPlan`] of the terms with these stencils (in the order the assembler
    /// visits them) into this matrix's pattern.
    pub fn scatter_plan<'s, const D: usize>(
        &self,
        stencils: impl IntoIterator<Item = &'s [usize; D]>,
    ) -> ScatterPlan {
        let fixed = crate::assembly::FIXED;
        let positions = stencils
            .into_iter()
            .map(|dofs| {
                let mut free: Vec<usize> = dofs.iter().copied().filter(|&i| i != fixed).collect();
                free.sort_unstable();
                if free.windows(2).any(|w| w[0] == w[1]) || self.values.len() > NOWHERE as usize {
                    return Vec::new();
                }
                let mut out = Vec::with_capacity(D * (D + 1) / 2);
                for (a, &i) in dofs.iter().enumerate() {
                    for &j in &dofs[..=a] {
                        if i == fixed || j == fixed {
                            out.push(NOWHERE);
                            continue;
                        }
                        match self.position(i, j) {
                            Some(k) => out.push(k as u32),
                            None => return Vec::new(),
                        }
                    }
                }
                out
            })
            .collect();
        ScatterPlan {
            pattern: self.pattern.clone(),
            positions,
        }
    }

    /// The zero matrix of a plan's pattern (sharing it, so that the plan applies).
    pub fn zeros_of(plan: &ScatterPlan) -> Self {
        Self {
            values: vec![0.0; plan.pattern.row_idx.len()],
            pattern: plan.pattern.clone(),
        }
    }

    /// Stored entries (upper triangle including the diagonal).
    pub fn nnz(&self) -> usize {
        self.values.len()
    }

    /// Entry (i, j); 0 outside the pattern.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.position(i, j).map_or(0.0, |k| self.values[k])
    }

    fn position(&self, i: usize, j: usize) -> Option<usize> {
        let (r, c) = if i <= j { (i, j) } else { (j, i) };
        let p = &self.pattern;
        if c >= p.n {
            return None;
        }
        let (lo, hi) = (p.col_ptr[c], p.col_ptr[c + 1]);
        p.row_idx[lo..hi].binary_search(&r).ok().map(|k| lo + k)
    }

    fn symbolic(&self) -> SymbolicSparseColMatRef<'_, usize> {
        let p = &self.pattern;
        SymbolicSparseColMatRef::new_checked(p.n, p.n, &p.col_ptr, None, &p.row_idx)
    }

    /// Iterates over stored entries (i ≤ j, value) column by column.
    fn entries(&self) -> impl Iterator<Item = (usize, usize, f64)> + '_ {
        let p = &self.pattern;
        (0..p.n).flat_map(move |j| {
            (p.col_ptr[j]..p.col_ptr[j + 1]).map(move |k| (p.row_idx[k], j, self.values[k]))
        })
    }
}

impl SymmetricMatrix for SparseSymmetricMatrix {
    type Factor = SparseLdlt;

    fn dim(&self) -> usize {
        self.pattern.n
    }

    fn set_zero(&mut self) {
        self.values.fill(0.0);
    }

    fn add_same_pattern(&mut self, other: &Self) -> bool {
        if !std::sync::Arc::ptr_eq(&self.pattern, &other.pattern) {
            return false;
        }
        for (a, b) in self.values.iter_mut().zip(&other.values) {
            *a += b;
        }
        true
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        match self.position(i, j) {
            Some(k) => self.values[k] += v,
            None => {
                debug_assert!(false, "entry ({i}, {j}) outside the sparsity pattern");
                if let Some(d) = self.pattern.diag.get(i.min(j)) {
                    self.values[*d] = f64::NAN;
                }
            }
        }
    }

    /// The same additions as the entry-by-entry default, found by one merge walk down each
    /// column of the pattern instead of a binary search per entry (the searches were a tenth
    /// of a shell assembly). The walk steps once and searches only across gaps (a cubic
    /// B-spline column holds ~150 rows, of which an element touches 48), on slices of the
    /// column taken once (stores into the values cannot move the pattern). Each entry
    /// receives one addition when the DOFs are distinct, so the result has the same bits;
    /// repeated DOFs take the default path.
    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        let fixed = crate::assembly::FIXED;
        let mut order: [usize; D] = std::array::from_fn(|a| a);
        // FIXED (usize::MAX) sorts last.
        order.sort_unstable_by_key(|&a| dofs[a]);
        let free = order.iter().take_while(|&&a| dofs[a] != fixed).count();
        let distinct = order[..free].windows(2).all(|w| dofs[w[0]] < dofs[w[1]]);
        if !distinct || (free > 0 && dofs[order[free - 1]] >= self.pattern.n) {
            super::symmetric::lower_block_entries(dofs, value, |i, j, v| self.add(i, j, v));
            return;
        }
        let pattern = &*self.pattern;
        // Rows of entries outside the pattern (none unless the pattern is wrong).
        let mut outside = Vec::new();
        for (cj, &b) in order[..free].iter().enumerate() {
            let j = dofs[b];
            let (lo, hi) = (pattern.col_ptr[j], pattern.col_ptr[j + 1]);
            // Rows i ≤ j of this column, ascending, as the pattern stores them.
            let rows = &pattern.row_idx[lo..hi];
            let values = &mut self.values[lo..hi];
            let mut k = 0;
            for &a in &order[..=cj] {
                let i = dofs[a];
                // The element's rows come in runs of consecutive DOFs: the next stored row
                // is usually the one wanted; across a gap, search the rest of the column.
                if k < rows.len() && rows[k] < i {
                    k += 1;
                    if k < rows.len() && rows[k] < i {
                        k += rows[k..].partition_point(|&r| r < i);
                    }
                }
                // `value` takes the slots lower triangle first, as the default scatter does.
                let v = value(a.max(b), a.min(b));
                if k < rows.len() && rows[k] == i {
                    values[k] += v;
                } else {
                    outside.push(i);
                }
            }
            // As `add` does for an entry outside the pattern (NaN absorbs later additions).
            for i in outside.drain(..) {
                debug_assert!(false, "entry ({i}, {j}) outside the sparsity pattern");
                self.values[pattern.diag[i]] = f64::NAN;
            }
        }
    }

    /// One addition per entry at its planned position (the same additions as
    /// [`Self::add_lower_block`]) when the plan was made for this pattern and covers the term.
    fn add_lower_block_planned<const D: usize>(
        &mut self,
        plan: &ScatterPlan,
        term: usize,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        let positions = match plan.positions.get(term) {
            Some(p) if p.len() == D * (D + 1) / 2 && Arc::ptr_eq(&plan.pattern, &self.pattern) => p,
            _ => return self.add_lower_block(dofs, value),
        };
        let mut e = 0;
        for a in 0..D {
            for (b, &k) in positions[e..e + a + 1].iter().enumerate() {
                if k != NOWHERE {
                    self.values[k as usize] += value(a, b);
                }
            }
            e += a + 1;
        }
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.values[self.pattern.diag[i]]
    }

    fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        let p = &self.pattern;
        for j in 0..p.n {
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                let (i, v) = (p.row_idx[k], self.values[k]);
                y[i] += v * x[j];
                if i != j {
                    y[j] += v * x[i];
                }
            }
        }
    }

    fn gershgorin_bounds(&self) -> (f64, f64) {
        self.gershgorin_bounds_in(&mut Vec::new())
    }

    fn gershgorin_bounds_in(&self, radius: &mut Vec<f64>) -> (f64, f64) {
        let n = self.pattern.n;
        if n == 0 {
            return (0.0, 0.0);
        }
        radius.clear();
        radius.resize(n, 0.0);
        for (i, j, v) in self.entries() {
            if i != j {
                radius[i] += v.abs();
                radius[j] += v.abs();
            }
        }
        (0..n).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), i| {
            let d = self.diagonal(i);
            (l.min(d - radius[i]), u.max(d + radius[i]))
        })
    }

    fn first_non_finite(&self) -> Option<usize> {
        // Values are stored column by column: the first non-finite one and its column.
        let k = self.values.iter().position(|v| !v.is_finite())?;
        Some(self.pattern.col_ptr.partition_point(|&start| start <= k) - 1)
    }

    fn congruence_scaled(&self, s: &[f64], out: &mut Self) {
        if !Arc::ptr_eq(&self.pattern, &out.pattern) {
            *out = self.clone();
        }
        let p = &self.pattern;
        for j in 0..p.n {
            for k in p.col_ptr[j]..p.col_ptr[j + 1] {
                out.values[k] = self.values[k] * s[p.row_idx[k]] * s[j];
            }
        }
    }
}

/// LDLᵀ of A + σI for a [`SparseSymmetricMatrix`] A, by faer's simplicial or supernodal
/// factorization without pivoting (so that D gives the inertia), after a fill-reducing AMD ordering. The
/// symbolic analysis is done on the first factorization of a pattern and reused for every
/// later one with the same pattern (e.g. across Newton iterations).
#[derive(Clone, Debug, Default)]
pub struct SparseLdlt {
    pattern: Option<Arc<SparsityPattern>>,
    symbolic: Option<Arc<SymbolicCholesky<usize>>>,
    l_values: Vec<f64>,
    shifted: Vec<f64>,
    /// The pivots D of the last factorization, in the permuted order.
    pivots: Vec<f64>,
    /// faer's scratch memory for the numeric factorization, kept between calls.
    factor_scratch: Scratch<Vec<MaybeUninit<u8>>>,
    /// faer's scratch memory for solves, kept between calls (solves take `&self`).
    solve_scratch: Scratch<Vec<MaybeUninit<u8>>>,
    inertia: Inertia,
    factored: bool,
    symbolic_analyses: usize,
}

/// `buffer` grown to at least the bytes `req` needs at any alignment.
fn reserve_scratch(buffer: &mut Vec<MaybeUninit<u8>>, req: faer::dyn_stack::StackReq) {
    let bytes = req.unaligned_bytes_required();
    if buffer.len() < bytes {
        buffer.resize(bytes, MaybeUninit::uninit());
    }
}

impl SparseLdlt {
    /// An empty workspace.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many symbolic analyses this workspace has done (1 for a fixed pattern).
    pub fn symbolic_analyses(&self) -> usize {
        self.symbolic_analyses
    }

    /// Whether faer chose the supernodal variant for the analysed pattern (None before the
    /// first factorization).
    pub fn is_supernodal(&self) -> Option<bool> {
        self.symbolic
            .as_ref()
            .map(|s| matches!(s.raw(), SymbolicCholeskyRaw::Supernodal(_)))
    }

    /// Inertia of the last successful factorization.
    pub fn inertia(&self) -> Inertia {
        self.inertia
    }

    /// The pivots D of the factor in `l_values` into `d`.
    fn pivots_into(l_values: &[f64], symbolic: &SymbolicCholesky<usize>, d: &mut Vec<f64>) {
        d.clear();
        match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let col_ptr = s.col_ptr();
                d.extend((0..s.nrows()).map(|k| l_values[col_ptr[k]]));
            }
            // Each supernode stores its columns as one dense column-major block whose leading
            // square part is the diagonal block; D sits on that block's diagonal.
            SymbolicCholeskyRaw::Supernodal(s) => {
                for k in 0..s.n_supernodes() {
                    let ncols = s.supernode_end()[k] - s.supernode_begin()[k];
                    let nrows = ncols + s.supernode(k).pattern().len();
                    let start = s.col_ptr_for_val()[k];
                    d.extend((0..ncols).map(|j| l_values[start + j * nrows + j]));
                }
            }
        }
    }
}

impl SymmetricFactor<SparseSymmetricMatrix> for SparseLdlt {
    fn factorize(&mut self, a: &SparseSymmetricMatrix, shift: f64) -> Result<Inertia, FactorError> {
        self.factored = false;
        self.inertia = Inertia::default();
        let n = a.dim();
        if n > 0 && !shift.is_finite() {
            return Err(FactorError::NonFinite { index: 0 });
        }
        if let Some(index) = a.first_non_finite() {
            return Err(FactorError::NonFinite { index });
        }
        let same_pattern = self
            .pattern
            .as_ref()
            .is_some_and(|p| Arc::ptr_eq(p, &a.pattern));
        if !same_pattern || self.symbolic.is_none() {
            // faer picks simplicial for sparse factors and supernodal (dense blocks) once the
            // fill makes them pay, e.g. a square 30×30 plate; both keep D explicit.
            let params = CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::AUTO,
                ..Default::default()
            };
            let symbolic = factorize_symbolic_cholesky(
                a.symbolic(),
                Side::Upper,
                SymmetricOrdering::Amd,
                params,
            )
            .map_err(|e| FactorError::Analysis {
                reason: format!("{e:?}"),
            })?;
            self.l_values = vec![0.0; symbolic.len_val()];
            self.symbolic = Some(Arc::new(symbolic));
            self.pattern = Some(a.pattern.clone());
            self.symbolic_analyses += 1;
        }
        let symbolic = self.symbolic.clone().ok_or(FactorError::NotFactored)?;
        self.shifted.clone_from(&a.values);
        for &d in &a.pattern.diag {
            self.shifted[d] += shift;
        }
        let matrix = SparseColMatRef::new(a.symbolic(), &self.shifted);
        let req = symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default());
        reserve_scratch(self.factor_scratch.get_mut(), req);
        let result = symbolic.factorize_numeric_ldlt(
            &mut self.l_values,
            matrix,
            Side::Upper,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(self.factor_scratch.get_mut()),
            Default::default(),
        );
        if let Err(LdltError::ZeroPivot { index }) = result {
            // faer reports the (permuted) step one-based; the position is informative only.
            return Err(FactorError::ZeroPivot {
                index: index.saturating_sub(1),
            });
        }
        // Pivot k of the permuted factorization belongs to row fwd[k] of A; its rounding error
        // scales with that row's diagonal (see `Inertia::from_pivots`).
        let rtol = ZERO_PIVOT_RTOL * a.pattern.max_col_count as f64;
        let diag_of = |k: usize| -> f64 {
            let row = match symbolic.perm() {
                Some(p) => p.arrays().0[k],
                None => k,
            };
            self.shifted[a.pattern.diag[row]].abs()
        };
        let mut pivots = std::mem::take(&mut self.pivots);
        Self::pivots_into(&self.l_values, &symbolic, &mut pivots);
        let inertia = Inertia::from_pivots(
            pivots.iter().enumerate().map(|(k, &d)| (d, diag_of(k))),
            rtol,
        );
        self.pivots = pivots;
        let inertia = inertia.map_err(|index| FactorError::NonFinite { index })?;
        // The solves' scratch is sized here, with the factor, not by the first solve.
        reserve_scratch(
            self.solve_scratch.get_mut(),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        );
        self.inertia = inertia;
        self.factored = true;
        Ok(inertia)
    }

    fn try_solve_in_place(&self, b: &mut [f64]) -> Result<(), FactorError> {
        let symbolic = match (&self.symbolic, self.factored) {
            (Some(s), true) => s,
            _ => return Err(FactorError::NotFactored),
        };
        let n = symbolic.nrows();
        if b.len() != n {
            return Err(FactorError::DimensionMismatch {
                expected: n,
                found: b.len(),
            });
        }
        let ldlt = LdltRef::<usize, f64>::new(symbolic, &self.l_values);
        self.solve_scratch.with(|scratch| {
            reserve_scratch(scratch, symbolic.solve_in_place_scratch::<f64>(1, Par::Seq));
            let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
            ldlt.solve_in_place_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(scratch));
        });
        Ok(())
    }
}
