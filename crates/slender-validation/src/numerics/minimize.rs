//! Minimum of a scalar function on an interval: golden-section search.

use super::NumericsError;

/// Most iterations of [`golden_min`]: each shrinks the bracket by 0.618, so 200 take any
/// `f64` interval below the resolution of its ends.
const GOLDEN_MAX_ITERATIONS: usize = 200;

/// Golden-section search for the minimum of `f` on `[a, b]` (`a < b`, both finite).
///
/// For a unimodal `f` (decreasing, then increasing) the minimizer stays inside the shrinking
/// bracket; otherwise it finds a local minimum. Stops when the bracket is no wider than `tol`
/// (absolute, in the units of `x`, finite and `> 0`) and returns its midpoint, so the answer
/// is within `tol/2` of the minimizer. Evaluates `f` at 2 points, then 1 per iteration
/// (`≈ 2.1·ln((b − a)/tol)` in all). A `tol` below what `f64` resolves on `[a, b]` gives
/// [`NumericsError::NoConvergence`].
pub fn golden_min<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    tol: f64,
) -> Result<f64, NumericsError<E>> {
    for (name, v) in [("a", a), ("b", b)] {
        if !v.is_finite() {
            return Err(NumericsError::InvalidInput {
                name,
                value: v,
                range: "finite",
            });
        }
    }
    if a >= b {
        return Err(NumericsError::InvalidInput {
            name: "b",
            value: b,
            range: "> a",
        });
    }
    if !(tol.is_finite() && tol > 0.0) {
        return Err(NumericsError::InvalidInput {
            name: "tol",
            value: tol,
            range: "finite and > 0",
        });
    }
    let mut f = |x| f(x).map_err(NumericsError::Evaluation);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    // a < x1 < x2 < b with x1, x2 at the golden ratios: one of them is reused each step.
    let mut x1 = b - g * (b - a);
    let mut x2 = a + g * (b - a);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    let mut iterations = 0;
    while b - a > tol {
        if iterations == GOLDEN_MAX_ITERATIONS {
            return Err(NumericsError::NoConvergence { iterations, a, b });
        }
        iterations += 1;
        if f1 < f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = f(x1)?;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = f(x2)?;
        }
    }
    Ok(0.5 * (a + b))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::convert::Infallible;

    fn ok(f: impl Fn(f64) -> f64) -> impl FnMut(f64) -> Result<f64, Infallible> {
        move |x| Ok(f(x))
    }

    #[test]
    fn finds_closed_form_minima() {
        // (x − 0.3)² + 1 on [0, 1]; x − ln x on [0.1, 5] (minimum at 1); cos on [2, 5] (π).
        /// `(f, a, b, minimizer)`.
        type Case = (fn(f64) -> f64, f64, f64, f64);
        let cases: [Case; 3] = [
            (|x| (x - 0.3).powi(2) + 1.0, 0.0, 1.0, 0.3),
            (|x| x - x.ln(), 0.1, 5.0, 1.0),
            (f64::cos, 2.0, 5.0, std::f64::consts::PI),
        ];
        for (f, a, b, x_min) in cases {
            for tol in [1e-4, 1e-7] {
                let x = golden_min(ok(f), a, b, tol).unwrap();
                // Bracket ≤ tol around the minimizer; f is flat there, so allow a little
                // for the comparisons that cannot tell f1 from f2.
                assert!((x - x_min).abs() <= tol, "tol {tol}: {x} vs {x_min}");
            }
        }
    }

    #[test]
    fn minimum_at_an_end_of_a_monotone_function() {
        let x = golden_min(ok(|x| x), 2.0, 3.0, 1e-8).unwrap();
        assert!((x - 2.0).abs() <= 1e-8, "{x}");
        let x = golden_min(ok(|x| -x), 2.0, 3.0, 1e-8).unwrap();
        assert!((x - 3.0).abs() <= 1e-8, "{x}");
    }

    #[test]
    fn bad_arguments_are_errors() {
        let f = ok(|x| x * x);
        assert!(matches!(
            golden_min(f, 1.0, 1.0, 1e-6),
            Err(NumericsError::InvalidInput { name: "b", .. })
        ));
        let f = ok(|x| x * x);
        assert!(matches!(
            golden_min(f, 0.0, 1.0, 0.0),
            Err(NumericsError::InvalidInput { name: "tol", .. })
        ));
        let f = ok(|x| x * x);
        assert!(matches!(
            golden_min(f, f64::NEG_INFINITY, 1.0, 1e-6),
            Err(NumericsError::InvalidInput { name: "a", .. })
        ));
        // A tolerance below the resolution at 1e6 cannot be met.
        let f = ok(|x| (x - 1e6).powi(2));
        assert!(matches!(
            golden_min(f, 1e6 - 1.0, 1e6 + 1.0, 1e-12),
            Err(NumericsError::NoConvergence { .. })
        ));
        let e = golden_min(|_| Err::<f64, _>("solve failed"), 0.0, 1.0, 1e-6).unwrap_err();
        assert_eq!(e, NumericsError::Evaluation("solve failed"));
    }
}
