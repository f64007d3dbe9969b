//! An obstacle moved under a flat cable (a mid-edge shell strip clamped at both ends) in a
//! session: the strip's vertices the obstacle sweeps are carried along and the strip
//! re-solves. The reference is independent of the obstacle code: the same scene with the
//! obstacle where it was and both clamps moved the other way (clamp moves), shifted back —
//! gravity is uniform, so only the relative placement of strip and obstacle matters, and a
//! frictionless equilibrium does not depend on the path.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session};

/// A strip 0.4 m × 20 mm × 0.3 mm (40 × 2 uniform elements) lying in y = 0 along x, its
/// edges at x = 0 and x = L clamped (taut: it sags under its weight along −y, its normal),
/// over a frictionless round bar across its width (along z) whose top is `clearance` (m)
/// below it. Contact acts at the strip's vertices: the bar (40 mm across) is four elements
/// wide, so that it cannot pass between two vertices.
fn scene(clearance: f64) -> Scene {
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

fn positions(session: &Session) -> Vec<Vec3> {
    session.results(0, None, 1.0, 1).shells[0]
        .positions
        .iter()
        .map(|p| Vec3::from(*p))
        .collect()
}

fn gap(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

fn cold() -> Session {
    let s = Session::new(scene(0.004)).unwrap();
    assert!(s.shell_runs()[0].report().converged());
    s
}

/// The clamps moved by −`shift` (clamp moves, not the obstacle code), shifted back. The two
/// clamps take turns by eighths: one clamp moved a whole slide alone would stretch the taut
/// strip by its length.
fn moved_clamps(shift: Vec3) -> Vec<Vec3> {
    let mut s = cold();
    for _ in 0..8 {
        for clamp in [0, 1] {
            let r = s
                .move_shell_clamp_by(0, clamp, Vec3::zeros(), -shift / 8.0)
                .unwrap();
            assert!(r.converged, "clamp {clamp}: {:?}", r.reason);
        }
    }
    positions(&s).iter().map(|p| p + shift).collect()
}

#[test]
fn a_bar_lifted_under_a_flat_cable_lands_where_the_clamps_lowered_the_other_way_do() {
    let mut session = cold();
    let free = positions(&session);
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
        let a = positions(&session);
        let d = gap(&a, &moved_clamps(total));
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
        let mut saved = Session::new(session.saved()).unwrap();
        for step in 1..=saved.motion_steps() {
            assert!(saved.run_motion_step(step).converged, "step {step}");
        }
        let ds = gap(&a, &positions(&saved));
        assert!(ds < 1e-7, "saved scene {ds:e}");
    }
    // Back where it started: the free strip again.
    let r = session.move_obstacle_by(0, Vec3::zeros(), -total).unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let d = gap(&positions(&session), &free);
    println!("bar back: {d:.2e} m from the free strip");
    assert!(d < 1e-7, "{d:e}");
}

#[test]
fn a_bar_pushed_into_a_clamped_edge_is_refused_and_keeps_the_equilibrium() {
    let mut session = cold();
    let before = positions(&session);
    // Slid under the clamped start, then lifted into it: the clamped edge is in the way.
    let r = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(-0.18, 0.0, 0.0))
        .unwrap();
    assert!(r.converged, "{:?}", r.reason);
    let under = positions(&session);
    let r = session
        .move_obstacle_by(0, Vec3::zeros(), Vec3::new(0.0, 0.02, 0.0))
        .unwrap();
    assert!(!r.converged);
    let why = r.reason.clone().unwrap_or_default();
    assert!(why.contains("clamped edge of strip \"flat\""), "{why}");
    assert!(gap(&positions(&session), &under) == 0.0);
    assert!(gap(&under, &before) < 1e-3);
}
