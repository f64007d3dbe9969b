//! One-dimensional root finding and minimization shared by the master curves and the sweeps.
//!
//! * [`brent_root`]: Brent's method on a sign-change bracket (the bend–twist events on the
//!   branch and the threshold `Y*`).
//! * [`bisect`] and [`bisect_sign`]: bisection on a bracket, on a predicate (which side of
//!   the threshold a probe falls on: Γ_c from the Hessian inertia) or on the sign of a
//!   function (the Vlasov boundary determinant), in linear or logarithmic scale.
//! * [`golden_min`]: golden-section search for the minimum of a unimodal function.
//!
//! Every function takes a fallible closure (`FnMut(f64) -> Result<_, E>`): an evaluation is
//! often a whole ODE integration or shell solve that may fail, and its error comes back
//! unchanged as [`NumericsError::Evaluation`]. Bad input (a non-bracketing interval, NaN
//! ends, a negative tolerance) is an error, never a panic or an endless loop.
//!
//! Hand-written on purpose: the `roots` crate named in design.md §A (`find_root_brent`) takes
//! an infallible `Fn(f64) -> f64`, evaluates both ends itself (each end here is an expensive
//! solve whose value the caller already has) and iterates differently, so its iterates, and
//! hence the benchmarks' numbers, would not be bit-identical to those recorded; neither it
//! nor argmin offers a predicate bisection whose probe may abort the search.

mod error;
mod minimize;
mod root;

pub use error::NumericsError;
pub use minimize::golden_min;
pub use root::{bisect, bisect_sign, brent_root, Bisection, Scale, Side};
