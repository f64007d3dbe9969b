//! The planar branch continued from the stress-free coil: the equilibrium and its stability
//! function at a given `X`, and a full trace with every change of the Morse index.

use super::continuation::{f_event, fold_event, walk_distance, EventFn, Point, Tracer, MAX_WALK};
use super::domain::{check_c, check_settings, check_x_positive, check_y, GAMMA_MAX};
use super::error::BendTwistError;
use super::morse_index::morse_index;
use super::planar::TWO_PI;
use super::types::{BranchEvent, EventKind, PlanarBranch, PlanarEquilibrium, Settings};

/// The stability function `f̂(X, Y)`: the sign of `f = δm_x(1)` of the reduced out-of-plane
/// system, normalized as `δm_x(1)/|(φ_x, φ_z, δm_x)(1)|` (dimensionless, in `[−1, 1]`).
///
/// It is evaluated on the planar branch continued from the stress-free coil: the first point
/// along the branch (from `X → 0`) with `X = x`. Before the first in-plane fold this is the
/// quasi-static loading path from `Γ = 0`. `f̂ > 0` for `x < X_c1` and `x > X_c2`; inside the
/// window its sign is `(−1)^{number of unstable out-of-plane modes}`, so it may be positive
/// there too (use [`super::planar_stable`] to classify). `x` must be `> 0` with
/// `Γ = (2πxy)³ ≤ GAMMA_MAX`.
pub fn stability_function(x: f64, y: f64, c: f64) -> Result<f64, BendTwistError> {
    Ok(planar_equilibrium(x, y, c)?.stability_function)
}

/// The planar equilibrium at `(x, y)` on the branch continued from the stress-free coil (first
/// point along the branch with `X = x`), with its stability data. Same domain as
/// [`stability_function`].
pub fn planar_equilibrium(x: f64, y: f64, c: f64) -> Result<PlanarEquilibrium, BendTwistError> {
    check_x_positive(x)?;
    check_y(y)?;
    check_c(c)?;
    let gamma = (TWO_PI * x * y).powi(3);
    if gamma > GAMMA_MAX {
        return Err(BendTwistError::InvalidParameter {
            name: "x",
            value: x,
            range: format!(
                "> 0 with Γ = (2πxy)³ ≤ {GAMMA_MAX:e}, i.e. x ≤ {} at y = {y}",
                GAMMA_MAX.cbrt() / (TWO_PI * y)
            ),
        });
    }
    let (walk, fine) = Tracer::pair(y, c, Settings::default().rtol);
    let xi = x.ln();
    let mut a = walk.start_coil()?;
    let guess = if a.p[1] >= xi {
        // Below the start (Γ ≤ 1), where the branch is a graph over X.
        a.p[0]
    } else {
        let mut h = 0.1;
        let mut guess = None;
        for _ in 0..MAX_WALK {
            let b = walk.step(&a, &mut h)?;
            if b.p[1] >= xi {
                guess = Some(a.p[0] + (b.p[0] - a.p[0]) * (xi - a.p[1]) / (b.p[1] - a.p[1]));
                break;
            }
            a = b;
        }
        guess.ok_or_else(|| walk.fail("too many continuation steps"))?
    };
    // Land exactly on X = x (Newton in η at fixed ξ from the interpolated η).
    let (p, _, _) = fine
        .correct([guess, xi], [0.0, 1.0], xi)
        .ok_or_else(|| fine.fail("could not land on the requested X"))?;
    let shot = fine.shoot(p).map_err(|e| fine.fail(e.to_string()))?;
    let index = morse_index(y, c, p[0], xi, fine.rtol).map_err(|e| fine.fail(e))?;
    let ln_k0 = p[0] - 2.0 / 3.0 * gamma.sqrt();
    Ok(PlanarEquilibrium {
        x,
        y,
        gamma,
        clamp_curvature: ln_k0.exp(),
        ln_clamp_curvature: ln_k0,
        clamp_moment: TWO_PI * y - ln_k0.exp(),
        tip_angle: shot.tip,
        stability_function: shot.f,
        index,
    })
}

/// Traces the planar branch at `(y, c)` from the stress-free coil up to `X = x_max` and
/// returns every change of stability with the Morse index on both sides (diagnostics: the
/// structure of the solution set; ~0.1 s at `Y = 1`, seconds at `Y = 10`). At every
/// continuation point it also checks that the index parities agree with the signs of `f̂`
/// and of the in-plane shooting derivative, and that the index only changes where one of
/// them changes sign.
///
/// `x_max` must be `> 0` with `(2π x_max y)³ ≤ GAMMA_MAX`.
pub fn planar_branch(
    y: f64,
    c: f64,
    x_max: f64,
    settings: &Settings,
) -> Result<PlanarBranch, BendTwistError> {
    check_y(y)?;
    check_c(c)?;
    check_x_positive(x_max)?;
    check_settings(settings)?;
    if (TWO_PI * x_max * y).powi(3) > GAMMA_MAX {
        return Err(BendTwistError::InvalidParameter {
            name: "x_max",
            value: x_max,
            range: format!("> 0 with (2π x_max y)³ ≤ {GAMMA_MAX:e}"),
        });
    }
    let (walk, _) = Tracer::pair(y, c, settings.rtol);
    let index_of =
        |p: &Point| morse_index(y, c, p.p[0], p.p[1], walk.rtol).map_err(|e| walk.fail(e));
    let mut a = walk.start_coil()?;
    let mut index_a = index_of(&a)?;
    let mut events = Vec::new();
    let mut points = 1;
    let mut h = 0.1;
    let xi_max = x_max.ln();
    while a.p[1] < xi_max {
        if points > MAX_WALK {
            return Err(walk.fail("too many continuation steps"));
        }
        // A step is kept when the index changes exactly as the signs of f̂ and ∂R/∂η say
        // (one eigenvalue per sign change); otherwise two changes hid in it: retry shorter.
        let mut tries = 0;
        let (b, index_b, f_crossed, fold_crossed) = loop {
            let b = walk.step(&a, &mut h)?;
            let index_b = index_of(&b)?;
            if (b.f > 0.0) != (index_b.1 % 2 == 0) || (b.r_eta > 0.0) != (index_b.0 % 2 == 0) {
                return Err(walk.fail(format!(
                    "index {index_b:?} inconsistent with the signs of f and R_η at X = {}",
                    b.x()
                )));
            }
            let f_crossed = (a.f > 0.0) != (b.f > 0.0);
            let fold_crossed = (a.r_eta > 0.0) != (b.r_eta > 0.0);
            let d_in = index_b.0.abs_diff(index_a.0);
            let d_out = index_b.1.abs_diff(index_a.1);
            if d_in == u32::from(fold_crossed) && d_out == u32::from(f_crossed) {
                break (b, index_b, f_crossed, fold_crossed);
            }
            tries += 1;
            if tries > 20 {
                return Err(walk.fail(format!(
                    "index changes from {index_a:?} to {index_b:?} near X = {} not resolved",
                    b.x()
                )));
            }
            h = 0.25 * h.min(walk_distance(&a, &b));
        };
        points += 1;
        let crossings: [(bool, EventKind, EventFn); 2] = [
            (f_crossed, EventKind::OutOfPlane, f_event),
            (fold_crossed, EventKind::InPlaneFold, fold_event),
        ];
        for (crossed, kind, event) in crossings {
            if crossed {
                // Located at the walking tolerance (diagnostics).
                let e = walk.refine(&a, &b, event)?.unwrap_or(b);
                events.push(BranchEvent {
                    x: e.x(),
                    kind,
                    index_before: index_a,
                    index_after: index_b,
                });
            }
        }
        index_a = index_b;
        a = b;
    }
    Ok(PlanarBranch {
        y,
        c,
        events,
        points,
        final_index: index_a,
    })
}
