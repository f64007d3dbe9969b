//! Roots of a scalar function on a bracket: Brent's method and bisection.

use super::NumericsError;

/// Most iterations of [`brent_root`]; Brent needs ~10–40 for tolerances near `f64`
/// resolution, so reaching it means the tolerance cannot be met.
const BRENT_MAX_ITERATIONS: usize = 200;

/// Default most halvings of [`bisect`]: more than any `f64` bracket can take before its
/// midpoint equals an end (≈2100 in linear scale), so the search ends on its tolerance or at
/// `f64` resolution.
const MAX_HALVINGS: usize = 2200;

/// Brent's root finder (Brent 1973, ch. 4: inverse quadratic interpolation, secant and
/// bisection steps) on `[a, b]`, given `fa = f(a)` and `fb = f(b)`.
///
/// The ends are not re-evaluated: the caller usually has them from a scan or a walk, and an
/// evaluation may be a whole ODE integration. Returns `a` or `b` if `fa` or `fb` is exactly
/// zero. Otherwise `fa` and `fb` must have opposite signs (else
/// [`NumericsError::NotBracketed`]), and the result `b` is returned once the bracket around
/// it has half-width `≤ 2ε|b| + tol/2` (absolute tolerance `tol`, in the units of `x`) or
/// `f(b) = 0`. `tol` must be finite and `≥ 0` (`0` means "to `f64` resolution").
pub fn brent_root<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    tol: f64,
) -> Result<f64, NumericsError<E>> {
    check_finite("a", a)?;
    check_finite("b", b)?;
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(NumericsError::InvalidInput {
            name: "tol",
            value: tol,
            range: "finite and >= 0",
        });
    }
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if fa.is_nan() || fb.is_nan() || fa.signum() == fb.signum() {
        return Err(NumericsError::NotBracketed { a, fa, b, fb });
    }
    let (mut a, mut fa, mut b, mut fb) = (a, fa, b, fb);
    // `b` is the best estimate, `c` the other end of the bracket, `a` the previous `b`;
    // `d` the last step and `e` the one before.
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..BRENT_MAX_ITERATIONS {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            // Interpolation: secant if only two distinct points, else inverse quadratic.
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            // Accept the interpolation only if it stays inside the bracket and shrinks
            // faster than bisection would; else bisect.
            if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b).map_err(NumericsError::Evaluation)?;
    }
    Err(NumericsError::NoConvergence {
        iterations: BRENT_MAX_ITERATIONS,
        a: b,
        b: c,
    })
}

/// Where a probe of [`bisect`] fell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// On the side of the `lo` end: the probe becomes the new `lo`.
    Low,
    /// On the side of the `hi` end: the probe becomes the new `hi`.
    High,
    /// Exactly on the threshold: the search stops there.
    Root,
}

/// In which variable [`bisect`] halves the bracket.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Arithmetic midpoint `(lo + hi)/2`; relative width `|hi − lo| / max(|lo|, |hi|)`.
    Linear,
    /// Geometric midpoint `√(lo·hi)` (both ends `> 0`); relative width
    /// `max(hi/lo, lo/hi) − 1`. For quantities known to a relative accuracy over decades.
    Log,
}

impl Scale {
    fn midpoint(self, lo: f64, hi: f64) -> f64 {
        match self {
            Scale::Linear => 0.5 * (lo + hi),
            Scale::Log => (lo * hi).sqrt(),
        }
    }

    fn wider_than(self, lo: f64, hi: f64, rel_tol: f64) -> bool {
        match self {
            Scale::Linear => (hi - lo).abs() > rel_tol * lo.abs().max(hi.abs()),
            Scale::Log => (hi / lo).max(lo / hi) - 1.0 > rel_tol,
        }
    }
}

/// Stopping rule of [`bisect`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bisection {
    /// Midpoint and width measure.
    pub scale: Scale,
    /// The search stops once the relative width of the bracket (see [`Scale`]) is
    /// `≤ rel_tol` (dimensionless, finite, `≥ 0`; `0` bisects to `f64` resolution).
    pub rel_tol: f64,
    /// The search also stops after this many probes.
    pub max_halvings: usize,
}

impl Bisection {
    /// Arithmetic bisection to relative width `rel_tol`.
    pub fn linear(rel_tol: f64) -> Self {
        Self {
            scale: Scale::Linear,
            rel_tol,
            max_halvings: MAX_HALVINGS,
        }
    }

    /// Geometric bisection to relative width `rel_tol`.
    pub fn log(rel_tol: f64) -> Self {
        Self {
            scale: Scale::Log,
            rel_tol,
            max_halvings: MAX_HALVINGS,
        }
    }

    /// The same with at most `n` probes.
    pub fn with_max_halvings(self, n: usize) -> Self {
        Self {
            max_halvings: n,
            ..self
        }
    }
}

/// Bisection on a predicate: `side(x)` tells on which side of the sought threshold `x` lies.
///
/// `lo` must be on the [`Side::Low`] side and `hi` on the [`Side::High`] side; they are not
/// probed (the caller has established the bracket, often at the cost of a solve per end), and
/// `lo > hi` is allowed. Each step probes the midpoint (see [`Scale`]) and replaces the end
/// on the same side; [`Side::Root`] returns the probe at once. The search stops when the
/// bracket is no wider than `settings.rel_tol`, when its midpoint equals an end (`f64`
/// resolution), or after `settings.max_halvings` probes, and returns the midpoint of the
/// final bracket. The probes depend only on the ends and the answers, so a deterministic
/// `side` gives a deterministic result.
pub fn bisect<E>(
    mut side: impl FnMut(f64) -> Result<Side, E>,
    lo: f64,
    hi: f64,
    settings: Bisection,
) -> Result<f64, NumericsError<E>> {
    check_finite("lo", lo)?;
    check_finite("hi", hi)?;
    if settings.scale == Scale::Log {
        for (name, v) in [("lo", lo), ("hi", hi)] {
            if v <= 0.0 {
                return Err(NumericsError::InvalidInput {
                    name,
                    value: v,
                    range: "> 0 for a logarithmic bisection",
                });
            }
        }
    }
    if !(settings.rel_tol.is_finite() && settings.rel_tol >= 0.0) {
        return Err(NumericsError::InvalidInput {
            name: "rel_tol",
            value: settings.rel_tol,
            range: "finite and >= 0",
        });
    }
    let scale = settings.scale;
    let (mut lo, mut hi) = (lo, hi);
    let mut probes = 0;
    while probes < settings.max_halvings && scale.wider_than(lo, hi, settings.rel_tol) {
        let mid = scale.midpoint(lo, hi);
        if mid == lo || mid == hi {
            return Ok(mid);
        }
        probes += 1;
        match side(mid).map_err(NumericsError::Evaluation)? {
            Side::Low => lo = mid,
            Side::High => hi = mid,
            Side::Root => return Ok(mid),
        }
    }
    Ok(scale.midpoint(lo, hi))
}

/// Bisection on the sign of `f`, given `f_lo = f(lo)` and `f_hi = f(hi)` (not re-evaluated).
///
/// Returns `lo` or `hi` if `f_lo` or `f_hi` is exactly zero; otherwise they must have
/// opposite signs (else [`NumericsError::NotBracketed`]). A probe where `f = 0` is returned
/// at once; a probe with the sign of `f_lo` replaces `lo`, any other (the other sign, or NaN)
/// replaces `hi`. Stopping rule and result as in [`bisect`].
pub fn bisect_sign<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    lo: f64,
    f_lo: f64,
    hi: f64,
    f_hi: f64,
    settings: Bisection,
) -> Result<f64, NumericsError<E>> {
    if f_lo == 0.0 {
        return Ok(lo);
    }
    if f_hi == 0.0 {
        return Ok(hi);
    }
    if f_lo.is_nan() || f_hi.is_nan() || f_lo.signum() == f_hi.signum() {
        return Err(NumericsError::NotBracketed {
            a: lo,
            fa: f_lo,
            b: hi,
            fb: f_hi,
        });
    }
    let low_sign = f_lo.signum();
    bisect(
        |x| {
            let fx = f(x)?;
            Ok(if fx == 0.0 {
                Side::Root
            } else if fx.signum() == low_sign {
                Side::Low
            } else {
                Side::High
            })
        },
        lo,
        hi,
        settings,
    )
}

fn check_finite<E>(name: &'static str, value: f64) -> Result<(), NumericsError<E>> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(NumericsError::InvalidInput {
            name,
            value,
            range: "finite",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::convert::Infallible;

    fn ok(f: impl Fn(f64) -> f64) -> impl FnMut(f64) -> Result<f64, Infallible> {
        move |x| Ok(f(x))
    }

    /// The Dottie number, the root of cos x = x.
    const DOTTIE: f64 = 0.739_085_133_215_160_6;

    #[test]
    fn brent_finds_closed_form_roots() {
        let g = |x: f64| x.cos() - x;
        let r = brent_root(ok(g), 0.0, g(0.0), 1.0, g(1.0), 1e-14).unwrap();
        assert!((r - DOTTIE).abs() < 1e-14, "{r}");
        let h = |x: f64| x * x * x - 2.0;
        let r = brent_root(ok(h), 0.0, h(0.0), 2.0, h(2.0), 0.0).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 4.0 * f64::EPSILON, "{r}");
        // Reversed bracket, root at the edge of the interval's resolution.
        let r = brent_root(ok(h), 2.0, h(2.0), 1.0, h(1.0), 1e-12).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-12, "{r}");
    }

    #[test]
    fn brent_meets_its_absolute_tolerance() {
        // A flat root: the x tolerance, not |f|, decides.
        let g = |x: f64| (x - 0.3).powi(3);
        for tol in [1e-3, 1e-6, 1e-9] {
            let r = brent_root(ok(g), 0.0, g(0.0), 1.0, g(1.0), tol).unwrap();
            assert!((r - 0.3).abs() <= tol, "tol {tol}: {r}");
        }
    }

    #[test]
    fn brent_returns_an_end_where_f_vanishes() {
        let g = |x: f64| x - 1.0;
        assert_eq!(brent_root(ok(g), 1.0, 0.0, 3.0, 2.0, 1e-9).unwrap(), 1.0);
        assert_eq!(brent_root(ok(g), -1.0, -2.0, 1.0, 0.0, 1e-9).unwrap(), 1.0);
    }

    #[test]
    fn non_bracketing_intervals_are_errors_not_panics() {
        let g = |x: f64| x * x + 1.0;
        let e = brent_root(ok(g), -1.0, g(-1.0), 1.0, g(1.0), 1e-9).unwrap_err();
        assert!(matches!(e, NumericsError::NotBracketed { .. }), "{e}");
        let e = brent_root(ok(g), 0.0, f64::NAN, 1.0, -1.0, 1e-9).unwrap_err();
        assert!(matches!(e, NumericsError::NotBracketed { .. }), "{e}");
        let e = bisect_sign(ok(g), -1.0, 2.0, 1.0, 2.0, Bisection::linear(1e-9)).unwrap_err();
        assert!(matches!(e, NumericsError::NotBracketed { .. }), "{e}");
    }

    #[test]
    fn bad_arguments_are_named() {
        let g = |x: f64| x;
        for (e, name) in [
            (
                brent_root(ok(g), f64::NAN, -1.0, 1.0, 1.0, 1e-9).unwrap_err(),
                "a",
            ),
            (
                brent_root(ok(g), -1.0, -1.0, 1.0, 1.0, -1e-9).unwrap_err(),
                "tol",
            ),
            (
                bisect_sign(ok(g), -1.0, -1.0, 1.0, 1.0, Bisection::log(1e-9)).unwrap_err(),
                "lo",
            ),
            (
                bisect_sign(ok(g), -1.0, -1.0, 1.0, 1.0, Bisection::linear(f64::NAN)).unwrap_err(),
                "rel_tol",
            ),
        ] {
            assert!(
                matches!(e, NumericsError::InvalidInput { name: n, .. } if n == name),
                "{e}"
            );
        }
    }

    #[test]
    fn evaluation_errors_come_back_unchanged() {
        let failing = |x: f64| {
            if x > 0.4 {
                Err("solve failed")
            } else {
                Ok(x - 0.7)
            }
        };
        let e = brent_root(failing, 0.0, -0.7, 1.0, 0.3, 1e-9).unwrap_err();
        assert_eq!(e, NumericsError::Evaluation("solve failed"));
        let e = bisect_sign(failing, 0.0, -0.7, 1.0, 0.3, Bisection::linear(1e-9)).unwrap_err();
        assert_eq!(e, NumericsError::Evaluation("solve failed"));
    }

    #[test]
    fn bisection_reaches_its_relative_width() {
        let g = |x: f64| x.cos() - x;
        let r = bisect_sign(ok(g), 0.0, g(0.0), 1.0, g(1.0), Bisection::linear(1e-12)).unwrap();
        assert!((r - DOTTIE).abs() <= 1e-12, "{r}");
        // Log scale: the root of x³ = 2000 on [1, 1000] to 1e-10 relative.
        let h = |x: f64| x * x * x - 2000.0;
        let r = bisect_sign(ok(h), 1.0, h(1.0), 1e3, h(1e3), Bisection::log(1e-10)).unwrap();
        assert!((r / 2000f64.cbrt() - 1.0).abs() <= 1e-10, "{r}");
        // Zero tolerance ends at f64 resolution on the exact root.
        let r = bisect_sign(ok(h), 1.0, h(1.0), 1e3, h(1e3), Bisection::linear(0.0)).unwrap();
        assert!(
            (r / 2000f64.cbrt() - 1.0).abs() <= 4.0 * f64::EPSILON,
            "{r}"
        );
    }

    #[test]
    fn predicate_bisection_counts_its_probes() {
        // A threshold at 1/3 in [0, 1]: n probes leave a bracket of width 2⁻ⁿ.
        let mut probes = 0;
        let r = bisect(
            |x: f64| {
                probes += 1;
                Ok::<_, Infallible>(if x < 1.0 / 3.0 { Side::Low } else { Side::High })
            },
            0.0,
            1.0,
            Bisection::linear(0.0).with_max_halvings(20),
        )
        .unwrap();
        assert_eq!(probes, 20);
        assert!((r - 1.0 / 3.0).abs() <= 0.5f64.powi(21), "{r}");
        // A reversed bracket works the same way.
        let r = bisect(
            |x: f64| Ok::<_, Infallible>(if x > 0.25 { Side::Low } else { Side::High }),
            1.0,
            0.0,
            Bisection::linear(1e-12),
        )
        .unwrap();
        assert!((r - 0.25).abs() <= 1e-12, "{r}");
        // An exact hit stops the search.
        let r = bisect(
            |x: f64| Ok::<_, Infallible>(if x == 0.5 { Side::Root } else { Side::Low }),
            0.0,
            1.0,
            Bisection::linear(1e-12),
        )
        .unwrap();
        assert_eq!(r, 0.5);
    }
}
