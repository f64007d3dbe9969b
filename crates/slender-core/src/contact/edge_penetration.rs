//! Whether a rod's centerline edge, or a shell strip's mid-surface triangle, passes *through*
//! an obstacle between its vertices.
//!
//! Contact acts at the vertices (see [`sites`](super::sites)): an obstacle thinner than an
//! element can sit between two vertices, and a solve then returns a cable or a strip that runs
//! through it, which no energy sees. This check makes such a shape visible in the results
//! instead of passing for a valid equilibrium. It asks whether the centerline (mid-surface)
//! itself enters the obstacle (signed distance below zero), not whether the tube (the
//! thickness) around it touches: a polyline resting on a curved surface dips into it between
//! vertices by the chord's sagitta, a discretization error of order l²/R, while a centerline
//! inside the obstacle is a pass-through.

use nalgebra::Vector3;

use super::Obstacle;

/// Intervals of the edge shorter than this (relative to the edge) are not split further: a
/// centerline that enters the obstacle over less than this is not reported.
const RESOLUTION: f64 = 1e-6;

/// A triangle's depth is searched to this fraction of its size (the distance from its centroid
/// to its farthest corner), and a triangle whose mid-surface enters an obstacle by less is
/// not reported (see [`deepest_point_inside_triangle`]).
const FACE_TOLERANCE: f64 = 1e-4;

/// Evaluations of the distance per triangle at most: the search's cost where a face grazes an
/// obstacle's surface or lies along it (see [`deepest_point_inside_triangle`]).
const MAX_FACE_EVALUATIONS: usize = 256;

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

/// Where the segment from `p` to `q` (m) first meets the surface of an obstacle without an
/// inside ([`Obstacle::signed`] false: a mesh), as a fraction t ∈ [0, 1) of the segment, or
/// `None` if it stays clear. Such a surface has no depth to search: an element whose vertices
/// are held off it by contact crosses it between them or not at all (the obstacle's own
/// time of impact, exact over a mesh's faces).
pub fn segment_crossing(
    obstacle: &dyn Obstacle,
    p: &Vector3<f64>,
    q: &Vector3<f64>,
) -> Option<f64> {
    let t = obstacle.time_of_impact(p, &(q - p), 0.0);
    (t < 1.0).then_some(t)
}

/// Where the segment from `p` to `q` (m) passes through the triangle `corners` (m), or `None`:
/// the point of the segment on the triangle's plane, inside the triangle or on its border
/// (Möller and Trumbore's test). A segment in the triangle's plane (or within round-off of
/// parallel to it) is not a crossing: it touches the triangle, as a contact does.
pub fn segment_through_triangle(
    p: &Vector3<f64>,
    q: &Vector3<f64>,
    corners: &[Vector3<f64>; 3],
) -> Option<Vector3<f64>> {
    let [a, b, c] = corners;
    let (e1, e2, d) = (b - a, c - a, q - p);
    let h = d.cross(&e2);
    let det = e1.dot(&h);
    // |det| = |d · (e1 × e2)|: the segment's length times twice the area times the sine of
    // its angle with the plane.
    if det.abs() <= 1e3 * f64::EPSILON * d.norm() * e1.cross(&e2).norm() {
        return None;
    }
    let s = p - a;
    let u = s.dot(&h) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let sq = s.cross(&e1);
    let v = d.dot(&sq) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(&sq) / det;
    (0.0..=1.0).contains(&t).then(|| p + d * t)
}

/// Where the triangle `corners` (m) is deepest inside the obstacle whose signed distance is
/// `distance` (negative inside, 1-Lipschitz): `Some((x, d))` with the point x at signed
/// distance d < 0 (m), or `None` if no point inside was found.
///
/// Best-first branch and bound: no point of a triangle is closer than d(m) − R, m its centroid
/// and R the distance from m to its farthest corner (the farthest point of a convex set from
/// m is a corner); the piece with the lowest bound is split in four at its edges' midpoints
/// until no bound is below the deepest point found (or the surface) by more than
/// [`FACE_TOLERANCE`] of the triangle's size, or after [`MAX_FACE_EVALUATIONS`]. Unlike on a
/// segment, the deepest point is not resolved to [`RESOLUTION`]: the pieces a Lipschitz bound
/// cannot prune around the minimum grow as the inverse of the tolerance in two dimensions, and
/// where the minimum is a line (a face across a cylinder) as its square. The depth returned is
/// that of the point returned, which is inside: a lower bound of the face's depth, to the
/// tolerance when the search closes; a face that only grazes the surface, by less than the
/// tolerance or than the search reaches in its budget, is not reported.
pub fn deepest_point_inside_triangle(
    distance: impl Fn(&Vector3<f64>) -> f64,
    corners: [Vector3<f64>; 3],
) -> Option<(Vector3<f64>, f64)> {
    let piece_of = |corners: [Vector3<f64>; 3]| {
        let [a, b, c] = corners;
        let m = (a + b + c) / 3.0;
        let reach = (a - m).norm().max((b - m).norm()).max((c - m).norm());
        let dm = distance(&m);
        (
            Piece {
                bound: dm - reach,
                corners,
            },
            m,
            dm,
        )
    };
    let (top, m, dm) = piece_of(corners);
    let mut best = (m, dm);
    for corner in corners {
        let d = distance(&corner);
        if d < best.1 {
            best = (corner, d);
        }
    }
    let tolerance = FACE_TOLERANCE * (dm - top.bound);
    if top.bound + tolerance >= 0.0f64.min(best.1) {
        // Clear by the Lipschitz bound (almost every face of a scene): no search, no buffer.
        return (best.1 < 0.0).then_some(best);
    }
    let mut pieces = std::collections::BinaryHeap::from([top]);
    let mut evaluations = 4;
    while let Some(Piece { bound, corners }) = pieces.pop() {
        // The lowest bound left cannot hold a point inside, or deeper than the best found by
        // more than the tolerance: the search is closed.
        if bound + tolerance >= 0.0f64.min(best.1) || evaluations + 4 > MAX_FACE_EVALUATIONS {
            break;
        }
        let [a, b, c] = corners;
        let (ab, bc, ca) = ((a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0);
        for child in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [bc, ca, ab]] {
            let (piece, m, dm) = piece_of(child);
            evaluations += 1;
            if dm < best.1 {
                best = (m, dm);
            }
            pieces.push(piece);
        }
    }
    (best.1 < 0.0).then_some(best)
}

/// A piece of a triangle in the search of [`deepest_point_inside_triangle`], ordered so that
/// the heap pops the lowest bound first.
struct Piece {
    /// No point of the piece is closer to the surface than this (m).
    bound: f64,
    corners: [Vector3<f64>; 3],
}

impl PartialEq for Piece {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == std::cmp::Ordering::Equal
    }
}

impl Eq for Piece {}

impl PartialOrd for Piece {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Piece {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other.bound.total_cmp(&self.bound)
    }
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

    #[test]
    fn a_segment_across_a_mesh_panel_crosses_it_where_it_meets_it() {
        // A horizontal panel 1 cm wide (two triangles) at z = -0.01 under a 25 cm edge that
        // dips from z = 0 to z = -0.03: it meets the panel's plane at t = 1/3, x = 8.33 cm,
        // inside the panel's strip x ∈ [0.08, 0.09]; the same edge ending at z = -0.005 does not.
        let panel = crate::contact::TriangleMesh::new(
            vec![
                Vector3::new(0.08, -0.1, -0.01),
                Vector3::new(0.09, -0.1, -0.01),
                Vector3::new(0.09, 0.1, -0.01),
                Vector3::new(0.08, 0.1, -0.01),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
            0.0,
        )
        .unwrap();
        assert!(!panel.signed());
        let p = Vector3::new(0.0, 0.0, 0.0);
        let t = segment_crossing(&panel, &p, &Vector3::new(0.25, 0.0, -0.03)).expect("crosses");
        assert!((t - 1.0 / 3.0).abs() < 1e-9, "t = {t}");
        assert_eq!(
            segment_crossing(&panel, &p, &Vector3::new(0.25, 0.0, -0.005)),
            None
        );
    }

    #[test]
    fn a_segment_through_a_triangle_meets_it_on_its_plane_and_others_miss() {
        let face = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
        ];
        let hit = |p: [f64; 3], q: [f64; 3]| {
            segment_through_triangle(&Vector3::from(p), &Vector3::from(q), &face)
        };
        // Slanted through the interior: z goes from -1 to 3, so the plane is a quarter of the
        // way, at (0.2, 0.1) + (0.4, 0.4)/4.
        let x = hit([0.2, 0.1, -1.0], [0.6, 0.5, 3.0]).expect("crosses");
        assert!((x - Vector3::new(0.3, 0.2, 0.0)).norm() < 1e-15, "{x:?}");
        // Either direction.
        let y = hit([0.6, 0.5, 3.0], [0.2, 0.1, -1.0]).expect("crosses");
        assert!((x - y).norm() < 1e-15);
        // Ending short of the plane, beside the triangle, beyond its hypotenuse, in its plane.
        assert_eq!(hit([0.2, 0.1, -1.0], [0.2, 0.1, -1e-9]), None);
        assert_eq!(hit([-0.1, 0.5, -1.0], [-0.1, 0.5, 1.0]), None);
        assert_eq!(hit([0.6, 0.6, -1.0], [0.6, 0.6, 1.0]), None);
        assert_eq!(hit([-1.0, 0.2, 0.0], [2.0, 0.2, 0.0]), None);
    }

    #[test]
    fn a_triangle_pierced_by_a_small_sphere_is_found_at_its_depth() {
        // A 10 cm triangle in the plane z = 0; a 2 mm sphere centred 0.5 mm below an interior
        // point, far from the corners and edges: only the face, not an edge, passes through it,
        // 1.5 mm deep at the point above the centre.
        let corners = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.1, 0.0, 0.0),
            Vector3::new(0.0, 0.1, 0.0),
        ];
        let centre = Vector3::new(0.03, 0.02, -0.0005);
        let sphere = |x: &Vector3<f64>| (x - centre).norm() - 0.002;
        for [p, q] in [[0, 1], [1, 2], [2, 0]] {
            assert_eq!(deepest_point_inside(sphere, &corners[p], &corners[q]), None);
        }
        let (x, d) = deepest_point_inside_triangle(sphere, corners).expect("the face runs through");
        // The depth to within the search's tolerance (1e-4 of the 4.7 cm reach: 4.7 µm; 0.2 µm
        // in the 256 evaluations), the point to about its square root over the sphere's
        // curvature.
        assert!(
            (x - Vector3::new(0.03, 0.02, 0.0)).norm() < 1e-4,
            "x = {x:?}"
        );
        assert!((d + 0.0015).abs() < 4.8e-6, "depth {d}");
        assert!(
            ((x - centre).norm() - 0.002 - d).abs() < 1e-15,
            "d is the distance at x"
        );
    }

    #[test]
    fn a_triangle_above_or_beside_a_sphere_is_not_reported() {
        let corners = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.1, 0.0, 0.0),
            Vector3::new(0.0, 0.1, 0.0),
        ];
        // Just below the face (0.1 mm gap) and beside it, past the hypotenuse.
        for centre in [
            Vector3::new(0.03, 0.02, -0.0021),
            Vector3::new(0.06, 0.06, 0.0),
        ] {
            let sphere = |x: &Vector3<f64>| (x - centre).norm() - 0.002;
            assert_eq!(
                deepest_point_inside_triangle(sphere, corners),
                None,
                "{centre:?}"
            );
        }
    }
}
