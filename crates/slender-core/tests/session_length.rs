//! Paying out and pulling in cable in a session (`Session::set_rod_length`): the hanging
//! cable must match the elastic catenary of its new length, and the same scene solved cold.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};

/// A thin rubber-like cord (d = 0.5 mm, E = 30 MPa, ρ = 1200 kg/m³), `elements` elements,
/// straight along x from the origin, `length` m long, held at both ends by `end` supports.
fn cord(length: f64, elements: usize, end: &str) -> Scene {
    cord_model(length, elements, end, "der")
}

/// As [`cord`], with the rod model `model`.
fn cord_model(length: f64, elements: usize, end: &str, model: &str) -> Scene {
    // Pins leave the cord free to spin about its axis: a twist hold at the start stops that.
    let extra = if end == "pin" {
        r#", { kind = "twist_hold", vertex = "start" }"#
    } else {
        ""
    };
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cord"
model = "{model}"
elements = {elements}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = {length} }}
section = {{ shape = "circle", diameter = 5e-4 }}
material = {{ young = 3e7, poisson = 0.45, density = 1200.0 }}
supports = [ {{ kind = "{end}", vertex = "start" }}, {{ kind = "{end}", vertex = "end" }}{extra} ]
"#
    ))
    .unwrap()
}

/// Sag (m) at mid-length of an elastic catenary (Irvine, *Cable Structures*, §2.2): rest
/// length `l0` (m), weight `q` per rest length (N/m), axial stiffness `ea` (N), supports at the
/// same height `span` (m) apart. The horizontal tension H solves
/// span = H·l0/EA + (2H/q)·asinh(q·l0/(2H)) (bisection on log H).
fn elastic_catenary_sag(l0: f64, q: f64, ea: f64, span: f64) -> f64 {
    let span_of = |h: f64| h * l0 / ea + 2.0 * h / q * (q * l0 / (2.0 * h)).asinh();
    let (mut lo, mut hi) = (1e-12_f64, 1e6_f64);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if span_of(mid) < span {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let h = (lo * hi).sqrt();
    let v = 0.5 * q * l0;
    q * l0 * l0 / (8.0 * ea) + h / q * ((1.0 + (v / h).powi(2)).sqrt() - 1.0)
}

fn mid_height(session: &Session, vertex: usize) -> f64 {
    session.results(0, None, 1.0, 1).rods[0].positions[vertex][2]
}

fn positions(session: &Session) -> Vec<Vec3> {
    session.results(0, None, 1.0, 1).rods[0]
        .positions
        .iter()
        .map(|p| Vec3::from(*p))
        .collect()
}

#[test]
fn a_cord_paid_out_and_pulled_in_hangs_as_the_elastic_catenary_of_its_length() {
    let d: f64 = 5e-4;
    let area = std::f64::consts::FRAC_PI_4 * d * d;
    let (q, ea) = (1200.0 * area * 9.81, 3e7 * area);
    let span = 0.8;
    // Pinned ends: a pin holds its vertex and leaves the tangent free, as a catenary's ends.
    let mut session = Session::new(cord(1.0, 80, "pin")).unwrap_or_else(|e| panic!("{e}"));
    let r = session
        .move_support_by(0, 1, Vec3::zeros(), Vec3::new(span - 1.0, 0.0, 0.0))
        .unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let check = |session: &Session, l0: f64| {
        let sag = -mid_height(session, 40);
        let exact = elastic_catenary_sag(l0, q, ea, span);
        let rel = (sag - exact).abs() / exact;
        println!("length {l0} m: sag {sag:.6e} m, elastic catenary {exact:.6e} m, rel {rel:.2e}");
        // Bending (EI·κ against the tension, a layer of √(EI/H) ≈ 1 cm at the pins) and the
        // 80 chords of the discretization are all that differ from the catenary (measured:
        // 5e-5 to 2.1e-4).
        assert!(rel < 1e-3, "length {l0}: sag {sag} vs {exact} ({rel:.2e})");
    };
    check(&session, 1.0);
    for l0 in [1.25, 1.1, 0.9] {
        let r = session.set_rod_length(0, l0).unwrap();
        assert!(r.converged, "length {l0}: {:?}", r.reason);
        assert!(r.stable, "length {l0}: unstable");
        assert_eq!(session.rod_length(0), Some(l0));
        check(&session, l0);
    }
    // Pulled in to 0.9 of the span: the cord is stretched taut, its tension EA·(span/l0 − 1)
    // (its sag under that tension, 0.3 mm, lengthens it by 3e-6 of the stretch).
    let l0 = 0.72;
    let r = session.set_rod_length(0, l0).unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let pull = session.results(0, None, 1.0, 1).rods[0].supports[1].force[0].abs();
    let exact = ea * (span / l0 - 1.0);
    println!("length {l0} m: end force {pull:.6e} N, stretched cord {exact:.6e} N");
    assert!((pull - exact).abs() < 1e-4 * exact, "{pull} vs {exact}");
}

#[test]
fn a_length_edit_lands_where_the_scene_of_that_length_solves_cold_and_saves_to_it() {
    for model in ["der", "cosserat", "se3"] {
        edited_matches_cold(model);
    }
}

fn edited_matches_cold(model: &str) {
    // Clamped ends: the edit must also give the clamped end edges their new rest length.
    let mut session = Session::new(cord_model(1.0, 60, "clamp", model)).unwrap();
    let pose = Vec3::new(-0.3, 0.1, 0.05);
    let turn = Vec3::new(0.0, 0.0, 0.4);
    assert!(session.move_support_by(0, 1, turn, pose).unwrap().converged);
    for l0 in [1.3, 0.95] {
        let r = session.set_rod_length(0, l0).unwrap();
        assert!(r.converged, "length {l0}: {:?}", r.reason);
        // The same cord built at that length, its end moved to the same place cold.
        let mut cold = Session::new(cord_model(l0, 60, "clamp", model)).unwrap();
        let to = Vec3::new(1.0 - l0, 0.0, 0.0) + pose;
        assert!(cold.move_support_by(0, 1, turn, to).unwrap().converged);
        let (a, b) = (positions(&session), positions(&cold));
        let gap = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        println!("{model}, length {l0} m: edited vs cold, largest vertex distance {gap:.2e} m");
        assert!(
            gap < 1e-6,
            "{model}, length {l0}: {gap:e} m from the cold solve"
        );
        // The saved scene has the new length and re-solves to the same shape.
        let mut saved = Session::new(session.saved()).unwrap();
        for step in 1..=saved.motion_steps() {
            assert!(saved.run_motion_step(step).converged, "step {step}");
        }
        assert_eq!(saved.rod_length(0), Some(l0));
        let back = positions(&saved);
        let gap = a
            .iter()
            .zip(&back)
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        assert!(
            gap < 1e-6,
            "{model}, length {l0}: saved scene {gap:e} m away"
        );
    }
}

#[test]
fn bad_length_edits_name_the_field_and_change_nothing() {
    let mut session = Session::new(cord(1.0, 20, "clamp")).unwrap();
    let before = positions(&session);
    for (rod, length, path) in [
        (0, f64::NAN, "rods[0].centerline.length"),
        (0, -1.0, "rods[0].centerline.length"),
        (0, 0.0, "rods[0].centerline.length"),
        (0, 11.0, "rods[0].centerline.length"),
        (0, 0.05, "rods[0].centerline.length"),
        (3, 1.0, "rods[3]"),
    ] {
        let e = session.set_rod_length(rod, length).unwrap_err();
        assert_eq!(e.path, path, "{length}: {e}");
    }
    let mut arc: Scene = toml::from_str(
        r#"
[[rods]]
elements = 20
centerline = { kind = "arc", start = [0.0, 0.0, 0.0], tangent = [1.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0], radius = 0.2, length = 0.5 }
section = { shape = "circle", diameter = 0.005 }
material = { young = 1e8, poisson = 0.4, density = 1200.0 }
supports = [ { kind = "clamp", vertex = "start" } ]
"#,
    )
    .unwrap();
    arc.gravity = [0.0, 0.0, -9.81];
    let e = Session::new(arc)
        .unwrap()
        .set_rod_length(0, 0.6)
        .unwrap_err();
    assert_eq!(e.path, "rods[0].centerline");
    // A clip given by arc length stays on the same point of the cable: its `at` scales.
    let mut clipped = cord(1.0, 20, "clamp");
    clipped.rods[0]
        .supports
        .push(toml::from_str("kind = \"clip\"\nat = 0.8").unwrap());
    let mut s = Session::new(clipped).unwrap();
    let held = s.pose(0, 2).unwrap().position;
    let r = s.set_rod_length(0, 0.7).unwrap();
    assert!(r.converged, "{:?}", r.reason);
    assert_eq!(s.spec().rods[0].supports[2].at, Some(0.8 * 0.7));
    assert_eq!(s.pose(0, 2).unwrap().position, held);
    assert_eq!(positions(&session), before);
}

/// Complete elliptic integrals K(k), E(k) of modulus k (arithmetic–geometric mean).
fn elliptic_ke(k: f64) -> (f64, f64) {
    let (mut a, mut b) = (1.0_f64, (1.0 - k * k).sqrt());
    let mut c_sum = 0.5 * k * k;
    let mut pow = 0.5;
    for _ in 0..40 {
        let c = 0.5 * (a - b);
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        pow *= 2.0;
        c_sum += pow * c * c;
        a = an;
        b = bn;
    }
    let kk = std::f64::consts::FRAC_PI_2 / a;
    (kk, kk * (1.0 - c_sum))
}

/// The modulus k and K(k) of the Euler elastica whose chord is `ratio` of its length:
/// 2E(k)/K(k) − 1 = ratio (bisection).
fn clamped_elastica(ratio: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (1e-9, 1.0 - 1e-12);
    for _ in 0..100 {
        let k = 0.5 * (lo + hi);
        let (kk, ee) = elliptic_ke(k);
        if 2.0 * ee / kk - 1.0 > ratio {
            lo = k;
        } else {
            hi = k;
        }
    }
    let k = 0.5 * (lo + hi);
    (k, elliptic_ke(k).0)
}

#[test]
fn a_taut_cable_paid_out_between_clamps_buckles_into_the_clamped_elastica() {
    // Weightless 6 mm cable (E = 1 GPa), clamped at both ends 1 m apart along x, straight and
    // taut; paying out cable compresses it past its Euler load and it must buckle into the
    // first clamped–clamped elastica: four quarter-waves of the Euler elastica, with
    // chord/length = 2E(k)/K(k) − 1, midpoint deflection k·L/K(k) and end force
    // 16·K(k)²·EI/L² (k = sin(α/2), α the largest angle to the chord).
    let (e, d) = (1e9_f64, 6e-3_f64);
    let ei = e * std::f64::consts::PI * d.powi(4) / 64.0;
    let mut scene = cord(1.0, 100, "clamp");
    scene.gravity = [0.0; 3];
    scene.rods[0].section = toml::from_str(
        r#"shape = "circle"
diameter = 6e-3"#,
    )
    .unwrap();
    scene.rods[0].material =
        Some(toml::from_str("young = 1e9\npoisson = 0.4\ndensity = 1400.0").unwrap());
    let mut session = Session::new(scene).unwrap();
    for l0 in [1.02, 1.05, 1.1] {
        let r = session.set_rod_length(0, l0).unwrap();
        assert!(r.converged, "length {l0}: {:?}", r.reason);
        assert!(r.stable, "length {l0}: unstable");
        // The elastica of the stretched length l0·(1 − P/EA): at 2 % of slack the end force
        // shortens the cable by 8.6e-5 of its length, which moves the deflection by 2e-3.
        let ea = e * std::f64::consts::FRAC_PI_4 * d * d;
        let (mut deflection, mut force) = (0.0, 0.0);
        for _ in 0..20 {
            let length = l0 * (1.0 - force / ea);
            let (k, kk) = clamped_elastica(1.0 / length);
            (deflection, force) = (k * length / kk, 16.0 * kk * kk * ei / (length * length));
        }
        let out = session.results(0, None, 1.0, 1);
        let rod = &out.rods[0];
        let mid = Vec3::from(rod.positions[50]);
        let measured = (mid.y * mid.y + mid.z * mid.z).sqrt();
        let push = rod.supports[1].force[0].abs();
        let (rd, rf) = (
            (measured - deflection).abs() / deflection,
            (push - force).abs() / force,
        );
        println!(
            "length {l0} m: midpoint deflection {measured:.6e} m (elastica {deflection:.6e}, \
             rel {rd:.1e}), end force {push:.6e} N (elastica {force:.6e}, rel {rf:.1e}), \
             {} iterations",
            r.iterations
        );
        // Measured: 2e-4 to 3.4e-4 (100 elements).
        assert!(rd < 1e-3 && rf < 1e-3, "length {l0}");
    }
}
