//! Shell strips in scenes with clamps at both ends, moved through `Session` (issue items:
//! shell supports in scene files, strip drags): the moved clamp against closed forms of the
//! strip's beam limit (clamped–guided bending 12EI/L³, Saint-Venant torsion GJ/L of a thin
//! rectangle), a move and its reverse, save → reload, and bad input named by field.
//!
//! Run with `cargo test -p slender-core --release --test integration shell_scene_clamps::`.

use slender_core::assembly::TermSet;
use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, Session, StripModel};

const LENGTH: f64 = 0.2;
const WIDTH: f64 = 0.01;
const THICKNESS: f64 = 1e-3;
const YOUNG: f64 = 5e9;

/// A strip clamped at both ends, no gravity, ν = `poisson`, `model`, n_L × n_W elements.
fn strip(model: &str, poisson: f64, n_length: usize, n_width: usize) -> Scene {
    toml::from_str(&format!(
        r#"
[[shells]]
name = "strip"
model = "{model}"
length = {LENGTH}
width = {WIDTH}
thickness = {THICKNESS}
material = {{ young = {YOUNG}, poisson = {poisson}, density = 1000.0 }}
elements = {n_length}
width_elements = {n_width}
grading = {{ kind = "uniform" }}
clamps = [{{ edge = "start" }}, {{ edge = "end" }}]
"#
    ))
    .expect("scene")
}

/// Elastic energy (J) of the strip's current equilibrium (no loads: all of it is internal).
fn energy(session: &Session) -> f64 {
    let run = &session.shell_runs()[0];
    match &session.compiled().shells[0].model {
        StripModel::Midedge(s) => {
            s.energy_terms(run.midedge_state().expect("mid-edge"), 1.0, TermSet::ALL)
        }
        StripModel::Bspline(s) => {
            s.energy_terms(run.bspline_state().expect("B-spline"), 1.0, TermSet::ALL)
        }
    }
}

fn positions(session: &Session) -> Vec<[f64; 3]> {
    session.results(0, None, 1.0, 1).shells[0].positions.clone()
}

fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (Vec3::from(*p) - Vec3::from(*q)).norm())
        .fold(0.0, f64::max)
}

/// End clamp moved across the strip's thickness by δ ≪ h (clamped–guided beam): the strain
/// energy is ½ k δ² with k = 12 E I / L³, E I = E w h³ / 12 (ν = 0: plate and beam agree).
#[test]
fn a_laterally_moved_end_clamp_needs_the_clamped_guided_beam_force() {
    let ei = YOUNG * WIDTH * THICKNESS.powi(3) / 12.0;
    let k_beam = 12.0 * ei / LENGTH.powi(3);
    for (model, n_length, n_width, tol) in [("midedge", 30, 2, 0.02), ("bspline", 16, 1, 0.005)] {
        let mut s = Session::new(strip(model, 0.0, n_length, n_width)).expect("session");
        let delta = 1e-2 * THICKNESS;
        let r = s
            .move_shell_clamp_by(0, 1, Vec3::zeros(), Vec3::new(0.0, delta, 0.0))
            .expect("edit");
        assert!(r.converged, "{model}: {r:?}");
        let k = 2.0 * energy(&s) / (delta * delta);
        let err = k / k_beam - 1.0;
        eprintln!("{model}: k = {k:.6e} N/m, 12EI/L³ = {k_beam:.6e}, error {err:+.3e}");
        assert!(err.abs() < tol, "{model}: {err:+.3e}");
    }
}

/// End clamp turned about the strip's axis by a small θ: the energy is ½ (GJ/L) θ² with the
/// thin rectangle's GJ = G w h³ / 3 (Kirchhoff plate torsion; the clamps' warping restraint
/// adds ≈ w/L·√(E/(48G))·… ≈ 1–2 % at w/L = 0.05, the narrow strip's edge zone of width ~h
/// removes ≈ 0.63 h/w, so the tolerance is 10 %).
#[test]
fn an_end_clamp_turned_about_the_axis_needs_the_thin_rectangle_torque() {
    let nu = 0.3;
    let g = YOUNG / (2.0 * (1.0 + nu));
    let gj = g * WIDTH * THICKNESS.powi(3) / 3.0;
    let k_beam = gj / LENGTH;
    for (model, n_length, n_width) in [("midedge", 30, 4), ("bspline", 16, 2)] {
        let mut s = Session::new(strip(model, nu, n_length, n_width)).expect("session");
        let theta = 1e-3;
        let r = s
            .move_shell_clamp_by(0, 1, Vec3::new(theta, 0.0, 0.0), Vec3::zeros())
            .expect("edit");
        assert!(r.converged, "{model}: {r:?}");
        let k = 2.0 * energy(&s) / (theta * theta);
        let err = k / k_beam - 1.0;
        eprintln!("{model}: T/θ = {k:.6e} N m, GJ/L = {k_beam:.6e}, error {err:+.3e}");
        assert!(err.abs() < 0.1, "{model}: {err:+.3e}");
    }
}

/// A flat cable sagging between its clamps (gravity across its thickness): a drag of the end
/// clamp (translation and rotation) and the reverse drag give back the start, and the
/// session's saved scene solves to the dragged equilibrium.
fn sagging(model: &str) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, -9.81, 0.0]
[[shells]]
name = "flat"
model = "{model}"
length = 0.3
width = 0.02
thickness = 3.0e-4
material = {{ young = 5.0e9, poisson = 0.3, density = 2000.0 }}
elements = 20
grading = {{ kind = "uniform" }}
clamps = [{{ edge = "start" }}, {{ edge = "end", offset = [-0.02, 0.01, 0.0] }}]
"#
    ))
    .expect("scene")
}

#[test]
fn moving_a_clamp_and_back_returns_to_the_start_and_the_saved_scene_reloads() {
    for model in ["midedge", "bspline"] {
        let mut s = Session::new(sagging(model)).expect("session");
        assert!(s.results(0, None, 1.0, 1).converged, "{model}");
        let start = positions(&s);
        let pose0 = s.shell_pose(0, 1).expect("the end clamp");
        assert!((pose0.position - Vec3::new(0.28, 0.01, 0.0)).norm() < 1e-15);
        let (rot, tr) = (Vec3::new(0.1, 0.0, 0.2), Vec3::new(-0.03, 0.02, 0.01));
        let r = s.move_shell_clamp_by(0, 1, rot, tr).expect("edit");
        assert!(r.converged, "{model}: {r:?}");
        let moved = positions(&s);
        assert!(max_distance(&moved, &start) > 1e-3, "{model}: it moved");
        // Save → reload: the same equilibrium.
        let saved = s.saved();
        let text = toml::to_string(&saved).expect("toml");
        let reloaded = Session::new(toml::from_str(&text).expect("parse")).expect("reload");
        let d = max_distance(&positions(&reloaded), &moved);
        eprintln!("{model}: saved and reloaded differs by {:.3e} L", d / 0.3);
        assert!(d < 1e-9 * 0.3, "{model}: {d:e}");
        // And back: the start.
        let r = s.move_shell_clamp(0, 1, pose0).expect("edit back");
        assert!(r.converged, "{model}: {r:?}");
        let d = max_distance(&positions(&s), &start);
        eprintln!("{model}: moved and back differs by {:.3e} L", d / 0.3);
        assert!(d < 1e-9 * 0.3, "{model}: {d:e}");
    }
}

/// A scene file's motion stage of a strip's clamp is the same path as a session edit.
#[test]
fn a_motion_stage_moves_the_clamp_as_the_session_edit_does() {
    let mut scene = sagging("midedge");
    scene.motion.push(toml::from_str(
        "shell = 0\nsupport = 1\ntranslate = [0.0, 0.03, 0.0]\nrotate = [0.0, 0.0, 0.3]\nsteps = 2",
    )
    .expect("stage"));
    let mut staged = Session::new(scene.clone()).expect("session");
    assert_eq!(staged.motion_steps(), 2);
    for k in 1..=2 {
        assert!(staged.run_motion_step(k).converged);
    }
    scene.motion.clear();
    let mut edited = Session::new(scene).expect("session");
    for _ in 0..2 {
        let r = edited
            .move_shell_clamp_by(0, 1, Vec3::new(0.0, 0.0, 0.15), Vec3::new(0.0, 0.015, 0.0))
            .expect("edit");
        assert!(r.converged, "{r:?}");
    }
    let d = max_distance(&positions(&staged), &positions(&edited));
    assert!(d < 1e-9 * 0.3, "{d:e}");
    let p = staged.shell_pose(0, 1).expect("clamp");
    assert!(
        (p.position - Vec3::new(0.28, 0.04, 0.0)).norm() < 1e-12,
        "{p:?}"
    );
}

/// A move that cannot converge keeps the last equilibrium and says so.
#[test]
fn a_move_that_does_not_converge_keeps_the_last_equilibrium() {
    let mut scene = sagging("bspline");
    scene.solver.max_iterations = 2;
    scene.solver.min_load_step = 0.2;
    let mut s = Session::new(scene).expect("session");
    let before = positions(&s);
    let pose = s.shell_pose(0, 1).expect("clamp");
    // Pulling the end 5 cm away from the start stretches a strip that is only 2 cm slack.
    let r = s
        .move_shell_clamp_by(0, 1, Vec3::zeros(), Vec3::new(0.05, 0.0, 0.0))
        .expect("edit");
    assert!(!r.converged, "{r:?}");
    assert!(r
        .reason
        .as_deref()
        .unwrap_or("")
        .contains("last equilibrium is kept"));
    assert_eq!(positions(&s), before);
    assert_eq!(s.shell_pose(0, 1), Some(pose));
}

fn error_of(text: &str) -> String {
    let scene: Scene = match toml::from_str(text) {
        Ok(s) => s,
        Err(e) => return format!("parse: {e}"),
    };
    match scene.compile() {
        Ok(_) => "accepted".into(),
        Err(e) => format!("{}: {}", e.path, e.message),
    }
}

const HEAD: &str = r#"
[[shells]]
length = 0.2
width = 0.01
thickness = 1e-3
material = { young = 5e9, poisson = 0.3, density = 1000.0 }
elements = 6
"#;

#[test]
fn bad_shell_supports_are_named_by_field() {
    let cases = [
        ("clamps = []", "shells[0].clamps: empty"),
        (
            r#"clamps = [{ edge = "end" }, { edge = "end" }]"#,
            "shells[0].clamps[1].edge",
        ),
        (
            r#"clamps = [{ edge = "start", offset = [nan, 0.0, 0.0] }]"#,
            "shells[0].clamps[0].offset",
        ),
        (
            r#"clamps = [{ edge = "start", rotate = [0.0, inf, 0.0] }]"#,
            "shells[0].clamps[0].rotate",
        ),
        (
            r#"clamps = [{ edge = "middle" }]"#,
            "unknown variant `middle`",
        ),
        (
            r#"clamps = [{ edge = "start", pose = 1 }]"#,
            "unknown field `pose`",
        ),
        (
            r#"support = "clamp_start"
clamps = [{ edge = "start" }]"#,
            "shells[0].support: give either",
        ),
        (
            r#"support = "clamp_end""#,
            "shells[0].support: \"clamp_end\"",
        ),
        (
            "forces = [{ station = 7, column = 0, force = [0.0, 1.0, 0.0] }]",
            "shells[0].forces[0].station: 7: off the strip; valid: 0..=6",
        ),
        (
            "forces = [{ station = 6, column = 3, force = [0.0, 1.0, 0.0] }]",
            "shells[0].forces[0].column: 3: off the strip",
        ),
        (
            "forces = [{ station = 6, column = 0, force = [nan, 1.0, 0.0] }]",
            "shells[0].forces[0].force",
        ),
        (
            "\n[[motion]]\nshell = 1\nsupport = 0",
            "motion[0].shell: 1: must be < 1",
        ),
        (
            "\n[[motion]]\nshell = 0\nsupport = 1",
            "motion[0].support: 1: must be < 1 (clamps of shell 0)",
        ),
        (
            "\n[[motion]]\nrod = 0\nshell = 0\nsupport = 0",
            "motion[0].shell: give either",
        ),
        ("\n[[motion]]\nsupport = 0", "motion[0].rod: missing"),
    ];
    for (extra, expected) in cases {
        let e = error_of(&format!("{HEAD}{extra}\n"));
        assert!(
            e.contains(expected),
            "{extra}: got {e:?}, expected {expected:?}"
        );
    }
    // The older files still work.
    assert_eq!(
        error_of(&format!("{HEAD}support = \"clamp_start\"\n")),
        "accepted"
    );
    assert_eq!(error_of(HEAD), "accepted");
}

/// A point force at the free end of a cantilever strip (start clamped): the beam's tip
/// deflection P L³ / (3 E I) in the small-deflection limit (ν = 0).
#[test]
fn a_point_force_at_a_station_bends_the_cantilever_as_the_beam() {
    let ei = YOUNG * WIDTH * THICKNESS.powi(3) / 12.0;
    let p = 1e-3 * 3.0 * ei / LENGTH.powi(2); // tip deflection 1e-3 L
    for (model, n_length, n_width, tol) in [("midedge", 30, 2, 0.02), ("bspline", 16, 1, 0.005)] {
        let text = format!(
            r#"
[[shells]]
model = "{model}"
length = {LENGTH}
width = {WIDTH}
thickness = {THICKNESS}
material = {{ young = {YOUNG}, poisson = 0.0, density = 1000.0 }}
elements = {n_length}
width_elements = {n_width}
clamps = [{{ edge = "start" }}]
forces = [{{ station = {n_length}, column = 0, force = [0.0, {half}, 0.0] }},
          {{ station = {n_length}, column = {n_width}, force = [0.0, {half}, 0.0] }}]
"#,
            half = 0.5 * p
        );
        let s = Session::new(toml::from_str(&text).expect("scene")).expect("session");
        let step = s.results(0, None, 1.0, 1);
        let r = &step.shells[0];
        assert!(r.converged, "{model}");
        let tip = r.positions[r.positions.len() - 1][1];
        let beam = p * LENGTH.powi(3) / (3.0 * ei);
        let err = tip / beam - 1.0;
        eprintln!("{model}: tip {tip:.6e} m, beam {beam:.6e} m, error {err:+.3e}");
        assert!(err.abs() < tol, "{model}: {err:+.3e}");
        // The clamp carries the force.
        assert!(
            r.relative_force_imbalance < 1e-6,
            "{}",
            r.relative_force_imbalance
        );
    }
}

/// Gravity edits re-solve the strips too, and the saved scene reloads to the same shape.
#[test]
fn a_gravity_edit_re_solves_the_strips_and_the_saved_scene_reloads() {
    for model in ["midedge", "bspline"] {
        let mut s = Session::new(sagging(model)).expect("session");
        let before = positions(&s);
        let r = s.set_gravity([0.0, -5.0, 2.0]).expect("edit");
        assert!(r.converged, "{model}: {r:?}");
        let after = positions(&s);
        assert!(
            max_distance(&after, &before) > 1e-4,
            "{model}: the strip moved"
        );
        let text = toml::to_string(&s.saved()).expect("toml");
        let reloaded = Session::new(toml::from_str(&text).expect("parse")).expect("reload");
        let d = max_distance(&positions(&reloaded), &after);
        assert!(d < 1e-9 * 0.3, "{model}: {d:e}");
    }
}

#[test]
fn clamp_poses_beyond_the_strip_are_refused() {
    let e = error_of(&format!(
        "{HEAD}clamps = [{{ edge = \"end\", offset = [0.5, 0.0, 0.0] }}]\n"
    ));
    assert!(
        e.starts_with("shells[0].clamps[0].offset: [0.5, 0.0, 0.0]"),
        "{e}"
    );
    assert!(e.contains("magnitude at most 0.4"), "{e}");
    let e = error_of(&format!(
        "{HEAD}clamps = [{{ edge = \"start\", rotate = [7.0, 0.0, 0.0] }}]\n"
    ));
    assert!(e.starts_with("shells[0].clamps[0].rotate"), "{e}");
}
