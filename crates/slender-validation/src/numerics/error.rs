//! Why a root or a minimum could not be found.

/// Why a root finder or minimizer stopped without an answer. `E` is the error type of the
/// evaluated function.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NumericsError<E> {
    /// An argument is NaN, infinite or outside its valid range.
    #[error("invalid {name} = {value}: must be {range}")]
    InvalidInput {
        /// Which argument (`a`, `b`, `tol`, `rel_tol`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The valid range.
        range: &'static str,
    },
    /// The function values at the ends of the interval do not have opposite signs (or one
    /// is NaN), so the interval is not known to contain a root.
    #[error("[{a}, {b}] does not bracket a root: f(a) = {fa}, f(b) = {fb} (need opposite signs)")]
    NotBracketed {
        /// One end.
        a: f64,
        /// The function there.
        fa: f64,
        /// The other end.
        b: f64,
        /// The function there.
        fb: f64,
    },
    /// The iteration limit was reached before the tolerance (the tolerance is below what
    /// `f64` resolves on this interval).
    #[error("no convergence in {iterations} iterations (last bracket [{a}, {b}])")]
    NoConvergence {
        /// Iterations done.
        iterations: usize,
        /// One end of the last bracket.
        a: f64,
        /// The other end.
        b: f64,
    },
    /// The evaluated function failed.
    #[error("{0}")]
    Evaluation(E),
}

impl<E> NumericsError<E> {
    /// The function's own error if it failed, else `other(self)` (for callers whose error
    /// type has no variant for the root finder's failures).
    pub fn into_evaluation_or(self, other: impl FnOnce(Self) -> E) -> E {
        match self {
            Self::Evaluation(e) => e,
            e => other(e),
        }
    }
}
