//! Symmetric banded matrices, their LDLᵀ factorization without pivoting, and the smallest
//! eigenpair by spectrum slicing.
//!
//! Why this is hand-written: the Newton solver for discrete elastic rods factors a symmetric
//! banded Hessian (half-bandwidth 10, n up to ~10⁵) and must also know its *inertia*, i.e. how
//! many eigenvalues are negative. An LDLᵀ factorization **without pivoting** gives that for free:
//! by Sylvester's law of inertia, A + σI and D have the same number of negative, zero and
//! positive eigenvalues, and D is diagonal. faer 0.24 has no banded factorization, and its sparse
//! LDLᵀ (symbolic analysis, supernodes, optional pivoting) is overkill for a plain band. The
//! kernel here costs O(n·bw²) flops, O(n·bw) memory, and never allocates once its buffers exist.
//!
//! Numerical caveat: LDLᵀ without pivoting is backward stable when A + σI is positive definite
//! (it is then Cholesky in disguise). For indefinite matrices it can suffer element growth or
//! break down on a zero pivot; breakdown is reported as [`FactorError::ZeroPivot`], never a panic.

use super::symmetric::{SymmetricFactor, SymmetricMatrix};

// Re-exported so that `linalg::banded::{…}` paths keep working.
pub use super::eigen::{smallest_eigenpair, EigenEstimate};
pub use super::symmetric::{FactorError, Inertia};

/// Pivots with |dᵢ| ≤ `ZERO_PIVOT_RTOL · (bw + 1) · sᵢ` are counted as numerically zero in the
/// inertia, sᵢ being the scale of the terms dᵢ was computed from (see
/// [`Inertia::from_pivots`]): their sign is below the rounding error of the factorization.
const ZERO_PIVOT_RTOL: f64 = f64::EPSILON;

/// A symmetric n×n matrix with half-bandwidth `bw`: entry (i, j) may be nonzero only if
/// |i − j| ≤ bw. Only the lower band is stored.
#[derive(Clone, Debug, PartialEq)]
pub struct SymmetricBandMatrix {
    n: usize,
    bw: usize,
    /// Row-major lower band: row `i` occupies `data[i·(bw+1)..(i+1)·(bw+1)]` and entry (i, j),
    /// i − bw ≤ j ≤ i, sits at offset `j + bw − i`, so the diagonal is last. The slots that
    /// would hold j < 0 (first `bw` rows) are padding and stay zero. Equal offsets in
    /// consecutive rows make the factorization's inner loops contiguous slices.
    data: Vec<f64>,
}

impl SymmetricBandMatrix {
    /// The n×n zero matrix with the given half-bandwidth.
    pub fn new(n: usize, half_bandwidth: usize) -> Self {
        // saturating_mul: an absurd size fails in the allocator with a clear message rather
        // than wrapping around to a small buffer.
        let len = n.saturating_mul(half_bandwidth.saturating_add(1));
        Self {
            n,
            bw: half_bandwidth,
            data: vec![0.0; len],
        }
    }

    /// Dimension n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Half-bandwidth bw (entries with |i − j| > bw are structurally zero).
    pub fn half_bandwidth(&self) -> usize {
        self.bw
    }

    /// Sets every entry to zero, keeping the storage.
    pub fn set_zero(&mut self) {
        self.data.fill(0.0);
    }

    /// Storage index of (i, j) for j ≤ i ≤ j + bw.
    #[inline]
    fn index(&self, i: usize, j: usize) -> usize {
        i * (self.bw + 1) + (j + self.bw - i)
    }

    /// Row `i` of the stored lower band (length bw + 1, diagonal last).
    #[inline]
    fn row(&self, i: usize) -> &[f64] {
        let w = self.bw + 1;
        &self.data[i * w..(i + 1) * w]
    }

    /// Adds `v` to entry (i, j) and, by symmetry, to (j, i); with i = j the diagonal entry is
    /// incremented once.
    ///
    /// Entries outside the matrix or the band are a programmer error: debug builds panic; release
    /// builds poison the diagonal with NaN so that the next factorization fails with
    /// [`FactorError::NonFinite`] instead of silently dropping the contribution.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let (r, c) = if i >= j { (i, j) } else { (j, i) };
        debug_assert!(
            r < self.n,
            "entry ({i}, {j}) outside a {0}×{0} matrix",
            self.n
        );
        debug_assert!(
            r - c <= self.bw,
            "entry ({i}, {j}) outside half-bandwidth {}",
            self.bw
        );
        if r < self.n && r - c <= self.bw {
            let k = self.index(r, c);
            self.data[k] += v;
        } else if self.n > 0 {
            let p = c.min(self.n - 1);
            let k = self.index(p, p);
            self.data[k] = f64::NAN;
        }
    }

    /// Entry (i, j); zero outside the band. Indices outside the matrix are a programmer error
    /// (debug builds panic, release builds return NaN).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (r, c) = if i >= j { (i, j) } else { (j, i) };
        debug_assert!(
            r < self.n,
            "entry ({i}, {j}) outside a {0}×{0} matrix",
            self.n
        );
        if r >= self.n {
            f64::NAN
        } else if r - c > self.bw {
            0.0
        } else {
            self.data[self.index(r, c)]
        }
    }

    /// y = A x.
    ///
    /// `x` and `y` must both have length n; otherwise (a programmer error) debug builds panic
    /// and release builds fill `y` with NaN.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let n = self.n;
        debug_assert!(
            x.len() == n && y.len() == n,
            "mul_vec: lengths must equal n = {n}"
        );
        if x.len() != n || y.len() != n {
            y.fill(f64::NAN);
            return;
        }
        match self.bw {
            6 => self.mul_vec_rows::<6>(x, y),
            10 => self.mul_vec_rows::<10>(x, y),
            11 => self.mul_vec_rows::<11>(x, y),
            12 => self.mul_vec_rows::<12>(x, y),
            _ => self.mul_vec_rows::<0>(x, y),
        }
    }

    /// [`Self::mul_vec`] with the rows i ≥ `BW` of a band of width `BW` (0: any width) in
    /// fixed-size loops, like the solves; the same operations in the same order (same bits).
    fn mul_vec_rows<const BW: usize>(&self, x: &[f64], y: &mut [f64]) {
        let (n, bw) = (self.n, self.bw);
        debug_assert!(BW == 0 || BW == bw);
        let head = if BW == 0 { n } else { BW.min(n) };
        for i in 0..head {
            let row = self.row(i);
            let lo = i.saturating_sub(bw);
            let off = lo + bw - i;
            let xi = x[i];
            let mut acc = row[bw] * xi;
            // Each stored a_ij (j < i) acts twice: on row i and, transposed, on row j. y[j] for
            // j < i is already initialized; y[i] is first written here.
            for ((yj, &xj), &a) in y[lo..i].iter_mut().zip(&x[lo..i]).zip(&row[off..bw]) {
                acc += a * xj;
                *yj += a * xi;
            }
            y[i] = acc;
        }
        for i in head..n {
            let row = self.row(i);
            let a: &[f64; BW] = row[..BW].try_into().expect("width BW");
            let xj: &[f64; BW] = x[i - BW..i].try_into().expect("width BW");
            let (above, below) = y.split_at_mut(i);
            let yj: &mut [f64; BW] = (&mut above[i - BW..]).try_into().expect("width BW");
            let xi = x[i];
            let mut acc = row[BW] * xi;
            for k in 0..BW {
                acc += a[k] * xj[k];
                yj[k] += a[k] * xi;
            }
            below[0] = acc;
        }
    }

    /// max |a_ii| (0 for the empty matrix).
    pub fn max_abs_diagonal(&self) -> f64 {
        (0..self.n).fold(0.0, |m, i| m.max(self.row(i)[self.bw].abs()))
    }

    /// Largest |a_ij| in the band (0 for the empty matrix).
    pub fn max_abs_entry(&self) -> f64 {
        (0..self.n).fold(0.0, |m, i| {
            let off = i.saturating_sub(self.bw) + self.bw - i;
            self.row(i)[off..].iter().fold(m, |m, a| m.max(a.abs()))
        })
    }

    /// Gershgorin bounds (lower, upper): every eigenvalue λ satisfies lower ≤ λ ≤ upper.
    /// Returns (0, 0) for the empty matrix. Allocates an n-vector of row radii.
    pub fn gershgorin_bounds(&self) -> (f64, f64) {
        self.gershgorin_bounds_in(&mut Vec::new())
    }

    /// [`Self::gershgorin_bounds`] with the row radii in `radius` (resized, reused).
    pub fn gershgorin_bounds_in(&self, radius: &mut Vec<f64>) -> (f64, f64) {
        if self.n == 0 {
            return (0.0, 0.0);
        }
        let bw = self.bw;
        radius.clear();
        radius.resize(self.n, 0.0);
        for i in 0..self.n {
            let row = self.row(i);
            let lo = i.saturating_sub(bw);
            let off = lo + bw - i;
            for (k, a) in row[off..bw].iter().enumerate() {
                radius[i] += a.abs();
                radius[lo + k] += a.abs();
            }
        }
        radius
            .iter()
            .enumerate()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, u), (i, r)| {
                let d = self.row(i)[bw];
                (l.min(d - r), u.max(d + r))
            })
    }

    /// Gershgorin lower bound min_i (a_ii − Σ_{j≠i} |a_ij|) ≤ λ_min (0 for the empty matrix).
    pub fn gershgorin_lower_bound(&self) -> f64 {
        self.gershgorin_bounds().0
    }

    /// Dense copy as a vector of rows (for tests and debugging).
    pub fn to_dense(&self) -> Vec<Vec<f64>> {
        (0..self.n)
            .map(|i| (0..self.n).map(|j| self.get(i, j)).collect())
            .collect()
    }

    /// First row holding a NaN or infinite stored entry.
    fn first_non_finite_row(&self) -> Option<usize> {
        (0..self.n).find(|&i| self.row(i).iter().any(|a| !a.is_finite()))
    }
}

/// Reusable LDLᵀ factorization of A + σI for a [`SymmetricBandMatrix`] A: L is unit lower
/// triangular with the same half-bandwidth as A, D is diagonal, and no pivoting is done so that
/// the signs of D are the inertia of A + σI.
///
/// The buffers grow on the first [`factorize`](Self::factorize) and are reused afterwards:
/// refactoring a matrix of the same (or smaller) size does not allocate.
#[derive(Clone, Debug, Default)]
pub struct BandLdlt {
    n: usize,
    bw: usize,
    shift: f64,
    /// Strictly lower part of L, row-major with `bw` slots per row at the same offsets as
    /// [`SymmetricBandMatrix`] (entry (i, j) at `i·bw + j + bw − i`).
    l: Vec<f64>,
    /// The pivots D.
    d: Vec<f64>,
    /// The scale of the terms each pivot was computed from (its rounding error's scale).
    pivot_scale: Vec<f64>,
    inertia: Inertia,
    factored: bool,
}

impl BandLdlt {
    /// An empty workspace; buffers are allocated by the first factorization.
    pub fn new() -> Self {
        Self::default()
    }

    /// Factors A + shift·I = L D Lᵀ (unit lower-banded L, diagonal D) without pivoting and
    /// returns the inertia of A + shift·I read off D (Sylvester's law of inertia).
    ///
    /// Pivots within their rounding error of zero ((bw + 1)·ε times the scale of the terms they
    /// were computed from) are counted in [`Inertia::zero`]: they are nonzero, so the
    /// factorization completes and can be solved with, but their sign is not trustworthy. An exactly zero pivot stops the factorization with
    /// [`FactorError::ZeroPivot`]; a NaN or infinity (in A, in `shift`, or from overflow) with
    /// [`FactorError::NonFinite`]. After an error the previous factorization is discarded.
    pub fn factorize(
        &mut self,
        a: &SymmetricBandMatrix,
        shift: f64,
    ) -> Result<Inertia, FactorError> {
        self.factored = false;
        self.inertia = Inertia::default();
        let (n, bw) = (a.n, a.bw);
        self.n = n;
        self.bw = bw;
        self.shift = shift;
        // resize() only allocates when growing past the capacity reached so far.
        self.l.resize(n * bw, 0.0);
        self.d.resize(n, 0.0);
        if n > 0 && !shift.is_finite() {
            return Err(FactorError::NonFinite { index: 0 });
        }

        let rtol = ZERO_PIVOT_RTOL * (bw as f64 + 1.0);
        self.pivot_scale.resize(n, 0.0);
        let mut rows = BandRows {
            l: &mut self.l[..n * bw],
            d: &mut self.d[..n],
            pivot_scale: &mut self.pivot_scale[..n],
        };
        // The rod models' widths get a kernel whose interior rows have a compile-time width.
        match bw {
            6 => rows.factor::<6>(a, shift)?,
            10 => rows.factor::<10>(a, shift)?,
            11 => rows.factor::<11>(a, shift)?,
            12 => rows.factor::<12>(a, shift)?,
            _ => rows.factor::<0>(a, shift)?,
        }
        let inertia = Inertia::from_pivots(
            self.d.iter().copied().zip(self.pivot_scale.iter().copied()),
            rtol,
        )
        .map_err(|index| FactorError::NonFinite { index })?;
        self.inertia = inertia;
        self.factored = true;
        Ok(inertia)
    }

    /// Inertia of the last successful factorization (all zero counts if there is none).
    pub fn inertia(&self) -> Inertia {
        self.inertia
    }

    /// True if the last call to [`factorize`](Self::factorize) succeeded.
    pub fn is_factored(&self) -> bool {
        self.factored
    }

    /// Dimension of the last factorization.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The shift σ of the last factorization (of A + σI).
    pub fn shift(&self) -> f64 {
        self.shift
    }

    /// b ← (A + σI)⁻¹ b using the last factorization.
    ///
    /// Calling this without a successful factorization or with `b.len() != n` is a programmer
    /// error: debug builds panic, release builds fill `b` with NaN so it cannot go unnoticed.
    /// Use [`try_solve_in_place`](Self::try_solve_in_place) to handle those cases as errors.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        if let Err(e) = self.try_solve_in_place(b) {
            debug_assert!(false, "BandLdlt::solve_in_place: {e}");
            b.fill(f64::NAN);
        }
    }

    /// b ← (A + σI)⁻¹ b, or an error if there is no valid factorization
    /// ([`FactorError::NotFactored`]) or `b` has the wrong length
    /// ([`FactorError::DimensionMismatch`]); `b` is untouched on error.
    pub fn try_solve_in_place(&self, b: &mut [f64]) -> Result<(), FactorError> {
        if !self.factored {
            return Err(FactorError::NotFactored);
        }
        let (n, bw) = (self.n, self.bw);
        if b.len() != n {
            return Err(FactorError::DimensionMismatch {
                expected: n,
                found: b.len(),
            });
        }
        match bw {
            6 => solve_rows::<6>(&self.l, &self.d, bw, b),
            10 => solve_rows::<10>(&self.l, &self.d, bw, b),
            11 => solve_rows::<11>(&self.l, &self.d, bw, b),
            12 => solve_rows::<12>(&self.l, &self.d, bw, b),
            _ => solve_rows::<0>(&self.l, &self.d, bw, b),
        }
        Ok(())
    }

    /// The pivots D of the last factorization (length n). After a failed factorization only
    /// the entries before the failing index are meaningful.
    pub fn pivots(&self) -> &[f64] {
        &self.d[..self.n.min(self.d.len())]
    }

    /// min |dᵢ| of the last successful factorization, or `None` if there is none or n = 0.
    pub fn min_abs_pivot(&self) -> Option<f64> {
        self.abs_pivot_fold(f64::min)
    }

    /// max |dᵢ| of the last successful factorization, or `None` if there is none or n = 0.
    pub fn max_abs_pivot(&self) -> Option<f64> {
        self.abs_pivot_fold(f64::max)
    }

    fn abs_pivot_fold(&self, f: fn(f64, f64) -> f64) -> Option<f64> {
        if !self.factored {
            return None;
        }
        self.pivots().iter().map(|d| d.abs()).reduce(f)
    }
}

/// The buffers of a [`BandLdlt`] being factored, row by row.
///
/// Why two code paths: with the half-bandwidth a compile-time constant `BW`, the rows at or
/// past `BW` (all but the first few) run loops of fixed trip counts over fixed-size arrays,
/// which the compiler unrolls without bounds checks: about half the instructions of the
/// general loops for a rod's band. Both paths do the same operations in the same order, so
/// the factors have the same bits. `BW = 0` means the general path for every row.
struct BandRows<'a> {
    l: &'a mut [f64],
    d: &'a mut [f64],
    pivot_scale: &'a mut [f64],
}

impl BandRows<'_> {
    fn factor<const BW: usize>(
        &mut self,
        a: &SymmetricBandMatrix,
        shift: f64,
    ) -> Result<(), FactorError> {
        let (n, bw) = (a.n, a.bw);
        debug_assert!(BW == 0 || BW == bw);
        for i in 0..n {
            let arow = a.row(i);
            let (done, rest) = self.l.split_at_mut(i * bw);
            let row = &mut rest[..bw];
            let lo = i.saturating_sub(bw);
            let off = lo + bw - i;
            if BW > 0 && i >= BW {
                let row: &mut [f64; BW] = row.try_into().expect("row of width BW");
                row.copy_from_slice(&arow[..BW]);
                // Rows i − BW … i − 1 of L, each BW wide.
                let above = &done[(i - BW) * BW..];
                for t in 0..BW {
                    let lj: &[f64; BW] = above[t * BW..(t + 1) * BW]
                        .try_into()
                        .expect("row of width BW");
                    let mut dot = -0.0;
                    for k in 0..t {
                        dot += row[k] * lj[BW - t + k];
                    }
                    row[t] -= dot;
                }
            } else {
                row[..off].fill(0.0);
                row[off..].copy_from_slice(&arow[off..bw]);
                // Row i of W = L·D, left to right: w_ij = a_ij − Σ_{lo ≤ k < j} w_ik·l_jk.
                // Row j of L holds l_jk for k ∈ [lo, j) at slots [lo + bw − j, bw).
                for t in 0..(i - lo) {
                    let j = lo + t;
                    let lj = &done[j * bw + (lo + bw - j)..(j + 1) * bw];
                    let (head, tail) = row.split_at_mut(off + t);
                    let dot: f64 = head[off..].iter().zip(lj).map(|(w, l)| w * l).sum();
                    tail[0] -= dot;
                }
            }

            // l_ij = w_ij / d_j and d_i = a_ii + σ − Σ_j w_ij·l_ij.
            let mut di = arow[bw] + shift;
            let mut scale = di.abs();
            let mut finite = true;
            for (x, &dj) in row[off..].iter_mut().zip(&self.d[lo..i]) {
                let w = *x;
                let l = w / dj;
                *x = l;
                di -= w * l;
                scale += (w * l).abs();
                finite &= l.is_finite();
            }
            self.pivot_scale[i] = scale;
            if !(finite && di.is_finite()) {
                return Err(FactorError::NonFinite { index: i });
            }
            if di == 0.0 {
                return Err(FactorError::ZeroPivot { index: i });
            }
            self.d[i] = di;
        }
        Ok(())
    }
}

/// b ← (L D Lᵀ)⁻¹ b for a band factor of half-bandwidth `bw` (`BW` as in [`BandRows`]: the
/// same operations in the same order on both paths).
fn solve_rows<const BW: usize>(l: &[f64], d: &[f64], bw: usize, b: &mut [f64]) {
    solve_rows_block::<BW, 1>(l, d, bw, [b]);
}

/// Row i of the forward substitution L y = b (a row-oriented dot product), any width:
/// y_i = (b_i − Σ_{k<i−1} l_ik·y_k) − l_{i,i−1}·y_{i−1}, the sum from −0 in increasing k.
#[inline]
fn forward_row(l: &[f64], bw: usize, i: usize, b: &mut [f64]) {
    let lo = i.saturating_sub(bw);
    let row = &l[i * bw + (lo + bw - i)..(i + 1) * bw];
    if let Some((last, head)) = row.split_last() {
        // The term of y_{i−1}, just computed, is subtracted last and alone: the chain from one
        // row to the next is one product and one subtraction.
        let dot: f64 = head.iter().zip(&b[lo..i - 1]).map(|(l, y)| l * y).sum();
        b[i] = (b[i] - dot) - last * b[i - 1];
    }
}

/// Row i of the back substitution Lᵀ x = z: once x_i is final, its contribution is removed
/// from the rows above (column-oriented, so L is still read row by row), any width.
#[inline]
fn back_row(l: &[f64], bw: usize, i: usize, b: &mut [f64]) {
    let xi = b[i];
    let lo = i.saturating_sub(bw);
    let row = &l[i * bw + (lo + bw - i)..(i + 1) * bw];
    for (x, l) in b[lo..i].iter_mut().zip(row) {
        *x -= l * xi;
    }
}

/// The forward substitution's rows BW … n − 1 (width BW > 0) for `K` right-hand sides side by
/// side: the same operations in the same order as [`forward_row`]. The last BW values of each
/// solution are carried in a window of locals, so a row's dot product does not wait for the
/// store and reload of the value the row before it just computed.
#[inline]
fn forward_rows_fixed<const BW: usize, const K: usize>(l: &[f64], bs: &mut [&mut [f64]; K]) {
    let n = bs[0].len();
    if BW == 0 || n <= BW {
        return;
    }
    let mut win = [[0.0; BW]; K];
    for (w, b) in win.iter_mut().zip(bs.iter()) {
        w.copy_from_slice(&b[..BW]);
    }
    for i in BW..n {
        let row: &[f64; BW] = l[i * BW..(i + 1) * BW].try_into().expect("width BW");
        for (w, b) in win.iter_mut().zip(bs.iter_mut()) {
            let mut dot = -0.0;
            for k in 0..BW.saturating_sub(1) {
                dot += row[k] * w[k];
            }
            let y = (b[i] - dot) - row[BW - 1] * w[BW - 1];
            b[i] = y;
            for k in 0..BW.saturating_sub(1) {
                w[k] = w[k + 1];
            }
            w[BW - 1] = y;
        }
    }
}

/// The back substitution's rows n − 1 … BW (width BW > 0) for `K` right-hand sides side by
/// side: the same operations in the same order as [`back_row`], with the BW entries that
/// row i updates carried in a window of locals instead of being read, updated and written
/// back in memory once per row.
#[inline]
fn back_rows_fixed<const BW: usize, const K: usize>(l: &[f64], bs: &mut [&mut [f64]; K]) {
    let n = bs[0].len();
    if BW == 0 || n <= BW {
        return;
    }
    // win[k] holds the partial x_{i−BW+k}; x holds the final x_i.
    let mut win = [[0.0; BW]; K];
    let mut x = [0.0; K];
    for ((w, xi), b) in win.iter_mut().zip(x.iter_mut()).zip(bs.iter()) {
        w.copy_from_slice(&b[n - 1 - BW..n - 1]);
        *xi = b[n - 1];
    }
    for i in (BW..n).rev() {
        let row: &[f64; BW] = l[i * BW..(i + 1) * BW].try_into().expect("width BW");
        for ((w, xi), b) in win.iter_mut().zip(x.iter_mut()).zip(bs.iter_mut()) {
            for k in 0..BW {
                w[k] -= row[k] * *xi;
            }
            // x_{i−1} has received its last update (from row i).
            *xi = w[BW - 1];
            if i > BW {
                b[i - 1] = *xi;
                for k in (1..BW).rev() {
                    w[k] = w[k - 1];
                }
                w[0] = b[i - 1 - BW];
            } else {
                b[..BW].copy_from_slice(w);
            }
        }
    }
}

/// [`solve_rows`] for `K` right-hand sides; each vector sees the same operations in the same
/// order as alone. The fixed-width rows run one vector at a time: their kernels can run the K
/// substitutions side by side, but that was measured slower (2.3 µs per vector alone against
/// 2.6 interleaved, 100 elements), as K windows of locals no longer fit in the registers.
/// `BW = 0`: the general loops for every row.
fn solve_rows_block<const BW: usize, const K: usize>(
    l: &[f64],
    d: &[f64],
    bw: usize,
    mut bs: [&mut [f64]; K],
) {
    let n = d.len();
    debug_assert!(BW == 0 || BW == bw);
    let head = if BW == 0 { n } else { BW.min(n) };
    for b in bs.iter_mut() {
        for i in 0..head {
            forward_row(l, bw, i, b);
        }
    }
    for b in bs.iter_mut() {
        forward_rows_fixed::<BW, 1>(l, &mut [&mut **b]);
    }
    for b in bs.iter_mut() {
        for (x, d) in b.iter_mut().zip(d) {
            *x /= d;
        }
    }
    for b in bs.iter_mut() {
        back_rows_fixed::<BW, 1>(l, &mut [&mut **b]);
    }
    for b in bs.iter_mut() {
        for i in (0..head).rev() {
            back_row(l, bw, i, b);
        }
    }
}

impl SymmetricMatrix for SymmetricBandMatrix {
    type Factor = BandLdlt;

    fn dim(&self) -> usize {
        self.n
    }

    fn set_zero(&mut self) {
        SymmetricBandMatrix::set_zero(self)
    }

    fn add_same_pattern(&mut self, other: &Self) -> bool {
        if self.n != other.n || self.bw != other.bw {
            return false;
        }
        for (a, b) in self.data.iter_mut().zip(&other.data) {
            *a += b;
        }
        true
    }

    #[inline]
    fn add(&mut self, i: usize, j: usize, v: f64) {
        SymmetricBandMatrix::add(self, i, j, v)
    }

    /// The same additions, in the same order, as the entry-by-entry default, with the band and
    /// size checked once per block instead of once per entry (the scatter of the rod stencils
    /// was a fifth of a warm re-solve).
    #[inline]
    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        let bw = self.bw;
        // Consecutive DOFs (an interior rod stencil): no slot is fixed, none repeats, and row
        // a of the block's lower triangle is a contiguous run of the band's row first + a.
        // Each entry receives one addition either way, so the result has the same bits.
        if let Some(&first) = dofs.first() {
            if D <= bw + 1
                && first != crate::assembly::FIXED
                && first + D <= self.n
                && dofs.iter().enumerate().all(|(a, &i)| i == first + a)
            {
                for a in 0..D {
                    let start = (first + a) * bw + first + bw;
                    for (b, x) in self.data[start..=start + a].iter_mut().enumerate() {
                        *x += value(a, b);
                    }
                }
                return;
            }
        }
        // Increasing DOFs (a stretch stencil: two vertices with an edge angle between them):
        // entry (a, b), b ≤ a, lies in band row dofs[a] at column dofs[b], with no ordering
        // test per entry. FIXED is the largest index, so only the last slot could be fixed,
        // and the bound on it excludes that. One addition per entry: the same bits.
        if D >= 2
            && dofs.windows(2).all(|w| w[0] < w[1])
            && dofs[D - 1] < self.n
            && dofs[D - 1] - dofs[0] <= bw
        {
            for (a, &r) in dofs.iter().enumerate() {
                let row = &mut self.data[r * bw + bw..];
                for (b, &c) in dofs[..=a].iter().enumerate() {
                    row[c] += value(a, b);
                }
            }
            return;
        }
        let (lo, hi) = dofs
            .iter()
            .filter(|&&i| i != crate::assembly::FIXED)
            .fold((usize::MAX, 0), |(l, h), &i| (l.min(i), h.max(i)));
        if lo == usize::MAX {
            return;
        }
        if hi >= self.n || hi - lo > self.bw {
            // Outside the matrix or the band: the checked path poisons the diagonal.
            super::symmetric::lower_block_entries(dofs, value, |i, j, v| self.add(i, j, v));
            return;
        }
        // Entry (r, c), c ≤ r ≤ c + bw, sits at r·(bw + 1) + c + bw − r = r·bw + c + bw.
        let data = &mut self.data;
        super::symmetric::lower_block_entries(dofs, value, |i, j, v| {
            let (r, c) = if i >= j { (i, j) } else { (j, i) };
            data[r * bw + c + bw] += v;
        });
    }

    fn diagonal(&self, i: usize) -> f64 {
        self.row(i)[self.bw]
    }

    fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        SymmetricBandMatrix::mul_vec(self, x, y)
    }

    fn gershgorin_bounds(&self) -> (f64, f64) {
        SymmetricBandMatrix::gershgorin_bounds(self)
    }

    fn gershgorin_bounds_in(&self, radius: &mut Vec<f64>) -> (f64, f64) {
        SymmetricBandMatrix::gershgorin_bounds_in(self, radius)
    }

    fn first_non_finite(&self) -> Option<usize> {
        self.first_non_finite_row()
    }

    fn congruence_scaled(&self, s: &[f64], out: &mut Self) {
        if out.n != self.n || out.bw != self.bw {
            *out = SymmetricBandMatrix::new(self.n, self.bw);
        }
        for i in 0..self.n {
            let lo = i.saturating_sub(self.bw);
            for j in lo..=i {
                let k = self.index(i, j);
                out.data[k] = self.data[k] * s[i] * s[j];
            }
        }
    }
}

impl SymmetricFactor<SymmetricBandMatrix> for BandLdlt {
    fn factorize(&mut self, a: &SymmetricBandMatrix, shift: f64) -> Result<Inertia, FactorError> {
        BandLdlt::factorize(self, a, shift)
    }

    fn try_solve_in_place(&self, b: &mut [f64]) -> Result<(), FactorError> {
        BandLdlt::try_solve_in_place(self, b)
    }

    fn solve_block_in_place<const K: usize>(&self, bs: [&mut [f64]; K]) {
        if !(self.factored && bs.iter().all(|b| b.len() == self.n)) {
            // The checked path reports (debug) or poisons (release) each bad solve.
            for b in bs {
                self.solve_in_place(b);
            }
            return;
        }
        let bw = self.bw;
        match bw {
            6 => solve_rows_block::<6, K>(&self.l, &self.d, bw, bs),
            10 => solve_rows_block::<10, K>(&self.l, &self.d, bw, bs),
            11 => solve_rows_block::<11, K>(&self.l, &self.d, bw, bs),
            12 => solve_rows_block::<12, K>(&self.l, &self.d, bw, bs),
            _ => solve_rows_block::<0, K>(&self.l, &self.d, bw, bs),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic entries in [−1, 1) (xorshift64).
    fn uniform(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        2.0 * ((*state >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }

    /// The fixed-width substitutions (windows of locals, `K` vectors side by side) give the
    /// bits of the general row-by-row loops, for every width with a fixed kernel and sizes
    /// below, at and past the width.
    #[test]
    fn fixed_width_solves_equal_the_general_loops_bit_for_bit() {
        let mut seed = 0x5EED_u64;
        for bw in [6, 10, 11, 12] {
            for n in [1, 2, bw - 1, bw, bw + 1, bw + 2, 3 * bw + 5, 100] {
                let mut a = SymmetricBandMatrix::new(n, bw);
                for i in 0..n {
                    for j in i.saturating_sub(bw)..=i {
                        a.add(i, j, uniform(&mut seed));
                    }
                    a.add(i, i, 2.0 * bw as f64);
                }
                let mut ldlt = BandLdlt::new();
                ldlt.factorize(&a, 0.0).expect("diagonally dominant");
                let rhs: Vec<Vec<f64>> = (0..3)
                    .map(|_| (0..n).map(|_| uniform(&mut seed)).collect())
                    .collect();
                let general: Vec<Vec<f64>> = rhs
                    .iter()
                    .map(|b| {
                        let mut x = b.clone();
                        solve_rows::<0>(&ldlt.l, &ldlt.d, bw, &mut x);
                        x
                    })
                    .collect();
                let mut single = rhs[0].clone();
                ldlt.solve_in_place(&mut single);
                let (mut x0, mut x1, mut x2) = (rhs[0].clone(), rhs[1].clone(), rhs[2].clone());
                ldlt.solve_block_in_place([&mut x0[..], &mut x1[..], &mut x2[..]]);
                let same =
                    |p: &[f64], q: &[f64]| p.iter().zip(q).all(|(x, y)| x.to_bits() == y.to_bits());
                assert!(same(&single, &general[0]), "bw {bw}, n {n}: single solve");
                for (x, g) in [&x0, &x1, &x2].into_iter().zip(&general) {
                    assert!(same(x, g), "bw {bw}, n {n}: block solve");
                }
            }
        }
    }
}
