//! The first guess of a strip held at both ends when one clamp moves (a drag, a motion stage):
//! the clamp's rigid motion blended along the length (weight s/L from the other clamp), the
//! strip's deflection from the chord between its clamps rescaled so that its centre line
//! keeps its length, and every row put back at its arc length along that centre line.
//!
//! Why: a thin strip bends almost inextensibly, and the blend alone changes its length (a
//! 1 cm axial push on a sagging 0.3 m strip raises the sag by centimetres, ~√(Lδ), while the
//! blend only shifts it). Newton then spends its iterations undoing the membrane strain the
//! guess put in. Measured on a flat cable (L = 0.3 m, L/h = 1000, n_L = 30, both ends
//! clamped, sagging), Newton iterations of a 1 cm push of one clamp from the loaded
//! equilibrium, mid-edge / B-spline: only the clamped rows moved 90 / 85 (the element at the
//! clamp is squashed); the blend 440 / 360; blend + length 64 / 94; blend + length + arc
//! length 7 / 6. What is left for Newton is the bending, which it solves in a few steps with
//! the mixed membrane update (`mixed_update`).
//!
//! The points are rows of equal rest station (index i·columns + j, row i along the length),
//! as the mid-edge mesh's vertices and the B-spline patch's control points are numbered.

use crate::bspline_shell::{ClampMotion, StripEnd};
use crate::geometry::Vec3;

/// The rows of a strip and the buffers of [`both_ends_guess`], kept by the strip models
/// between calls (in a [`Scratch`](crate::scratch::Scratch)) so that a drag allocates
/// nothing.
#[derive(Default)]
pub struct StripGuess {
    /// Rest position of each row along the length as a fraction of L (∈ [0, 1]); set by the
    /// model.
    pub stations: Vec<f64>,
    /// Whether each row is held by a clamp; set by the model.
    pub held: Vec<bool>,
    /// Row centres before the motion, after it, deflection from the chord, rescaled.
    old: Vec<Vec3>,
    moved: Vec<Vec3>,
    deflection: Vec<Vec3>,
    scaled: Vec<Vec3>,
    /// Arc lengths along `old` and `scaled` (m).
    s_old: Vec<f64>,
    s_new: Vec<f64>,
}

/// `out` ← the centre of every row.
fn centres_into(points: &[Vec3], columns: usize, out: &mut Vec<Vec3>) {
    out.clear();
    out.extend(
        points
            .chunks(columns)
            .map(|row| row.iter().sum::<Vec3>() / row.len() as f64),
    );
}

/// `s` ← the arc length at every point of the polyline `c` (m).
fn arc_lengths_into(c: &[Vec3], s: &mut Vec<f64>) {
    s.clear();
    s.resize(c.len(), 0.0);
    for i in 1..c.len() {
        s[i] = s[i - 1] + (c[i] - c[i - 1]).norm();
    }
}

/// Length of the polyline through `c` (m).
fn polyline_length(c: &[Vec3]) -> f64 {
    c.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// Moves `points` (rows of `columns` points; `rows.stations` and `rows.held` describe each
/// row) for the clamp motion `m` from load factor `from` to `to` on a strip held at both
/// ends. Held rows are only moved approximately: the caller puts them where their clamps hold
/// them.
pub fn both_ends_guess(
    points: &mut [Vec3],
    columns: usize,
    m: &ClampMotion,
    from: f64,
    to: f64,
    guess: &mut StripGuess,
) {
    let StripGuess {
        stations,
        held,
        old,
        moved: c,
        deflection: d,
        scaled,
        s_old,
        s_new,
    } = guess;
    let rows = stations.len();
    centres_into(points, columns, old);
    let before = polyline_length(old);
    for (i, row) in points.chunks_mut(columns).enumerate() {
        let w = match m.end {
            StripEnd::Start => 1.0 - stations[i],
            StripEnd::End => stations[i],
        };
        for p in row.iter_mut() {
            *p = m.carry(p, from, to, w);
        }
    }
    centres_into(points, columns, c);
    let (a, b) = (c[0], c[rows - 1]);
    let chord = b - a;
    let chord2 = chord.norm_squared();
    if chord2 == 0.0 {
        return;
    }
    // Deflection of every free row's centre from the chord.
    d.clear();
    d.extend(c.iter().zip(held.iter()).map(|(ci, &h)| {
        if h {
            Vec3::zeros()
        } else {
            let t = (ci - a).dot(&chord) / chord2;
            ci - (a + chord * t)
        }
    }));
    // The length of the centre line scaled by 1 + β, as `polyline_length` measures it, without
    // a copy per bisection step.
    let length = |beta: f64| -> f64 {
        let at = |i: usize| c[i] + d[i] * beta;
        (1..rows).map(|i| (at(i) - at(i - 1)).norm()).sum::<f64>() - before
    };
    // The length grows monotonically with the deflection's scale 1 + β on [−1, ∞): bisect
    // for its root (a straight strip has no deflection to scale: then nothing changes).
    let (mut lo, mut hi) = (-1.0, 0.0);
    let f0 = length(0.0);
    if f0.abs() <= 1e-12 * before {
        return;
    }
    if f0 < 0.0 {
        lo = 0.0;
        hi = 1.0;
        while length(hi) < 0.0 {
            hi *= 2.0;
            if hi > 1e3 {
                return;
            }
        }
    } else if length(lo) > 0.0 {
        // Even straightened to the chord the strip is too long: straighten it.
        hi = lo;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if length(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let beta = 0.5 * (lo + hi);
    scaled.clear();
    scaled.extend(c.iter().zip(d.iter()).map(|(ci, di)| ci + di * beta));
    // Each row back at the arc length it had along the centre line (the scaling stretches
    // the segments where the slope is steep and shortens the others: membrane strain that
    // Newton would have to undo).
    arc_lengths_into(old, s_old);
    arc_lengths_into(scaled, s_new);
    let total = s_new[rows - 1];
    let mut k = 0;
    for (i, row) in points.chunks_mut(columns).enumerate() {
        let mut target = scaled[i];
        if !held[i] {
            let s = s_old[i] / before * total;
            while k + 2 < rows && s_new[k + 1] < s {
                k += 1;
            }
            let span = s_new[k + 1] - s_new[k];
            let t = if span > 0.0 {
                (s - s_new[k]) / span
            } else {
                0.0
            };
            target = scaled[k] + (scaled[k + 1] - scaled[k]) * t.clamp(0.0, 1.0);
        }
        let shift = target - c[i];
        for p in row.iter_mut() {
            *p += shift;
        }
    }
}
