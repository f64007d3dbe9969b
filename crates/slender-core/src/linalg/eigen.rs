//! The smallest eigenpair of a symmetric matrix by spectrum slicing with LDLᵀ inertia counts,
//! for any storage implementing [`SymmetricMatrix`].

use super::symmetric::{FactorError, SymmetricFactor, SymmetricMatrix};

/// Smallest eigenvalue and a unit eigenvector of a symmetric matrix, from
/// [`smallest_eigenpair`].
#[derive(Clone, Debug, PartialEq)]
pub struct EigenEstimate {
    /// Estimate of λ_min.
    pub value: f64,
    /// Unit-norm approximate eigenvector for `value`.
    pub vector: Vec<f64>,
    /// Number of LDLᵀ factorizations performed (the dominant cost).
    pub iterations: usize,
}

/// Upper limit on spectrum-slicing steps. Each step shrinks the bracket at least by half every
/// second step, and the bracket starts at width ≤ 2s and stops at ≥ 64·ε·s, so about 100 steps
/// are the worst case; the limit only guards against surprises.
const MAX_SLICES: usize = 200;
/// Inverse-iteration steps after each factorization that certifies a lower bound.
const INNER_STEPS: usize = 2;
/// Inverse-iteration steps allowed for the final eigenvector refinement.
const FINAL_STEPS: usize = 8;
/// Absolute accuracy floor, in units of ε·s (s bounds ‖A‖₂): below it, inertia counts and
/// residuals are dominated by rounding.
const ABS_FLOOR: f64 = 4.0;
/// Relative (to s) displacement of a slicing shift that hit a singular factorization.
const NUDGE: f64 = 1e-12;

/// Smallest eigenvalue λ_min and a unit eigenvector of the symmetric banded matrix `a`, using
/// only banded LDLᵀ factorizations (in `ws`, whose buffers are reused).
///
/// Method: spectrum slicing. By Sylvester's law, the number of negative pivots of A − σI is the
/// number of eigenvalues below σ. A bracket [lo, hi] ∋ λ_min is kept, where lo has no eigenvalue
/// below it (Gershgorin, or a factorization with no negative pivot) and hi is a Rayleigh quotient
/// or a shift with at least one eigenvalue below it. Each factorization with no negative pivot
/// is reused for a couple of inverse-iteration steps; their Rayleigh quotient ρ and residual r
/// lower hi and propose the next shift ρ − r (Weinstein: an eigenvalue lies within r of ρ), which
/// converges fast once the eigenvector emerges. If that proposal does not halve the bracket, the
/// next shift bisects it, so progress is guaranteed. For a positive definite A the first shift
/// is 0 (or the Gershgorin bound if that is positive), i.e. plain inverse iteration, and a few
/// factorizations suffice. A shift hitting a singular factorization is nudged by a relative
/// 1e-12. The start vector is fixed, so results are deterministic. Allocates O(n) scratch.
///
/// Guarantee: with s the Gershgorin bound on ‖A‖₂ and tol = max(rel_tol·|λ|, 64·ε·s), the
/// returned value lies in a final bracket of width ≤ tol (barring the iteration cap or the
/// bracket reaching floating-point resolution, neither expected), so |value − λ_min| ≤ tol up to
/// rounding of order (bw + 1)·ε·s in the inertia counts (the count "no eigenvalue below σ" is
/// reliable because no-pivot LDLᵀ of a positive definite matrix is backward stable). Hence the
/// relative accuracy is `rel_tol` when |λ_min| ≳ 64·ε·s/rel_tol, and degrades to the absolute
/// floor for nearly singular A. `rel_tol` is clamped to [ε, 1]. The vector is refined by
/// inverse iteration just below the bracket until ‖Av − value·v‖ ≤ tol (at most a few steps;
/// when λ_min is nearly multiple the vector may mix the nearby eigenvectors, but the residual
/// stays of the order of the cluster width).
///
/// Errors: [`FactorError::EmptyMatrix`] for n = 0, [`FactorError::NonFinite`] if `a` holds a
/// NaN or infinity. The zero matrix returns value 0 without factorizing.
pub fn smallest_eigenpair<M: SymmetricMatrix>(
    a: &M,
    ws: &mut M::Factor,
    rel_tol: f64,
) -> Result<EigenEstimate, FactorError> {
    smallest_eigenpair_near(a, ws, rel_tol, None)
}

/// Relative distance below a guessed eigenvalue of the first slicing shift of
/// [`smallest_eigenpair_near`].
const GUESS_MARGIN: f64 = 0.05;

/// As [`smallest_eigenpair`], warm: `guess` is an approximate eigenvector of λ_min (e.g. the
/// last one of a slowly changing matrix). It replaces the fixed start vector, and the first
/// shift is placed just below its Rayleigh quotient instead of at 0 or the Gershgorin bound;
/// when the guess is good, the bracket closes in two or three factorizations instead of a
/// bisection from the Gershgorin bound. The bracket logic, hence the guarantee, is that of
/// [`smallest_eigenpair`]; a poor guess only costs factorizations. A guess of the wrong
/// length, or zero or not finite, is ignored.
pub fn smallest_eigenpair_near<M: SymmetricMatrix>(
    a: &M,
    ws: &mut M::Factor,
    rel_tol: f64,
    guess: Option<&[f64]>,
) -> Result<EigenEstimate, FactorError> {
    let mut scratch = EigenScratch::default();
    let (value, iterations) = smallest_eigenpair_near_in(a, ws, rel_tol, guess, &mut scratch)?;
    Ok(EigenEstimate {
        value,
        vector: scratch.vector,
        iterations,
    })
}

/// The buffers of [`smallest_eigenpair_near_in`], reused between calls (a solver that slices
/// the spectrum at every indefinite iterate then allocates nothing for it).
#[derive(Clone, Debug, Default)]
pub struct EigenScratch {
    /// The eigenvector estimate (unit 2-norm) of the last call.
    pub vector: Vec<f64>,
    /// A v, and the guess while it is normalized.
    av: Vec<f64>,
    /// The Gershgorin row radii.
    radius: Vec<f64>,
}

/// [`smallest_eigenpair_near`] into reused buffers: returns the eigenvalue estimate and the
/// factorizations spent; the eigenvector is left in `scratch.vector`.
pub fn smallest_eigenpair_near_in<M: SymmetricMatrix>(
    a: &M,
    ws: &mut M::Factor,
    rel_tol: f64,
    guess: Option<&[f64]>,
    scratch: &mut EigenScratch,
) -> Result<(f64, usize), FactorError> {
    let n = a.dim();
    if n == 0 {
        return Err(FactorError::EmptyMatrix);
    }
    if let Some(index) = a.first_non_finite() {
        return Err(FactorError::NonFinite { index });
    }
    let EigenScratch {
        vector: v,
        av,
        radius,
    } = scratch;
    let (g_lo, g_hi) = a.gershgorin_bounds_in(radius);
    let s = g_lo.abs().max(g_hi.abs());
    start_vector_into(v, n);
    let warm = guess.is_some_and(|g| {
        g.len() == n && {
            av.clear();
            av.extend_from_slice(g);
            normalize(av).is_ok() && {
                std::mem::swap(v, av);
                true
            }
        }
    });
    if s == 0.0 {
        return Ok((0.0, 0));
    }
    let rel_tol = if rel_tol.is_nan() {
        f64::EPSILON
    } else {
        rel_tol.clamp(f64::EPSILON, 1.0)
    };
    // The absolute resolution is set by the largest diagonal entry (a shift below ε·max|aᵢᵢ| is
    // lost on the stiffest rows), not by the Gershgorin bound, which can overshoot ‖A‖ by
    // orders of magnitude on graded matrices; the inertia counts themselves are reliable to
    // each pivot's own rounding error (`Inertia::from_pivots`).
    let diag_max = (0..n).fold(0.0_f64, |m, i| m.max(a.diagonal(i).abs()));
    let floor = ABS_FLOOR * f64::EPSILON * diag_max.max(f64::MIN_POSITIVE);
    // Accuracy target for a bracket: relative to the smallest |λ| it admits.
    let tol = |lo: f64, hi: f64| {
        let m = if lo > 0.0 || hi < 0.0 {
            lo.abs().min(hi.abs())
        } else {
            0.0
        };
        (rel_tol * m).max(floor)
    };
    let _ = s;

    av.clear();
    av.resize(n, 0.0);
    let mut slicer = Slicer {
        a,
        ws,
        nudge: NUDGE * s,
        factorizations: 0,
    };

    // Initial bracket: Gershgorin below; the diagonal entries and the start vector's Rayleigh
    // quotient are Rayleigh quotients, hence upper bounds on λ_min.
    let (mut rho, mut res) = rayleigh(a, v, av);
    let mut lo = g_lo;
    let mut hi = (0..n).fold(rho, |m, i| m.min(a.diagonal(i))).max(lo);
    let mut have_vector = false;
    // Try 0 first when it can separate: for positive definite A this is plain inverse
    // iteration. Otherwise start at lo, which is below the spectrum.
    let mut proposal = Some(if warm {
        // Just below the guess's Rayleigh quotient (an upper bound of λ_min): if no eigenvalue
        // lies below, the inverse iteration there converges at once.
        rho - res.max(GUESS_MARGIN * rho.abs())
    } else if lo < 0.0 && 0.0 < hi {
        0.0
    } else {
        lo
    });

    for _ in 0..MAX_SLICES {
        let width = hi - lo;
        if width <= tol(lo, hi) {
            break;
        }
        let mid = 0.5 * (lo + hi);
        let (sigma, proposed) = match proposal.take() {
            Some(p) if p >= lo && p < hi => (p, true),
            _ => (mid, false),
        };
        if !proposed && (mid <= lo || mid >= hi) {
            break; // bracket at floating-point resolution
        }
        match slicer.count(sigma, lo, hi)? {
            Slice::Below(shift) => {
                lo = lo.max(shift);
                for _ in 0..INNER_STEPS {
                    inverse_step::<M>(slicer.ws, v)?;
                    (rho, res) = rayleigh(a, v, av);
                    hi = hi.min(rho);
                }
                have_vector = true;
                proposal = Some(rho - res.max(0.5 * tol(lo, hi)));
            }
            Slice::Above(shift) => hi = hi.min(shift),
        }
        // Rounding can cross the bounds by O(ε·s); keep the bracket well-formed.
        hi = hi.max(lo);
        if proposed && hi - lo > 0.5 * width {
            proposal = None;
        }
    }

    // Refine the eigenvector by inverse iteration just below the bracket, where A − σI is
    // positive definite with smallest eigenvalue in [w, 2w].
    let target = tol(lo, hi);
    if !have_vector || res > target {
        let w = (hi - lo).max(target);
        let mut sigma = lo - w;
        let mut factored = false;
        for _ in 0..4 {
            slicer.factorizations += 1;
            match slicer.ws.factorize(a, -sigma) {
                Ok(inertia) if inertia.is_positive_definite() => {
                    factored = true;
                    break;
                }
                Ok(_) | Err(FactorError::ZeroPivot { .. }) => sigma -= w,
                Err(e) => return Err(e),
            }
        }
        if factored {
            for _ in 0..FINAL_STEPS {
                inverse_step::<M>(slicer.ws, v)?;
                (rho, res) = rayleigh(a, v, av);
                if res <= target {
                    break;
                }
            }
        }
    }

    // max/min rather than clamp: no panic even if rounding left hi a hair below lo.
    Ok((rho.max(lo).min(hi), slicer.factorizations))
}

/// Outcome of one slicing factorization at the (possibly nudged) shift it carries.
enum Slice {
    /// No eigenvalue below the shift; the workspace holds the positive definite factorization.
    Below(f64),
    /// At least one eigenvalue below the shift.
    Above(f64),
}

struct Slicer<'a, M: SymmetricMatrix> {
    a: &'a M,
    ws: &'a mut M::Factor,
    nudge: f64,
    factorizations: usize,
}

impl<M: SymmetricMatrix> Slicer<'_, M> {
    /// Counts eigenvalues below σ ∈ [lo, hi], moving σ by up to ±nudge (kept inside the
    /// bracket) if A − σI is numerically singular there.
    fn count(&mut self, sigma: f64, lo: f64, hi: f64) -> Result<Slice, FactorError> {
        let delta = self.nudge.min(0.25 * (hi - lo));
        for shift in [sigma, sigma - delta, sigma + delta] {
            self.factorizations += 1;
            match self.ws.factorize(self.a, -shift) {
                Ok(i) if i.negative > 0 => return Ok(Slice::Above(shift)),
                Ok(i) if i.zero == 0 => return Ok(Slice::Below(shift)),
                Ok(_) | Err(FactorError::ZeroPivot { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        // Singular at three nearby shifts: an eigenvalue lies within about delta of σ.
        Ok(Slice::Above(sigma + delta))
    }
}

/// v ← (A − σI)⁻¹ v / ‖·‖ with the factorization held by `ws`.
fn inverse_step<M: SymmetricMatrix>(ws: &M::Factor, v: &mut [f64]) -> Result<(), FactorError> {
    ws.try_solve_in_place(v)?;
    normalize(v)
}

/// Scales `v` to unit 2-norm (dividing by max|vᵢ| first, so huge entries do not overflow).
fn normalize(v: &mut [f64]) -> Result<(), FactorError> {
    let (imax, m) = v.iter().enumerate().fold((0, 0.0_f64), |(k, m), (i, x)| {
        // Written so that a NaN is selected and then reported.
        if x.abs() > m || (x.is_nan() && !m.is_nan()) {
            (i, x.abs())
        } else {
            (k, m)
        }
    });
    if !m.is_finite() || m == 0.0 {
        return Err(FactorError::NonFinite { index: imax });
    }
    let norm = m * v.iter().map(|x| (x / m) * (x / m)).sum::<f64>().sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
    Ok(())
}

/// Rayleigh quotient ρ = vᵀAv of the unit vector `v` and residual ‖Av − ρv‖ (`av` is scratch).
fn rayleigh<M: SymmetricMatrix>(a: &M, v: &[f64], av: &mut [f64]) -> (f64, f64) {
    a.mul_vec(v, av);
    let rho: f64 = v.iter().zip(av.iter()).map(|(x, y)| x * y).sum();
    let res = v
        .iter()
        .zip(av.iter())
        .map(|(x, y)| (y - rho * x) * (y - rho * x))
        .sum::<f64>()
        .sqrt();
    (rho, res)
}

/// Deterministic unit start vector: entries in [0.5, 1.5) from a fixed xorshift sequence, so
/// that it is not orthogonal to a structured eigenvector (as a constant vector could be).
fn start_vector_into(v: &mut Vec<f64>, n: usize) {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    v.clear();
    v.extend((0..n).map(|_| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        0.5 + (state >> 11) as f64 / (1u64 << 53) as f64
    }));
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.iter_mut().for_each(|x| *x /= norm);
}
