//! A small adaptive explicit Runge–Kutta integrator: Dormand–Prince 5(4) with FSAL and
//! the standard step-size control (Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.4–5).
//!
//! # Why it is hand-written
//!
//! The master curves only need the end state of small fixed-size systems (a handful of
//! states, including the variational equations) at tight tolerances. The field's crate
//! `russell_ode` needs the system OpenBLAS/LAPACK libraries, which this workspace does not
//! want to depend on, and `ode_solvers` 0.6.2 returns wrong end-point values depending on
//! the output step (a known bug). A hundred-line integrator with tests against closed
//! forms is the smaller risk.
//!
//! The state is a const-generic `[f64; N]`, so everything lives on the stack. There is no
//! dense output: integrate to each point you need. Variational (Jacobian) equations are
//! integrated by appending them to the state, so they share the error control.

/// Tolerances and limits of one integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// Relative tolerance of the local error (per step), dimensionless.
    pub rtol: f64,
    /// Absolute tolerance of the local error (per step), in the units of the state.
    pub atol: f64,
    /// Maximum number of steps (accepted and rejected) before giving up.
    pub max_steps: usize,
    /// First trial step size (in the units of the independent variable); estimated from
    /// the right-hand side when `None`.
    pub initial_step: Option<f64>,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_steps: 100_000,
            initial_step: None,
        }
    }
}

impl Options {
    /// Options with the given relative and absolute tolerances and default limits.
    pub fn with_tolerances(rtol: f64, atol: f64) -> Self {
        Self {
            rtol,
            atol,
            ..Self::default()
        }
    }
}

/// Work done by one integration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps.
    pub rejected: usize,
    /// Right-hand-side evaluations.
    pub evaluations: usize,
}

/// The end state of an integration and the work it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution<const N: usize> {
    /// The state at the end point `s1`.
    pub y: [f64; N],
    /// Work done.
    pub stats: Stats,
}

/// Why an integration failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OdeError {
    /// Non-finite interval, initial state or tolerances.
    #[error("invalid ODE input: {0}")]
    InvalidInput(&'static str),
    /// The step size fell below the resolution of the independent variable (a singularity,
    /// or a right-hand side that keeps returning non-finite values).
    #[error("step size underflow at s = {s}")]
    StepSizeUnderflow {
        /// Where the integration stopped.
        s: f64,
    },
    /// More than `max_steps` steps were needed.
    #[error("more than {max_steps} steps needed (stopped at s = {s})")]
    TooManySteps {
        /// Where the integration stopped.
        s: f64,
        /// The limit that was hit.
        max_steps: usize,
    },
}

// Dormand–Prince 5(4) tableau (Hairer's DOPRI5).
const C: [f64; 6] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0];
const A2: [f64; 1] = [1.0 / 5.0];
const A3: [f64; 2] = [3.0 / 40.0, 9.0 / 40.0];
const A4: [f64; 3] = [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0];
const A5: [f64; 4] = [
    19372.0 / 6561.0,
    -25360.0 / 2187.0,
    64448.0 / 6561.0,
    -212.0 / 729.0,
];
const A6: [f64; 5] = [
    9017.0 / 3168.0,
    -355.0 / 33.0,
    46732.0 / 5247.0,
    49.0 / 176.0,
    -5103.0 / 18656.0,
];
/// Fifth-order weights; also the last stage row (FSAL: stage 7 is evaluated at the new point).
const B: [f64; 6] = [
    35.0 / 384.0,
    0.0,
    500.0 / 1113.0,
    125.0 / 192.0,
    -2187.0 / 6784.0,
    11.0 / 84.0,
];
/// Difference between the fifth- and fourth-order weights (stages 1..=7).
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

const SAFETY: f64 = 0.9;
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 10.0;

/// `y + h * Σ a_j k_j`.
fn combine<const N: usize>(y: &[f64; N], h: f64, a: &[f64], k: &[[f64; N]]) -> [f64; N] {
    // Plain loops: `array::from_fn` over iterator sums does not vectorise and dominated
    // the run time.
    let mut acc = [0.0; N];
    for (aj, kj) in a.iter().zip(k) {
        for i in 0..N {
            acc[i] += aj * kj[i];
        }
    }
    let mut out = *y;
    for i in 0..N {
        out[i] += h * acc[i];
    }
    out
}

/// RMS norm of `v` weighted by `atol + rtol * max(|a|, |b|)`.
fn weighted_rms<const N: usize>(v: &[f64; N], a: &[f64; N], b: &[f64; N], o: &Options) -> f64 {
    if N == 0 {
        return 0.0;
    }
    let sum: f64 = (0..N)
        .map(|i| {
            let w = o.atol + o.rtol * a[i].abs().max(b[i].abs());
            (v[i] / w).powi(2)
        })
        .sum();
    (sum / N as f64).sqrt()
}

/// Integrates `y' = f(s, y)` from `(s0, y0)` to `s1` (either direction) and returns the
/// state at `s1`.
///
/// The local error of each step, measured in the RMS norm weighted by
/// `atol + rtol * |y|`, is kept below one; the global error is typically within a small
/// multiple of `rtol` for well-conditioned problems. A step whose right-hand side is not
/// finite is rejected and retried with a smaller step.
pub fn integrate<const N: usize, F>(
    mut f: F,
    s0: f64,
    y0: [f64; N],
    s1: f64,
    opts: &Options,
) -> Result<Solution<N>, OdeError>
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    if !(s0.is_finite() && s1.is_finite()) {
        return Err(OdeError::InvalidInput("non-finite interval"));
    }
    if y0.iter().any(|v| !v.is_finite()) {
        return Err(OdeError::InvalidInput("non-finite initial state"));
    }
    let tolerances_ok = opts.rtol.is_finite()
        && opts.atol.is_finite()
        && opts.rtol >= 0.0
        && opts.atol >= 0.0
        && opts.rtol + opts.atol > 0.0;
    if !tolerances_ok {
        return Err(OdeError::InvalidInput(
            "tolerances must be finite, >= 0 and not both 0",
        ));
    }
    let mut stats = Stats::default();
    if s1 == s0 {
        return Ok(Solution { y: y0, stats });
    }
    let dir = (s1 - s0).signum();
    let span = (s1 - s0).abs();

    let mut s = s0;
    let mut y = y0;
    let mut k1 = f(s, &y);
    stats.evaluations += 1;
    if k1.iter().any(|v| !v.is_finite()) {
        return Err(OdeError::StepSizeUnderflow { s });
    }
    let mut h = match opts.initial_step {
        Some(h0) if h0.is_finite() && h0 > 0.0 => h0.min(span),
        _ => initial_step(&mut f, s, &y, &k1, dir, span, opts, &mut stats),
    };
    let mut last_rejected = false;

    loop {
        if stats.accepted + stats.rejected >= opts.max_steps {
            return Err(OdeError::TooManySteps {
                s,
                max_steps: opts.max_steps,
            });
        }
        // Land exactly on s1 (and avoid a sliver of a last step).
        let remaining = (s1 - s).abs();
        let last = h >= remaining * (1.0 - 1e-12);
        if last {
            h = remaining;
        }
        // Relative to |s| only: near s = 0 a component starting at zero with a tiny atol
        // can legitimately ask for a very small first step.
        if h <= 16.0 * f64::EPSILON * s.abs() || h < f64::MIN_POSITIVE {
            return Err(OdeError::StepSizeUnderflow { s });
        }
        let hs = dir * h;

        let k2 = f(s + C[1] * hs, &combine(&y, hs, &A2, &[k1]));
        let k3 = f(s + C[2] * hs, &combine(&y, hs, &A3, &[k1, k2]));
        let k4 = f(s + C[3] * hs, &combine(&y, hs, &A4, &[k1, k2, k3]));
        let k5 = f(s + C[4] * hs, &combine(&y, hs, &A5, &[k1, k2, k3, k4]));
        let s_new = if last { s1 } else { s + hs };
        let k6 = f(s + C[5] * hs, &combine(&y, hs, &A6, &[k1, k2, k3, k4, k5]));
        let y_new = combine(&y, hs, &B, &[k1, k2, k3, k4, k5, k6]);
        let k7 = f(s_new, &y_new);
        stats.evaluations += 6;

        let err_vec = combine(&[0.0; N], hs, &E, &[k1, k2, k3, k4, k5, k6, k7]);
        let err = weighted_rms(&err_vec, &y, &y_new, opts);

        if err.is_finite() && err <= 1.0 && k7.iter().all(|v| v.is_finite()) {
            stats.accepted += 1;
            s = s_new;
            y = y_new;
            k1 = k7; // FSAL
            if last {
                return Ok(Solution { y, stats });
            }
            let mut fac = if err == 0.0 {
                FAC_MAX
            } else {
                (SAFETY * err.powf(-0.2)).clamp(FAC_MIN, FAC_MAX)
            };
            // Do not grow right after a rejection (Hairer's recommendation).
            if last_rejected {
                fac = fac.min(1.0);
            }
            h *= fac;
            last_rejected = false;
        } else {
            stats.rejected += 1;
            let fac = if err.is_finite() {
                (SAFETY * err.powf(-0.2)).clamp(FAC_MIN, 1.0)
            } else {
                FAC_MIN
            };
            h *= fac;
            last_rejected = true;
        }
    }
}

/// Hairer's starting-step heuristic (HNW I, §II.4): an explicit Euler step that would
/// have local error ~0.01, corrected with a second derivative estimate.
#[allow(clippy::too_many_arguments)]
fn initial_step<const N: usize, F>(
    f: &mut F,
    s: f64,
    y: &[f64; N],
    f0: &[f64; N],
    dir: f64,
    span: f64,
    opts: &Options,
    stats: &mut Stats,
) -> f64
where
    F: FnMut(f64, &[f64; N]) -> [f64; N],
{
    let d0 = weighted_rms(y, y, y, opts);
    let d1 = weighted_rms(f0, y, y, opts);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    }
    .min(span);
    let y1: [f64; N] = std::array::from_fn(|i| y[i] + dir * h0 * f0[i]);
    let f1 = f(s + dir * h0, &y1);
    stats.evaluations += 1;
    let df: [f64; N] = std::array::from_fn(|i| (f1[i] - f0[i]) / h0);
    let d2 = weighted_rms(&df, y, y, opts);
    let m = d1.max(d2);
    let h1 = if !m.is_finite() {
        h0 * 1e-3
    } else if m <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / m).powf(0.2)
    };
    (100.0 * h0).min(h1).min(span)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tight() -> Options {
        Options::with_tolerances(1e-12, 1e-14)
    }

    #[test]
    fn exponential_decay_to_1e_10() {
        let sol = integrate(|_, y: &[f64; 1]| [-y[0]], 0.0, [1.0], 5.0, &tight()).unwrap();
        let exact = (-5.0f64).exp();
        assert!(((sol.y[0] - exact) / exact).abs() < 1e-10, "{:?}", sol);
    }

    #[test]
    fn backward_integration() {
        let sol = integrate(|_, y: &[f64; 1]| [-y[0]], 2.0, [1.0], 0.0, &tight()).unwrap();
        let exact = 2.0f64.exp();
        assert!(((sol.y[0] - exact) / exact).abs() < 1e-10, "{:?}", sol);
    }

    #[test]
    fn harmonic_oscillator_to_1e_10() {
        // y'' = -ω² y, y(0)=1, y'(0)=0 over several periods.
        let w = 3.0f64;
        let t1 = 10.0;
        let sol = integrate(
            |_, y: &[f64; 2]| [y[1], -w * w * y[0]],
            0.0,
            [1.0, 0.0],
            t1,
            &tight(),
        )
        .unwrap();
        let exact = [(w * t1).cos(), -w * (w * t1).sin()];
        let scale = [1.0, w];
        for i in 0..2 {
            let rel = (sol.y[i] - exact[i]).abs() / scale[i];
            assert!(rel < 1e-10, "component {i}: {rel:e} ({:?})", sol);
        }
    }

    #[test]
    fn non_autonomous_closed_form() {
        // y' = cos(s) y, y(0) = 1  =>  y = exp(sin s).
        let sol = integrate(
            |s, y: &[f64; 1]| [s.cos() * y[0]],
            0.0,
            [1.0],
            7.0,
            &tight(),
        )
        .unwrap();
        let exact = 7.0f64.sin().exp();
        assert!(((sol.y[0] - exact) / exact).abs() < 1e-10);
    }

    #[test]
    fn error_decreases_with_tolerance() {
        let w = 2.0f64;
        let t1 = 6.0;
        let exact = (w * t1).cos();
        let mut previous = f64::INFINITY;
        let mut previous_steps = 0;
        for rtol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
            let sol = integrate(
                |_, y: &[f64; 2]| [y[1], -w * w * y[0]],
                0.0,
                [1.0, 0.0],
                t1,
                &Options::with_tolerances(rtol, rtol * 1e-2),
            )
            .unwrap();
            let err = (sol.y[0] - exact).abs();
            assert!(
                err < previous / 5.0,
                "rtol {rtol:e}: {err:e} vs {previous:e}"
            );
            assert!(err < 1e3 * rtol, "rtol {rtol:e}: {err:e}");
            assert!(sol.stats.accepted > previous_steps);
            previous = err;
            previous_steps = sol.stats.accepted;
        }
    }

    #[test]
    fn variational_equations_as_extra_states() {
        // y' = -y², y(0) = a  =>  y(t) = a / (1 + a t), ∂y/∂a = 1 / (1 + a t)².
        let a = 0.7;
        let t = 3.0;
        let sol = integrate(
            |_, z: &[f64; 2]| [-z[0] * z[0], -2.0 * z[0] * z[1]],
            0.0,
            [a, 1.0],
            t,
            &tight(),
        )
        .unwrap();
        let d = 1.0 + a * t;
        assert!((sol.y[0] - a / d).abs() < 1e-12);
        assert!((sol.y[1] - 1.0 / (d * d)).abs() < 1e-12);
    }

    #[test]
    fn zero_length_interval_returns_initial_state() {
        let sol = integrate(|_, y: &[f64; 1]| [y[0]], 1.0, [2.0], 1.0, &tight()).unwrap();
        assert_eq!(sol.y, [2.0]);
        assert_eq!(sol.stats.accepted, 0);
    }

    #[test]
    fn bad_input_is_an_error() {
        let f = |_: f64, y: &[f64; 1]| [y[0]];
        assert!(integrate(f, 0.0, [1.0], f64::NAN, &tight()).is_err());
        assert!(integrate(f, 0.0, [f64::INFINITY], 1.0, &tight()).is_err());
        assert!(integrate(f, 0.0, [1.0], 1.0, &Options::with_tolerances(0.0, 0.0)).is_err());
        assert!(integrate(f, 0.0, [1.0], 1.0, &Options::with_tolerances(-1.0, 0.0)).is_err());
    }

    #[test]
    fn blow_up_is_an_error_not_a_panic() {
        // y' = y², y(0) = 1 blows up at t = 1.
        let r = integrate(|_, y: &[f64; 1]| [y[0] * y[0]], 0.0, [1.0], 2.0, &tight());
        assert!(r.is_err(), "{r:?}");
        let r = integrate(
            |_, y: &[f64; 1]| [y[0]],
            0.0,
            [1.0],
            1e3,
            &Options {
                max_steps: 10,
                ..tight()
            },
        );
        assert!(matches!(r, Err(OdeError::TooManySteps { .. })), "{r:?}");
    }
}
