//! Whether a centerline edge passes *through* an obstacle between its two end vertices.
//!
//! Contact acts at the vertices (see [`sites`](super::sites)): an obstacle thinner than an
//! element can sit between two vertices, and a solve then returns a cable that runs through
//! it, which no energy sees. This check makes such a shape visible in the results instead of
//! passing for a valid equilibrium. It asks whether the edge's centerline itself enters the
//! obstacle (signed distance below zero), not whether the tube around it touches: a polyline
//! resting on a curved surface dips into it between vertices by the chord's sagitta, a
//! discretization error of order l²/R, while a centerline inside the obstacle is a
//! pass-through.

use nalgebra::Vector3;

/// Intervals of the edge shorter than this (relative to the edge) are not split further: a
/// centerline that enters the obstacle over less than this is not reported.
const RESOLUTION: f64 = 1e-6;

/// Evaluations of the distance per edge at most (a bound on the search, never reached for an
/// edge that is clear of the obstacle by more than its length's millionth).
const MAX_EVALUATIONS: usize = 4096;

/// Where the segment from `p` to `q` (m) is deepest inside the obstacle whose signed distance
/// is `distance` (negative inside, 1-Lipschitz, as [`Obstacle::surface`](super::Obstacle)
/// gives it): `Some((t, d))` with the point p + t (q − p) at signed distance d < 0 (m), or
/// `None` if the segment stays outside.
///
/// Branch and bound on the Lipschitz bound: on a piece [a, b] of the segment with end
/// distances dₐ, d_b, no point is closer than (dₐ + d_b − (b − a)·|q − p|)/2, so pieces with a
/// positive bound are clear and the others are halved. Once a point inside is found, the
/// search goes on to the deepest point (to [`RESOLUTION`] of the edge), so that the reported
/// depth is the edge's, not the first found.
pub fn deepest_point_inside(
    distance: impl Fn(&Vector3<f64>) -> f64,
    p: &Vector3<f64>,
    q: &Vector3<f64>,
) -> Option<(f64, f64)> {
    let length = (q - p).norm();
    let at = |t: f64| distance(&(p + (q - p) * t));
    let (dp, dq) = (at(0.0), at(1.0));
    let mut best = if dp <= dq { (0.0, dp) } else { (1.0, dq) };
    if 0.5 * (dp + dq - length) >= 0.0f64.min(best.1) {
        // Clear by the Lipschitz bound (almost every edge of a scene): no search, no buffer.
        return (best.1 < 0.0).then_some(best);
    }
    // Pieces (a, b, d(a), d(b)) still to search.
    let mut pieces = vec![(0.0, 1.0, dp, dq)];
    let mut evaluations = 2;
    while let Some((a, b, da, db)) = pieces.pop() {
        let bound = 0.5 * (da + db - (b - a) * length);
        // A piece that cannot hold a point inside, or not deeper than the best one found.
        if bound >= 0.0f64.min(best.1) || b - a < RESOLUTION || evaluations >= MAX_EVALUATIONS {
            continue;
        }
        let m = 0.5 * (a + b);
        let dm = at(m);
        evaluations += 1;
        if dm < best.1 {
            best = (m, dm);
        }
        pieces.push((a, m, da, dm));
        pieces.push((m, b, dm, db));
    }
    (best.1 < 0.0).then_some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Signed distance to an infinite cylinder of radius `r` about the y axis through `c`.
    fn bar(c: Vector3<f64>, r: f64) -> impl Fn(&Vector3<f64>) -> f64 {
        move |x: &Vector3<f64>| ((x.x - c.x).powi(2) + (x.z - c.z).powi(2)).sqrt() - r
    }

    #[test]
    fn a_segment_across_a_thin_bar_is_found_at_its_depth() {
        // A 25 cm edge along x, 0.4 mm above the axis of a 1 mm bar off its middle: the
        // centerline is 0.6 mm deep inside at x = 0.1 (t = 0.4), and both ends are far out.
        let p = Vector3::new(0.0, 0.0, 0.0);
        let q = Vector3::new(0.25, 0.0, 0.0);
        let (t, d) = deepest_point_inside(bar(Vector3::new(0.1, 0.0, -0.0004), 0.001), &p, &q)
            .expect("the edge runs through the bar");
        assert!((t - 0.4).abs() < 1e-5, "t = {t}");
        assert!((d + 0.0006).abs() < 1e-9, "depth {d}");
    }

    #[test]
    fn a_segment_clear_of_the_bar_or_only_grazing_its_surface_is_not_reported() {
        let p = Vector3::new(0.0, 0.0, 0.0);
        let q = Vector3::new(0.25, 0.0, 0.0);
        // 0.1 mm above the bar's top.
        assert_eq!(
            deepest_point_inside(bar(Vector3::new(0.1, 0.0, -0.0011), 0.001), &p, &q),
            None
        );
        // Far away: two evaluations and done.
        assert_eq!(
            deepest_point_inside(bar(Vector3::new(0.1, 0.0, -1.0), 0.001), &p, &q),
            None
        );
    }
}
