//! Pseudo-arclength continuation of the planar branch and the location of its events.
//!
//! The planar solutions at fixed `Y` form one curve in the `(η, ln X)` plane (`η` the
//! shooting unknown of [`super::planar`]), which for `Y ≳ 1` folds back and forth in `X`
//! (in-plane snaps). It is followed by pseudo-arclength continuation with step control on the
//! turning of the tangent and on the change of `f̂`. Sign changes of `f̂` and of the in-plane
//! derivative are refined by Brent's method on the branch; a local minimum of `f̂` between
//! two points is minimized (golden section) to catch a pair of crossings inside one step
//! (near the tongue tip). Both come from [`crate::numerics`].

use super::error::BendTwistError;
use super::planar::{gamma_of, shoot_full, Shot, TWO_PI};
use crate::numerics::{brent_root, golden_min};
use crate::ode::OdeError;
use std::f64::consts::PI;

/// The continuation from the coil starts at `X = min(X_START, 1/(2πY))`, i.e. `Γ ≤ 1`, far
/// below every instability (the lowest, `X_c1` at `Y = Y_MAX`, has `Γ ≈ 10³`).
const X_START: f64 = 0.02;

/// A converged point of the planar branch.
#[derive(Clone, Copy, Debug)]
pub(super) struct Point {
    /// `(η, ξ)`.
    pub(super) p: [f64; 2],
    /// Unit tangent in the direction of travel.
    pub(super) t: [f64; 2],
    /// `∂R/∂η` (sign: in-plane parity).
    pub(super) r_eta: f64,
    /// `f̂` (sign: out-of-plane parity).
    pub(super) f: f64,
}

impl Point {
    pub(super) fn x(&self) -> f64 {
        self.p[1].exp()
    }
}

/// Largest turn of the tangent per continuation step (rad).
const MAX_TURN: f64 = 0.12;
/// Largest change of `f̂` per continuation step without a change of sign.
const MAX_DF: f64 = 0.2;
/// Largest and smallest step length in the `(η, ln X)` plane.
const H_MAX: f64 = 1.0;
const H_MIN: f64 = 1e-9;
/// Most continuation steps of one walk (a full trace at `Y = 20` takes ~400).
pub(super) const MAX_WALK: usize = 100_000;
/// Loosest integration tolerance used while walking along the branch; events are refined
/// with the requested tolerance.
const RTOL_WALK: f64 = 1e-8;

/// The planar problem at one `(Y, c)`, integrated at one tolerance.
#[derive(Clone, Copy, Debug)]
pub(super) struct Tracer {
    pub(super) y: f64,
    pub(super) c: f64,
    pub(super) rtol: f64,
    /// Newton on the branch stops after an update below this (the update is applied, the
    /// data are those of the previous iterate).
    newton_tol: f64,
}

impl Tracer {
    /// The walking tracer (loose) and the refining tracer (as requested).
    pub(super) fn pair(y: f64, c: f64, rtol: f64) -> (Self, Self) {
        let walk = Self {
            y,
            c,
            rtol: rtol.max(RTOL_WALK),
            // Quadratic convergence: the point after an update of 1e-5 is accurate to ~1e-10,
            // while f̂ and the tangent are those 1e-5 away (enough to walk).
            newton_tol: 1e-5,
        };
        let mut fine = Self {
            y,
            c,
            rtol,
            newton_tol: 0.0,
        };
        fine.newton_tol = fine.noise();
        // (`correct` raises it to the noise level at the current η.)
        (walk, fine)
    }

    /// Level below which Newton updates at `η` are integration noise: the log-amplitude `Λ`
    /// is integrated to `rtol·|Λ|`, and `|Λ|` reaches `|η|` (≈70 for the coil at `Y = 20`,
    /// where the branch is known to ~5e-6 at `rtol = 1e-8`).
    fn noise_at(&self, eta: f64) -> f64 {
        (30.0 * self.rtol * (1.0 + 0.1 * eta.abs())).max(1e-11)
    }

    /// [`Self::noise_at`] for `|η| ≤ 1`.
    fn noise(&self) -> f64 {
        self.noise_at(0.0)
    }

    pub(super) fn fail(&self, detail: impl Into<String>) -> BendTwistError {
        BendTwistError::NoConvergence {
            y: self.y,
            c: self.c,
            detail: detail.into(),
        }
    }

    pub(super) fn shoot(&self, p: [f64; 2]) -> Result<Shot, OdeError> {
        shoot_full(self.y, self.c, p[0], p[1], self.rtol)
    }

    /// Completes a point with its tangent, oriented along `dir`.
    fn point(&self, p: [f64; 2], shot: &Shot, dir: [f64; 2]) -> Result<Point, BendTwistError> {
        let norm = shot.r_eta.hypot(shot.r_xi);
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(self.fail("singular branch (zero gradient)"));
        }
        let mut t = [-shot.r_xi / norm, shot.r_eta / norm];
        if t[0] * dir[0] + t[1] * dir[1] < 0.0 {
            t = [-t[0], -t[1]];
        }
        Ok(Point {
            p,
            t,
            r_eta: shot.r_eta,
            f: shot.f,
        })
    }

    /// Damped Newton in `η` at fixed `ξ` from `eta`, on a branch where `∂R/∂η > 0`.
    fn solve_at_xi(&self, xi: f64, mut eta: f64) -> Result<Point, BendTwistError> {
        for _ in 0..60 {
            let shot = self
                .shoot([eta, xi])
                .map_err(|e| self.fail(e.to_string()))?;
            if shot.r_eta.is_nan() || shot.r_eta <= 0.0 {
                // Off the in-plane stable branch: walk toward the root instead.
                eta -= shot.r.signum() * 0.5;
                continue;
            }
            let d = (-shot.r / shot.r_eta).clamp(-1.0, 1.0);
            if d.abs() <= self.noise_at(eta) {
                return self.point([eta + d, xi], &shot, [0.0, 1.0]);
            }
            eta += d;
        }
        Err(self.fail(format!("no planar solution found at X = {}", xi.exp())))
    }

    /// Newton on `R(p) = 0`, `a·p = b` from `guess`: the point and the shot of the last
    /// iterate, and the number of iterations.
    pub(super) fn correct(
        &self,
        guess: [f64; 2],
        a: [f64; 2],
        b: f64,
    ) -> Option<([f64; 2], Shot, usize)> {
        self.correct_to(guess, a, b, self.newton_tol)
    }

    /// [`Self::correct`] with an explicit tolerance on the Newton update.
    fn correct_to(
        &self,
        guess: [f64; 2],
        a: [f64; 2],
        b: f64,
        tol: f64,
    ) -> Option<([f64; 2], Shot, usize)> {
        let tol = tol.max(self.noise_at(guess[0]));
        let mut p = guess;
        for it in 1..=8 {
            let shot = self.shoot(p).ok()?;
            let g = a[0] * p[0] + a[1] * p[1] - b;
            let det = shot.r_eta * a[1] - shot.r_xi * a[0];
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let d0 = (-shot.r * a[1] + shot.r_xi * g) / det;
            let d1 = (-shot.r_eta * g + a[0] * shot.r) / det;
            if !(d0.is_finite() && d1.is_finite()) || d0.abs().max(d1.abs()) > 1.0 {
                return None;
            }
            p = [p[0] + d0, p[1] + d1];
            if d0.abs().max(d1.abs()) <= tol {
                return Some((p, shot, it));
            }
        }
        None
    }

    /// One accepted continuation step from `last` with trial length `h` (adapted in place).
    pub(super) fn step(&self, last: &Point, h: &mut f64) -> Result<Point, BendTwistError> {
        loop {
            if *h < H_MIN {
                return Err(self.fail(format!("continuation step underflow at X = {}", last.x())));
            }
            let pred = [last.p[0] + *h * last.t[0], last.p[1] + *h * last.t[1]];
            let b = last.t[0] * pred[0] + last.t[1] * pred[1];
            // Tight enough for the tangent and f̂ (taken at the last iterate) at this scale,
            // not below the noise of the integration.
            let noise = self.noise_at(last.p[0]);
            let tol = (1e-3 * *h).min(self.newton_tol).max(noise);
            let Some((p, shot, iterations)) = self.correct_to(pred, last.t, b, tol) else {
                *h *= 0.5;
                continue;
            };
            let next = self.point(p, &shot, last.t)?;
            let turn = (next.t[0] * last.t[0] + next.t[1] * last.t[1])
                .clamp(-1.0, 1.0)
                .acos();
            let same_sign = (next.f > 0.0) == (last.f > 0.0);
            let df = if same_sign {
                (next.f - last.f).abs()
            } else {
                0.0
            };
            let drift = (p[0] - pred[0]).hypot(p[1] - pred[1]);
            // Small turns and a corrector that stays close to the predictor keep the walk on
            // the branch (coarse steps jump between the tightly packed sheets of the folded
            // branch); small changes of f̂ resolve its dips (a change of sign is refined
            // anyway).
            if turn > MAX_TURN || df > MAX_DF || drift > 0.2 * *h + 10.0 * tol {
                *h *= 0.5;
                continue;
            }
            if iterations <= 2 && df < 0.5 * MAX_DF {
                // Aim at half the largest turn.
                *h = (*h * (0.5 * MAX_TURN / turn.max(1e-3)).clamp(0.7, 1.6)).min(H_MAX);
            }
            return Ok(next);
        }
    }

    /// The point of the branch between `a` and `b` whose projection on the chord is at
    /// fraction `tau`, from a cubic Hermite guess built on the end tangents.
    fn on_chord(&self, a: &Point, b: &Point, tau: f64) -> Result<Point, BendTwistError> {
        let chord = [b.p[0] - a.p[0], b.p[1] - a.p[1]];
        let len2 = chord[0] * chord[0] + chord[1] * chord[1];
        // End tangents scaled to d(position)/dτ (their projection on the chord is |chord|²).
        let scaled = |t: [f64; 2]| {
            let proj = t[0] * chord[0] + t[1] * chord[1];
            if proj > 0.1 * len2.sqrt() {
                [t[0] * len2 / proj, t[1] * len2 / proj]
            } else {
                chord
            }
        };
        let (ta, tb) = (scaled(a.t), scaled(b.t));
        let (t2, t3) = (tau * tau, tau * tau * tau);
        let (h00, h10, h01, h11) = (
            2.0 * t3 - 3.0 * t2 + 1.0,
            t3 - 2.0 * t2 + tau,
            -2.0 * t3 + 3.0 * t2,
            t3 - t2,
        );
        let guess: [f64; 2] =
            std::array::from_fn(|i| h00 * a.p[i] + h10 * ta[i] + h01 * b.p[i] + h11 * tb[i]);
        let rhs = chord[0] * (a.p[0] + tau * chord[0]) + chord[1] * (a.p[1] + tau * chord[1]);
        // Converged to the noise level (`correct_to` raises 0 to it): events are located with
        // these points.
        let (p, shot, _) = self
            .correct_to(guess, chord, rhs, 0.0)
            .ok_or_else(|| self.fail("no branch point on a chord"))?;
        self.point(p, &shot, a.t)
    }

    /// `a` re-evaluated at this tracer's tolerance (same position: walk points are on the
    /// branch to ~1e-10).
    fn reevaluate(&self, a: &Point) -> Result<Point, BendTwistError> {
        let shot = self.shoot(a.p).map_err(|e| self.fail(e.to_string()))?;
        self.point(a.p, &shot, a.t)
    }

    /// Root of `event` on the branch between `a` and `b`, or `None` if at this tracer's
    /// tolerance the event does not change sign between them (a walk at a looser tolerance
    /// can see a spurious change when the event is ~1e-8 from zero at a point).
    pub(super) fn refine(
        &self,
        a: &Point,
        b: &Point,
        event: EventFn,
    ) -> Result<Option<Point>, BendTwistError> {
        let ea = event(&self.reevaluate(a)?);
        let eb = event(&self.reevaluate(b)?);
        if ea.signum() == eb.signum() {
            return Ok(None);
        }
        let tau = brent_root(
            |tau| Ok(event(&self.on_chord(a, b, tau)?)),
            0.0,
            ea,
            1.0,
            eb,
            1e-10,
        )
        .map_err(|e| e.into_evaluation_or(|e| self.fail(e.to_string())))?;
        self.on_chord(a, b, tau).map(Some)
    }

    /// The minimum of `f̂` on the branch between `a` and `b`.
    pub(super) fn minimize_f(&self, a: &Point, b: &Point) -> Result<Point, BendTwistError> {
        let tau = golden_min(|tau| Ok(self.on_chord(a, b, tau)?.f), 0.0, 1.0, 1e-7)
            .map_err(|e| e.into_evaluation_or(|e| self.fail(e.to_string())))?;
        self.on_chord(a, b, tau)
    }

    pub(super) fn start_coil(&self) -> Result<Point, BendTwistError> {
        let x0 = X_START.min(1.0 / (TWO_PI * self.y));
        self.solve_at_xi(x0.ln(), (TWO_PI * self.y).ln())
    }

    /// The hanging state at `x_top`, walking down in `X`. The first guess is the linear tip
    /// layer `θ ≈ A Ai((1 − S)Γ^{1/3})`, whose `η` is `ln(2πY Γ^{1/12}/(2√π |Ai'(0)|))`.
    pub(super) fn start_hanging(&self, x_top: f64) -> Result<Point, BendTwistError> {
        const AI_PRIME_0: f64 = 0.258_819_403_792_806_8;
        let xi = x_top.ln();
        let gamma = gamma_of(xi, self.y);
        let guess =
            (TWO_PI * self.y * gamma.powf(1.0 / 12.0) / (2.0 * PI.sqrt() * AI_PRIME_0)).ln();
        let mut p = self.solve_at_xi(xi, guess)?;
        if p.t[1] > 0.0 {
            p.t = [-p.t[0], -p.t[1]];
        }
        Ok(p)
    }
}

/// What a walk along the branch found.
pub(super) enum WalkEnd {
    /// First loss of stability, refined: the point on the branch.
    Loss(Point),
    /// Left the `X` range without loss.
    Stable,
}

/// Distance between two points in the `(η, ln X)` plane.
pub(super) fn walk_distance(a: &Point, b: &Point) -> f64 {
    (b.p[0] - a.p[0]).hypot(b.p[1] - a.p[1])
}

/// An event function on the branch: it changes sign where an eigenvalue crosses zero.
pub(super) type EventFn = fn(&Point) -> f64;

/// Event functions.
pub(super) fn f_event(p: &Point) -> f64 {
    p.f
}
pub(super) fn fold_event(p: &Point) -> f64 {
    p.r_eta
}

/// Walks from the stable point `start` until stability is lost (refined with `fine`) or `X`
/// leaves `(x_low, x_high)`.
pub(super) fn walk_to_loss(
    walk: &Tracer,
    fine: &Tracer,
    start: Point,
    x_low: f64,
    x_high: f64,
) -> Result<WalkEnd, BendTwistError> {
    let (lo, hi) = (x_low.ln(), x_high.ln());
    let mut h = 0.1;
    let mut before: Option<Point> = None;
    let mut a = start;
    for _ in 0..MAX_WALK {
        let b = walk.step(&a, &mut h)?;
        if b.f <= 0.0 {
            if let Some(e) = fine.refine(&a, &b, f_event)? {
                return Ok(WalkEnd::Loss(e));
            }
        }
        if b.r_eta <= 0.0 {
            if let Some(e) = fine.refine(&a, &b, fold_event)? {
                return Ok(WalkEnd::Loss(e));
            }
        }
        // A local minimum of f̂ at a: two crossings may hide between its neighbours.
        if let Some(z) = before {
            if a.f < z.f && a.f < b.f && a.f < 0.5 {
                let m = walk.minimize_f(&z, &b)?;
                if m.f <= 0.0 {
                    if let Some(e) = fine.refine(&z, &m, f_event)? {
                        return Ok(WalkEnd::Loss(e));
                    }
                }
            }
        }
        if b.p[1] >= hi || b.p[1] <= lo {
            return Ok(WalkEnd::Stable);
        }
        before = Some(a);
        a = b;
    }
    Err(walk.fail("too many continuation steps"))
}
