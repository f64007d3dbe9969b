//! Obstacles moved in a session (`Session::move_obstacle_by`) under cables and flat cables: a
//! frictionless equilibrium does not depend on the path, so the moved obstacle's equilibrium
//! must be the one the scene reaches when the supports move the other way instead — the
//! reference is an independent solve by support moves, not the edit's own output.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};

/// A cable 1 m long clamped at both ends 1 m apart (taut: it sags by 2 mm under its weight,
/// in its plane), with `obstacle` (a TOML `shape` table), model `model`. Taut, its
/// equilibria are unique: a slack cable lifted by a bar swings out of its plane to one side
/// or the other (measured: mirror images 0.2 m apart), so that two paths may end on either.
fn scene(model: &str, obstacle: &str) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
model = "{model}"
elements = 50
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 2.0e8, poisson = 0.4, density = 1400.0 }}
supports = [ {{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }} ]
[[obstacles]]
name = "bar"
shape = {obstacle}
[contact]
activation = 1e-4
"#
    ))
    .unwrap()
}

fn cold(model: &str, obstacle: &str) -> Session {
    let s = Session::new(scene(model, obstacle)).unwrap();
    assert!(s.report(0).converged(), "{model}");
    s
}

/// A saved scene solved again: the loads, then its motion stages (the supports' moves).
fn resolved(session: &Session) -> Session {
    let mut s = Session::new(session.saved()).unwrap();
    for step in 1..=s.motion_steps() {
        assert!(s.run_motion_step(step).converged, "step {step}");
    }
    s
}

/// The reference for an obstacle moved by `shift` (m): the same scene with the obstacle where
/// it was and both clamps moved by −`shift` instead (by support moves, not the obstacle
/// code), the result shifted back by `shift`. Gravity is uniform, so only the relative
/// placement of cable and obstacle matters.
fn moved_clamps(model: &str, obstacle: &str, shift: Vec3) -> Vec<Vec3> {
    let mut s = cold(model, obstacle);
    for support in [0, 1] {
        let r = s
            .move_support_by(0, support, Vec3::zeros(), -shift)
            .unwrap();
        assert!(r.converged, "{model}: clamp {support}: {:?}", r.reason);
    }
    positions(&s).iter().map(|p| p + shift).collect()
}

fn positions(session: &Session) -> Vec<Vec3> {
    vec3s(&session.results(0, None, 1.0, 1).rods[0].positions)
}

fn vec3s(points: &[[f64; 3]]) -> Vec<Vec3> {
    points.iter().map(|p| Vec3::from(*p)).collect()
}

fn gap(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

fn bar(x: f64, z: f64) -> String {
    format!(
        r#"{{ kind = "cylinder", point = [{x}, 0.0, {z}], axis = [0.0, 1.0, 0.0], radius = 0.02 }}"#
    )
}

/// The lowest point (m) of the cable.
fn lowest(p: &[Vec3]) -> f64 {
    p.iter().map(|p| p.z).fold(f64::INFINITY, f64::min)
}

#[test]
fn a_bar_pushed_up_under_a_taut_cable_lands_where_the_clamps_moved_the_other_way_do() {
    for model in ["der", "cosserat", "se3"] {
        // The bar starts below the cable (no contact), rises into it and lifts it by 4 cm,
        // slides along it, turns about its axis point (a round bar: the same bar), and lets
        // it down again.
        let mut session = cold(model, &bar(0.45, -0.05));
        let free = positions(&session);
        assert!(
            lowest(&free) > -0.02,
            "{model}: the cable hangs clear of the bar"
        );
        let moves = [
            (Vec3::zeros(), Vec3::new(0.0, 0.0, 0.07)),
            (Vec3::zeros(), Vec3::new(-0.15, 0.0, 0.0)),
            (Vec3::new(0.0, 0.3, 0.0), Vec3::zeros()),
        ];
        let mut total = Vec3::zeros();
        for (turn, shift) in moves {
            let r = session.move_obstacle_by(0, turn, shift).unwrap();
            assert!(r.converged, "{model}: {:?}", r.reason);
            assert!(r.stable, "{model}");
            total += shift;
            let (x, z) = (0.45 + total.x, -0.05 + total.z);
            let a = positions(&session);
            let b = moved_clamps(model, &bar(0.45, -0.05), total);
            let d = gap(&a, &b);
            // The cable rests on top of the bar (radius 0.02, cable radius 0.003): its
            // highest vertex at most a little above the top (a vertex on the top, its
            // neighbours touching), at least the sagitta of an element below (the top between
            // two touching vertices).
            let top = a.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
            println!(
                "{model}: bar at ({x}, {z}): edited vs cold {d:.2e} m, {} iterations, highest point {top:.5} m",
                r.iterations
            );
            assert!(d < 1e-7, "{model}: {d:e} m from the clamps moved instead");
            assert!(top < z + 0.0235 && top > z + 0.015, "{model}: {top}");
            // The saved scene has the moved bar and re-solves to the same shape.
            // The saved scene keeps the bar where the file has it and moves it by a motion
            // stage: it re-solves to the same shape.
            let ds = gap(&a, &positions(&resolved(&session)));
            assert!(ds < 1e-7, "{model}: saved scene {ds:e}");
        }
        let r = session
            .move_obstacle_by(0, Vec3::zeros(), Vec3::new(0.15, 0.0, -0.07))
            .unwrap();
        assert!(r.converged, "{model}: {:?}", r.reason);
        let d = gap(&positions(&session), &free);
        println!("{model}: bar back below: {d:.2e} m from the free cable");
        assert!(d < 1e-7, "{model}: {d:e}");
    }
}

#[test]
fn a_ring_slid_along_the_cable_carries_it_the_same_by_either_path() {
    // A grommet the cable runs through (frictionless), lifted and slid along: the equilibrium
    // is the same whichever way the ring got there (no cold solve can thread the ring where
    // it ends). Its tube (8 mm) is thicker than half an element, so that no edge slips
    // through between two vertices.
    let ring = r#"{ kind = "torus", center = [0.3, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = 0.025, tube_radius = 0.008 }"#;
    let mut one = cold("der", ring);
    let r = one
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(0.2, 0.0, 0.03))
        .unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let mut two = cold("der", ring);
    for shift in [Vec3::new(0.0, 0.0, 0.03), Vec3::new(0.2, 0.0, 0.0)] {
        let r = two.move_obstacle_by(0, Vec3::zeros(), shift).unwrap();
        assert!(r.converged, "{:?}", r.reason);
    }
    let (a, b) = (positions(&one), positions(&two));
    let d = gap(&a, &b);
    // The ring lifted the cable: at x = 0.5 it rests on the bottom of the hole (centre
    // 0.03, hole radius 0.017, cable radius 0.003: z ≈ 0.016).
    let mid = a[25];
    println!(
        "ring: one move vs two {d:.2e} m, {} iterations, cable at x = {:.3}: z = {:.4}",
        r.iterations, mid.x, mid.z
    );
    assert!(d < 1e-7, "{d:e}");
    assert!((mid.z - 0.016).abs() < 2e-3, "{mid:?}");
}

#[test]
fn bad_obstacle_moves_are_refused_by_name_and_keep_the_equilibrium() {
    let mut session = cold("der", &bar(0.0, -0.05));
    let before = positions(&session);
    let e = session
        .move_obstacle_by(1, Vec3::zeros(), Vec3::new(0.0, 0.0, 0.1))
        .unwrap_err();
    assert!(e.to_string().contains("obstacles[1]"), "{e}");
    let e = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(f64::NAN, 0.0, 0.0))
        .unwrap_err();
    assert!(
        e.to_string().contains("obstacles[0]") && e.to_string().contains("finite"),
        "{e}"
    );
    let e = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(1e6, 0.0, 0.0))
        .unwrap_err();
    assert!(e.to_string().contains("too large"), "{e}");
    // Pushed up into the clamped start: the clamp's vertex is in the way.
    let r = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(0.0, 0.0, 0.05))
        .unwrap();
    assert!(!r.converged);
    let why = r.reason.clone().unwrap_or_default();
    assert!(why.contains("held vertex 0"), "{why}");
    assert_eq!(positions(&session), before, "the equilibrium is kept");
    assert_eq!(
        session.saved().obstacles[0].shape,
        scene("der", &bar(0.0, -0.05)).obstacles[0].shape,
        "the bar stays where it was"
    );
}

#[test]
fn a_motion_stage_moves_an_obstacle_and_bad_stages_are_refused_by_name() {
    let stage = |fields: &str| -> Scene {
        let mut s: Scene = scene("der", &bar(0.45, -0.05));
        let extra: Scene = toml::from_str(&format!(
            "[[motion]]\n{fields}\ntranslate = [0.0, 0.0, 0.07]\nsteps = 2\n"
        ))
        .unwrap();
        s.motion = extra.motion;
        s
    };
    let mut s = Session::new(stage("obstacle = 0")).unwrap();
    for step in 1..=s.motion_steps() {
        assert!(s.run_motion_step(step).converged, "step {step}");
    }
    let d = gap(
        &positions(&s),
        &moved_clamps("der", &bar(0.45, -0.05), Vec3::new(0.0, 0.0, 0.07)),
    );
    println!("motion stage: {d:.2e} m from the clamps moved instead");
    assert!(d < 1e-7, "{d:e}");
    let c = s.obstacle_reference(0).unwrap();
    assert!((c - Vec3::new(0.45, 0.0, 0.02)).norm() < 1e-15, "{c:?}");
    for (fields, path, words) in [
        ("obstacle = 1", "motion[0].obstacle", "must be < 1"),
        ("obstacle = 0\nrod = 0", "motion[0].obstacle", "alone"),
    ] {
        let e = stage(fields).compile().unwrap_err().to_string();
        assert!(e.contains(path) && e.contains(words), "{fields}: {e}");
    }
}

// ---- Flat cables: an obstacle moved under a mid-edge shell strip clamped at both ends ----
//
// The strip's vertices the obstacle sweeps are carried along and the strip re-solves; the
// reference is again the same scene with the obstacle where it was and both clamps moved the
// other way (clamp moves), shifted back.

/// A strip 0.4 m × 20 mm × 0.3 mm (40 × 2 uniform elements) lying in y = 0 along x, its
/// edges at x = 0 and x = L clamped (taut: it sags under its weight along −y, its normal),
/// over a frictionless round bar across its width (along z) whose top is `clearance` (m)
/// below it. Contact acts at the strip's vertices: the bar (40 mm across) is four elements
/// wide, so that it cannot pass between two vertices.
fn strip_scene(clearance: f64) -> Scene {
    let radius = 0.02;
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[shells]]
name = "flat"
length = 0.4
width = 0.02
thickness = 0.3e-3
material = {{ young = 2.0e9, poisson = 0.3, density = 1400.0 }}
elements = 40
width_elements = 2
grading = {{ kind = "uniform" }}
clamps = [{{ edge = "start" }}, {{ edge = "end" }}]
[[obstacles]]
name = "bar"
friction = 0.0
shape = {{ kind = "cylinder", point = [0.18, {}, 0.0], axis = [0.0, 0.0, 1.0], radius = {radius} }}
[contact]
activation = 1e-5
"#,
        -clearance - radius
    ))
    .unwrap()
}

fn strip_positions(session: &Session) -> Vec<Vec3> {
    vec3s(&session.results(0, None, 1.0, 1).shells[0].positions)
}

fn cold_strip() -> Session {
    let s = Session::new(strip_scene(0.004)).unwrap();
    assert!(s.shell_runs()[0].report().converged());
    s
}

/// The clamps moved by −`shift` (clamp moves, not the obstacle code), shifted back. The two
/// clamps take turns by eighths: one clamp moved a whole slide alone would stretch the taut
/// strip by its length.
fn moved_strip_clamps(shift: Vec3) -> Vec<Vec3> {
    let mut s = cold_strip();
    for _ in 0..8 {
        for clamp in [0, 1] {
            let r = s
                .move_shell_clamp_by(0, clamp, Vec3::zeros(), -shift / 8.0)
                .unwrap();
            assert!(r.converged, "clamp {clamp}: {:?}", r.reason);
        }
    }
    strip_positions(&s).iter().map(|p| p + shift).collect()
}

#[test]
fn a_bar_lifted_under_a_flat_cable_lands_where_the_clamps_lowered_the_other_way_do() {
    let mut session = cold_strip();
    let free = strip_positions(&session);
    let lowest = free.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
    assert!(
        lowest > -0.004,
        "the strip hangs clear of the bar: {lowest}"
    );
    let mut total = Vec3::zeros();
    // Up 1.2 cm into the strip (its middle lifted by 8 mm), then slid 4 cm along it.
    for shift in [Vec3::new(0.0, 0.012, 0.0), Vec3::new(0.04, 0.0, 0.0)] {
        let r = session.move_obstacle_by(0, Vec3::zeros(), shift).unwrap();
        assert!(r.converged, "{:?}", r.reason);
        total += shift;
        let a = strip_positions(&session);
        let d = gap(&a, &moved_strip_clamps(total));
        // The strip rests on the bar's top (y = total.y − 0.004) at h/2 = 0.15 mm.
        let top = a.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
        let bar_top = total.y - 0.004;
        println!(
            "bar moved by {total:?}: edited vs clamps moved {d:.2e} m, {} iterations, strip's \
             highest point {top:.5} m over the bar's top {bar_top:.5} m",
            r.iterations
        );
        assert!(d < 1e-7, "{d:e} m from the clamps moved instead");
        assert!(top > bar_top && top < bar_top + 1e-3, "{top}");
        // The saved scene keeps the bar where the file has it and moves it by a motion stage.
        let ds = gap(&a, &strip_positions(&resolved(&session)));
        assert!(ds < 1e-7, "saved scene {ds:e}");
    }
    // Back where it started: the free strip again.
    let r = session.move_obstacle_by(0, Vec3::zeros(), -total).unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let d = gap(&strip_positions(&session), &free);
    println!("bar back: {d:.2e} m from the free strip");
    assert!(d < 1e-7, "{d:e}");
}

#[test]
fn a_bar_pushed_into_a_flat_cables_clamped_edge_is_refused_and_keeps_the_equilibrium() {
    let mut session = cold_strip();
    let before = strip_positions(&session);
    // Slid under the clamped start, then lifted into it: the clamped edge is in the way.
    let r = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(-0.18, 0.0, 0.0))
        .unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let under = strip_positions(&session);
    let r = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(0.0, 0.02, 0.0))
        .unwrap();
    assert!(!r.converged);
    let why = r.reason.clone().unwrap_or_default();
    assert!(why.contains("clamped edge of strip \"flat\""), "{why}");
    assert!(gap(&strip_positions(&session), &under) == 0.0);
    assert!(gap(&under, &before) < 1e-3);
}
