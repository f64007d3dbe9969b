//! One contact radius per rod with self-contact (every rod of the scene in one structure):
//! a thin cable sagging onto a thick one rests with their centerlines r_a + r_b apart (up to
//! the activation distance), measured here from the result positions; a thin and a thick rod
//! lying on one floor each rest at its own radius above it.

use slender_core::scene::{Scene, Session, TimeRun};

const G: f64 = 9.81;
/// Activation distance ĝ (m) of both scenes.
const ACTIVATION: f64 = 1e-5;

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

/// Closest distance (m) from point `x` to segment [p, q] (the projection clamped to it).
fn point_segment_distance(x: [f64; 3], p: [f64; 3], q: [f64; 3]) -> f64 {
    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    let r = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
    let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let t = ((r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / dd).clamp(0.0, 1.0);
    let e = [r[0] - t * d[0], r[1] - t * d[1], r[2] - t * d[2]];
    (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
}

/// Closest distance (m) between segments [p0, p1] and [q0, q1], by another route than the
/// core's clamped solve (`contact::segment_distance`): |p(s) − q(t)|² is a convex quadratic
/// on the unit square, so its minimum is the interior stationary point when that lies in the
/// square, and otherwise on an edge of it — one of the four endpoint-to-segment distances.
fn segment_distance(p0: [f64; 3], p1: [f64; 3], q0: [f64; 3], q1: [f64; 3]) -> f64 {
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (d1, d2, r) = (sub(p1, p0), sub(q1, q0), sub(p0, q0));
    // Stationary point: [a −b; −b e] (s, t) = (−c, f).
    let (a, b, e) = (dot(d1, d1), dot(d1, d2), dot(d2, d2));
    let (c, f) = (dot(d1, r), dot(d2, r));
    let det = a * e - b * b;
    if det > 1e-12 * a * e {
        let s = (b * f - c * e) / det;
        let t = (a * f - b * c) / det;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            let g = [
                r[0] + s * d1[0] - t * d2[0],
                r[1] + s * d1[1] - t * d2[1],
                r[2] + s * d1[2] - t * d2[2],
            ];
            return dot(g, g).sqrt();
        }
    }
    point_segment_distance(p0, q0, q1)
        .min(point_segment_distance(p1, q0, q1))
        .min(point_segment_distance(q0, p0, p1))
        .min(point_segment_distance(q1, p0, p1))
}

/// Closest distance (m) between two polylines.
fn polyline_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    let mut best = f64::INFINITY;
    for u in a.windows(2) {
        for v in b.windows(2) {
            best = best.min(segment_distance(u[0], u[1], v[0], v[1]));
        }
    }
    best
}

#[test]
fn a_thin_cable_sagging_onto_a_thick_one_rests_at_the_sum_of_their_radii() {
    // Thin: d = 4 mm, cantilevered along x; thick: d = 16 mm, clamped at both ends across
    // it, 10.5 mm below (0.5 mm of clearance at rest). The thin one sags ~18 mm at the
    // crossing under its weight, so it presses on the thick one.
    let (r_thin, r_thick) = (0.002, 0.008);
    let text = format!(
        r#"
gravity = [0.0, 0.0, -{G}]

[[rods]]
name = "thin"
elements = 30
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.1105], direction = [1.0, 0.0, 0.0], length = 0.6 }}
section = {{ shape = "circle", diameter = {} }}
material = {{ young = 5.0e9, poisson = 0.4, density = 1500.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}]

[[rods]]
name = "thick"
elements = 30
centerline = {{ kind = "straight", start = [0.31, -0.295, 0.1], direction = [0.0, 1.0, 0.0], length = 0.6 }}
section = {{ shape = "circle", diameter = {} }}
material = {{ young = 5.0e8, poisson = 0.4, density = 1500.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }}]

[contact]
self_contact = true
activation = {ACTIVATION}
"#,
        2.0 * r_thin,
        2.0 * r_thick
    );
    let s = Session::new(scene(&text)).expect("compiles");
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged, "{:?}", s.report(0).status);
    assert_eq!(r.structures.len(), 1, "self-contact: one structure");
    let pairs = r.segment_contacts.as_ref().expect("self-contact results");
    assert!(!pairs.is_empty(), "the cables do not touch");
    assert!(pairs.iter().all(|p| p.rod_a != p.rod_b));
    let distance = polyline_distance(&r.rods[0].positions, &r.rods[1].positions);
    let clearance = distance - (r_thin + r_thick);
    let mut pushed = 0.0;
    for p in pairs {
        pushed += if p.rod_a == "thin" {
            p.force_a[2]
        } else {
            p.force_b[2]
        };
    }
    println!(
        "thin (r = {r_thin} m) on thick (r = {r_thick} m): {} pairs, centerlines {distance:.9} m apart = r_a + r_b + {clearance:.3e} m (ĝ = {ACTIVATION:.0e}), reported min gap {:.3e} m, the thick cable pushes the thin one up with {pushed:.4} N",
        pairs.len(),
        r.min_segment_gap.unwrap(),
    );
    assert!(
        clearance > 0.0 && clearance < ACTIVATION,
        "centerlines {distance} m apart, r_a + r_b = {}",
        r_thin + r_thick
    );
    assert!(pushed > 0.0);
}

#[test]
fn a_thin_rod_and_a_thick_rod_on_one_floor_rest_at_their_own_radii() {
    // With self-contact both rods are one structure; each must keep its own radius from the
    // floor, not the structure's largest. Backward Euler from 1 mm above, damped to rest.
    let (r_thin, r_thick, length) = (0.001, 0.006, 0.2);
    let rod = |name: &str, y: f64, r: f64| {
        format!(
            r#"
[[rods]]
name = "{name}"
elements = 10
centerline = {{ kind = "straight", start = [0.0, {y}, {z}], direction = [1.0, 0.0, 0.0], length = {length} }}
section = {{ shape = "circle", diameter = {d} }}
material = {{ young = 2.0e11, poisson = 0.3, density = 7850.0 }}
"#,
            z = r + 0.001,
            d = 2.0 * r
        )
    };
    let text = format!(
        r#"
gravity = [0.0, 0.0, -{G}]
{}{}
[[obstacles]]
name = "floor"
friction = 0.3
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[contact]
self_contact = true
activation = {ACTIVATION}

[time]
dt = 1e-3
duration = 0.2
scheme = "backward_euler"
rayleigh_mass = 20.0
"#,
        rod("thin", -0.05, r_thin),
        rod("thick", 0.05, r_thick),
    );
    let compiled = scene(&text).compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    while !run.finished() {
        let r = run.step();
        assert!(r.converged, "{:?}", r.failure);
        assert!(run.frame(0).min_gap.unwrap() > 0.0);
    }
    let last = run.frame(1);
    let weight: f64 = [r_thin, r_thick]
        .iter()
        .map(|r| 7850.0 * std::f64::consts::PI * r * r * length * G)
        .sum();
    for (rod, r) in last.rods.iter().zip([r_thin, r_thick]) {
        let (low, high) = rod
            .positions
            .iter()
            .map(|p| p[2] - r)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), g| {
                (l.min(g), h.max(g))
            });
        let contacts = last.obstacles[0]
            .contacts
            .iter()
            .filter(|c| c.rod == rod.name)
            .count();
        println!(
            "{} (r = {r} m) at rest on the floor: {contacts} contacts, its surface {low:.3e} to {high:.3e} m above it (ĝ = {ACTIVATION:.0e})",
            rod.name
        );
        assert_eq!(contacts, 11, "{}: every vertex on the floor", rod.name);
        assert!(
            low > 0.0 && high < ACTIVATION,
            "{}: {low:e} .. {high:e}",
            rod.name
        );
    }
    let fz = last.obstacles[0].force[2];
    println!("floor force / weight − 1 = {:.2e}", fz / weight - 1.0);
    assert!((fz / weight - 1.0).abs() < 1e-6, "{fz} vs {weight}");
}
