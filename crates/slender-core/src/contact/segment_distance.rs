//! The distance between two segments with its exact gradient and Hessian in the segments'
//! twelve endpoint coordinates — the geometry of cable–cable and self-contact.
//!
//! Where the closest points lie decides the formula (Ericson, Real-Time Collision Detection
//! §5.1.9): inside both segments, the distance of the two lines; at an end of one segment,
//! the distance of that end point to the other segment's line; at ends of both, the distance
//! of two points. Each is a smooth function near the configuration, differentiated to second
//! order by forward-mode dual numbers (`shell::dual`, exact to round-off). The distance is
//! continuous with a continuous gradient across the regions; near-parallel segments are
//! classified by their end points (the lines' distance is ill-conditioned there).

use crate::shell::dual::{cross3, dot3, point, sub3, Dual2};

/// Twelve variables: a₀, a₁ (first segment), b₀, b₁ (second), three coordinates each.
pub type SegmentPairDual = Dual2<12>;

/// Below this |e_a × e_b|² / (|e_a|² |e_b|²) (sin² of the angle) segments count as parallel.
const PARALLEL: f64 = 1e-10;

/// Parameters (s, t) ∈ [0, 1]² of the closest points of segments a₀a₁ and b₀b₁.
pub fn closest_parameters(x: &[f64; 12]) -> (f64, f64) {
    let p = |k: usize| nalgebra::Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let (a0, a1, b0, b1) = (p(0), p(1), p(2), p(3));
    let (d1, d2, r) = (a1 - a0, b1 - b0, a0 - b0);
    let (a, e, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    let c = d1.dot(&r);
    let b = d1.dot(&d2);
    let denom = a * e - b * b;
    let mut s = if denom > PARALLEL * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Distance (m) between segments a₀a₁ and b₀b₁ (coordinates as in [`SegmentPairDual`]),
/// without derivatives: for step caps, which evaluate it many times.
pub fn segment_distance(x: &[f64; 12]) -> f64 {
    let p = |k: usize| nalgebra::Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let (s, t) = closest_parameters(x);
    let pa = p(0) + (p(1) - p(0)) * s;
    let pb = p(2) + (p(3) - p(2)) * t;
    (pa - pb).norm()
}

/// Distance (m) from point p to segment ab (coordinates p, a, b), without derivatives.
pub fn point_segment_distance(x: &[f64; 9]) -> f64 {
    let p = |k: usize| nalgebra::Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let (q, a, b) = (p(0), p(1), p(2));
    let e = b - a;
    let t = ((q - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
    (q - a - e * t).norm()
}

/// |p − q|² for points p, q given as variable triples `i` and `j`.
fn point_point(x: &[f64; 12], i: usize, j: usize) -> SegmentPairDual {
    let d = sub3(&point::<12>(x, i), &point::<12>(x, j));
    dot3(&d, &d)
}

/// Squared distance from point `p` to the line through points `a`, `b` (variable triples).
fn point_line(x: &[f64; 12], p: usize, a: usize, b: usize) -> SegmentPairDual {
    let (pp, pa, pb) = (point::<12>(x, p), point::<12>(x, a), point::<12>(x, b));
    let n = cross3(&sub3(&pa, &pp), &sub3(&pb, &pp));
    let e = sub3(&pb, &pa);
    dot3(&n, &n) / dot3(&e, &e)
}

/// Squared distance between the lines through a₀a₁ and b₀b₁.
fn line_line(x: &[f64; 12]) -> SegmentPairDual {
    let (a0, a1, b0, b1) = (point(x, 0), point(x, 1), point(x, 2), point(x, 3));
    let n = cross3(&sub3(&a1, &a0), &sub3(&b1, &b0));
    let h = dot3(&n, &sub3(&b0, &a0));
    (h * h) / dot3(&n, &n)
}

/// Squared distance between segments a₀a₁ and b₀b₁ (variables as in [`SegmentPairDual`]),
/// with its gradient and Hessian.
pub fn segment_distance_squared(x: &[f64; 12]) -> SegmentPairDual {
    let (s, t) = closest_parameters(x);
    let end = |u: f64| (u == 0.0 || u == 1.0).then_some(if u == 0.0 { 0 } else { 1 });
    match (end(s), end(t)) {
        (Some(i), Some(j)) => point_point(x, i, 2 + j),
        (Some(i), None) => point_line(x, i, 2, 3),
        (None, Some(j)) => point_line(x, 2 + j, 0, 1),
        (None, None) => line_line(x),
    }
}

/// Squared distance from point p to segment ab (variables p, a, b as three triples), with its
/// gradient and Hessian: to the line inside the segment, to the nearer end beyond it.
pub fn point_segment_distance_squared(x: &[f64; 9]) -> Dual2<9> {
    let p = |k: usize| nalgebra::Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
    let (pp, a, b) = (p(0), p(1), p(2));
    let e = b - a;
    let t = (pp - a).dot(&e) / e.norm_squared();
    let (pd, ad, bd) = (point::<9>(x, 0), point::<9>(x, 1), point::<9>(x, 2));
    if t <= 0.0 {
        let d = sub3(&pd, &ad);
        dot3(&d, &d)
    } else if t >= 1.0 {
        let d = sub3(&pd, &bd);
        dot3(&d, &d)
    } else {
        let n = cross3(&sub3(&ad, &pd), &sub3(&bd, &pd));
        let ed = sub3(&bd, &ad);
        dot3(&n, &n) / dot3(&ed, &ed)
    }
}

/// The edge–edge mollifier m(c) = c (2 − c) for c = |e_a × e_b|² / ε_x below 1, and 1 above:
/// it fades the edge–edge contact out as the edges turn parallel, where their distance is
/// ill-conditioned and the vertex–edge contacts, which are well conditioned there, take over.
/// `scale` is ε_x (m⁴).
pub fn edge_edge_mollifier(x: &[f64; 12], scale: f64) -> SegmentPairDual {
    let (a0, a1, b0, b1) = (point(x, 0), point(x, 1), point(x, 2), point(x, 3));
    let n = cross3(&sub3(&a1, &a0), &sub3(&b1, &b0));
    let c = dot3(&n, &n).scale(1.0 / scale);
    if c.v >= 1.0 {
        return Dual2::constant(1.0);
    }
    let two_minus_c = Dual2::constant(2.0) - c;
    c * two_minus_c
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brute_force(x: &[f64; 12]) -> f64 {
        let p = |k: usize| nalgebra::Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
        let mut best = f64::INFINITY;
        for i in 0..=400 {
            for j in 0..=400 {
                let (s, t) = (i as f64 / 400.0, j as f64 / 400.0);
                let a = p(0) + (p(1) - p(0)) * s;
                let b = p(2) + (p(3) - p(2)) * t;
                best = best.min((a - b).norm_squared());
            }
        }
        best
    }

    #[test]
    fn every_region_matches_a_brute_force_minimum_and_central_differences() {
        let cases: [[f64; 12]; 5] = [
            // Crossing interiors (line–line).
            [0., 0., 0., 1., 0., 0., 0.5, -1., 0.3, 0.5, 1., 0.4],
            // An end against an interior (point–line).
            [0., 0., 0., 1., 0., 0., 1.3, -1., 0.2, 1.2, 1., 0.3],
            // Two ends (point–point).
            [0., 0., 0., 1., 0., 0., 1.5, 0.5, 0.2, 2.5, 1.0, 0.1],
            // Near-parallel, overlapping.
            [0., 0., 0., 1., 0., 0., 0.2, 0.3, 0.0, 1.2, 0.3, 1e-9],
            // Skew, the second end of b closest to a's interior.
            [0., 0., 0., 2., 0., 0., 0.7, 0.2, 0.5, 0.9, 0.8, 1.5],
        ];
        for x in cases {
            let d = segment_distance_squared(&x);
            let bf = brute_force(&x);
            // The 400 × 400 grid overestimates the minimum by up to (|e|/400)² ≈ 3e-5.
            assert!(d.v <= bf + 1e-12 && d.v >= bf - 3e-5, "{} vs {bf}", d.v);
            let h = 1e-6;
            for i in 0..12 {
                let mut xp = x;
                let mut xm = x;
                xp[i] += h;
                xm[i] -= h;
                let (dp, dm) = (segment_distance_squared(&xp), segment_distance_squared(&xm));
                let fd_g = (dp.v - dm.v) / (2.0 * h);
                assert!(
                    (fd_g - d.g[i]).abs() < 1e-7,
                    "case {x:?}, ∂{i}: {fd_g} vs {}",
                    d.g[i]
                );
                for j in 0..12 {
                    let fd_h = (dp.g[j] - dm.g[j]) / (2.0 * h);
                    assert!(
                        (fd_h - d.h[(j, i)]).abs() < 1e-5,
                        "case {x:?}, ∂{i}∂{j}: {fd_h} vs {}",
                        d.h[(j, i)]
                    );
                }
            }
        }
    }
}

#[cfg(test)]
mod point_segment_tests {
    use super::*;

    #[test]
    fn point_segment_matches_closed_forms_and_differences() {
        for x in [
            [0.5, 1.0, 0.3, 0., 0., 0., 1., 0., 0.],
            [-0.5, 1.0, 0.3, 0., 0., 0., 1., 0., 0.],
            [1.7, -0.2, 0.1, 0., 0., 0., 1., 0., 0.],
        ] {
            let d = point_segment_distance_squared(&x);
            let px = x[0].clamp(0.0, 1.0);
            let exact = (x[0] - px).powi(2) + x[1] * x[1] + x[2] * x[2];
            assert!((d.v - exact).abs() < 1e-14, "{} vs {exact}", d.v);
            let h = 1e-6;
            for i in 0..9 {
                let (mut xp, mut xm) = (x, x);
                xp[i] += h;
                xm[i] -= h;
                let (dp, dm) = (
                    point_segment_distance_squared(&xp),
                    point_segment_distance_squared(&xm),
                );
                assert!(((dp.v - dm.v) / (2.0 * h) - d.g[i]).abs() < 1e-7);
                for j in 0..9 {
                    assert!(((dp.g[j] - dm.g[j]) / (2.0 * h) - d.h[(j, i)]).abs() < 1e-5);
                }
            }
        }
    }

    #[test]
    fn mollifier_is_smooth_and_one_away_from_parallel() {
        let crossing = [0., 0., 0., 1., 0., 0., 0.5, -1., 0.3, 0.5, 1., 0.4];
        assert_eq!(edge_edge_mollifier(&crossing, 1e-3).v, 1.0);
        let parallel = [0., 0., 0., 1., 0., 0., 0., 0.1, 0., 1., 0.1, 0.02];
        let m = edge_edge_mollifier(&parallel, 1e-3);
        assert!(m.v > 0.0 && m.v < 1.0);
        let h = 1e-7;
        for i in 0..12 {
            let (mut xp, mut xm) = (parallel, parallel);
            xp[i] += h;
            xm[i] -= h;
            let fd =
                (edge_edge_mollifier(&xp, 1e-3).v - edge_edge_mollifier(&xm, 1e-3).v) / (2.0 * h);
            assert!((fd - m.g[i]).abs() < 1e-6, "{i}: {fd} vs {}", m.g[i]);
        }
    }
}
