//! The stability boundaries `X_c1(Y)`, `X_c2(Y)` and the tongue tip `(Y*, X*)`: walks along
//! the planar branch from both ends to the first loss of stability, and the root in `Y` of
//! the minimum of `f̂` along the branch.

use super::continuation::{walk_to_loss, Point, Tracer, WalkEnd, MAX_WALK};
use super::domain::{check_c, check_settings, check_x_positive, check_y, Y_MAX, Y_MIN};
use super::error::BendTwistError;
use super::morse_index::morse_index;
use super::types::{Settings, StabilityBoundary};
use crate::numerics::brent_root;

/// `X` where the continuation from the hanging branch starts. Every change of stability lies
/// below it over `[Y_MIN, Y_MAX] × [C_MIN, C_MAX]`: the largest `X_c2` is the large-`Y` limit
/// at `c = 0.5`, 0.7114; the tests trace the whole branch beyond it.
const X_TOP: f64 = 1.2;

/// The stability boundaries `X_c1(Y)`, `X_c2(Y)` at torsion ratio `c = GJ/EI`, with default
/// [`Settings`].
///
/// `lower` is where the planar branch, continued from the stress-free coil (`X → 0`), first
/// loses stability; `upper` is where the branch, continued down from the hanging rod, first
/// loses stability. Both are `None` when the coil reaches the hanging state without losing
/// stability (`Y < Y*`, see [`threshold_y`]). Refined to ~1e-9 relative in `X`.
///
/// Results are memoized per `(y, c)` (the sweeps ask for the same `Y` many times). Cost of a
/// first call in release builds: 1–25 ms for `Y ≤ 1`, ~40 ms at `Y = 2`, ~0.1 s at `Y = 10`,
/// ~0.25 s at `Y = 20`; a repeated call is a hash lookup (~30 ns). `y` must be in
/// `[Y_MIN, Y_MAX]`, `c` in `[C_MIN, C_MAX]`.
pub fn critical_boundaries(y: f64, c: f64) -> Result<StabilityBoundary, BendTwistError> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<(u64, u64), StabilityBoundary>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let key = (y.to_bits(), c.to_bits());
    // A poisoned lock only means another thread panicked while inserting; the map is still
    // a valid cache.
    if let Some(b) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(*b);
    }
    let b = critical_boundaries_with(y, c, &Settings::default())?;
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, b);
    Ok(b)
}

/// [`critical_boundaries`] with explicit numerical settings (not memoized).
pub fn critical_boundaries_with(
    y: f64,
    c: f64,
    settings: &Settings,
) -> Result<StabilityBoundary, BendTwistError> {
    check_y(y)?;
    check_c(c)?;
    check_settings(settings)?;
    let (walk, fine) = Tracer::pair(y, c, settings.rtol);
    let x_top = x_top(c);
    let start = walk.start_coil()?;
    require_stable(&walk, &start, "the stress-free coil")?;
    let lower = match walk_to_loss(&walk, &fine, start, 0.0, x_top)? {
        WalkEnd::Stable => {
            return Ok(StabilityBoundary {
                y,
                lower: None,
                upper: None,
            })
        }
        WalkEnd::Loss(p) => p.x(),
    };
    let top = walk.start_hanging(x_top)?;
    require_stable(&walk, &top, "the hanging rod")?;
    // Walk on below X_c1: near the tongue tip the whole window can lie inside one step, and
    // the dip of f̂ only shows once f̂ rises again.
    let upper = match walk_to_loss(&walk, &fine, top, 0.5 * lower, f64::INFINITY)? {
        WalkEnd::Loss(p) => p.x(),
        WalkEnd::Stable => {
            return Err(
                walk.fail("the branch from the hanging rod passed X_c1 without losing stability")
            )
        }
    };
    if upper <= lower {
        return Err(walk.fail(format!(
            "inconsistent boundaries X_c1 = {lower}, X_c2 = {upper}"
        )));
    }
    Ok(StabilityBoundary {
        y,
        lower: Some(lower),
        upper: Some(upper),
    })
}

/// `X` where the continuation from the hanging rod starts: above every stability change of
/// the branch. Cheaper twisting (smaller `c`) destabilizes the tip curl up to larger `X`.
fn x_top(_c: f64) -> f64 {
    X_TOP
}

/// Checks, with the Morse index, that a start point of a walk is stable.
fn require_stable(tr: &Tracer, p: &Point, what: &str) -> Result<(), BendTwistError> {
    let index = morse_index(tr.y, tr.c, p.p[0], p.p[1], tr.rtol).map_err(|e| tr.fail(e))?;
    if index == (0, 0) && p.f > 0.0 && p.r_eta > 0.0 {
        Ok(())
    } else {
        Err(tr.fail(format!(
            "{what} at X = {} is not stable (index {index:?})",
            p.x()
        )))
    }
}

/// Ground-truth classification: `true` ("2-D") if the planar equilibrium at `(x, y)` is
/// stable, `false` ("3-D") if it is unstable, i.e. `X_c1(Y) < x < X_c2(Y)`.
///
/// Inside that window every planar equilibrium of the branch is unstable (checked by a full
/// trace of the branch with its Morse index in the tests), so the answer does not depend on
/// which planar state a loading path would follow. Uses the memoized
/// [`critical_boundaries`]. `x` must be finite and `> 0`.
pub fn planar_stable(x: f64, y: f64, c: f64) -> Result<bool, BendTwistError> {
    check_x_positive(x)?;
    Ok(critical_boundaries(y, c)?.planar_stable(x))
}

/// The threshold `Y*(c)` below which the planar equilibrium is stable for every `X`: the tip
/// of the unstable tongue, where `X_c1 = X_c2` (see [`tongue_tip`]).
pub fn threshold_y(c: f64) -> Result<f64, BendTwistError> {
    Ok(tongue_tip(c)?.0)
}

/// `(Y*, X*)`: the tip of the unstable tongue, found as the root in `Y` of the first local
/// minimum of `f̂` along the branch from the coil (positive below `Y*`, negative above);
/// `X*` is where that minimum lies at `Y*`. Refined to ~1e-9 in `Y`. Cost: ~0.2 s.
pub fn tongue_tip(c: f64) -> Result<(f64, f64), BendTwistError> {
    check_c(c)?;
    let rtol = Settings::default().rtol;
    let min_f = |y: f64| -> Result<(f64, f64), BendTwistError> {
        let (walk, fine) = Tracer::pair(y, c, rtol);
        let mut a = walk.start_coil()?;
        let mut h = 0.1;
        let mut before: Option<Point> = None;
        for _ in 0..MAX_WALK {
            let b = walk.step(&a, &mut h)?;
            if let Some(z) = before {
                if a.f <= z.f && a.f < b.f {
                    let m = fine.minimize_f(&z, &b)?;
                    return Ok((m.f, m.x()));
                }
            }
            if b.p[1] > x_top(c).ln() {
                break;
            }
            before = Some(a);
            a = b;
        }
        Err(walk.fail("no minimum of the stability function"))
    };
    // Bracket: f̂ has a positive minimum below Y*, a negative one above.
    let (mut lo, mut hi) = (0.7, 1.0);
    let mut g_lo = min_f(lo)?.0;
    let mut g_hi = min_f(hi)?.0;
    for _ in 0..10 {
        if g_lo > 0.0 && g_hi <= 0.0 {
            break;
        }
        if g_lo <= 0.0 {
            (hi, g_hi) = (lo, g_lo);
            lo = (0.7 * lo).max(Y_MIN);
            g_lo = min_f(lo)?.0;
        } else {
            (lo, g_lo) = (hi, g_hi);
            hi = (1.4 * hi).min(Y_MAX);
            g_hi = min_f(hi)?.0;
        }
    }
    if !(g_lo > 0.0 && g_hi <= 0.0) {
        return Err(BendTwistError::NoConvergence {
            y: hi,
            c,
            detail: "no sign change of the minimum of f̂ in Y".into(),
        });
    }
    let y_star = brent_root(|y| Ok(min_f(y)?.0), lo, g_lo, hi, g_hi, 1e-9).map_err(|e| {
        e.into_evaluation_or(|e| BendTwistError::NoConvergence {
            y: lo,
            c,
            detail: format!("threshold Y* in [{lo}, {hi}]: {e}"),
        })
    })?;
    Ok((y_star, min_f(y_star)?.1))
}
