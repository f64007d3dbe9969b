//! The Cosserat rod and the SE(3) beam in scene files (`model = "..."` per rod): the same
//! routing operations the discrete elastic rod is checked on, against the same independent
//! references (Euler's elastica by elliptic integrals), the warm Session path (moves, a clip
//! added and the scene saved), and the errors for what these models do not take.

use nalgebra::Vector3;
use slender_core::scene::spec::{SupportKind, SupportSpec};
use slender_core::scene::{Scene, Session};

use crate::common;
use common::{clamped_elastica_deflection, elliptic_ke};

const SHEARABLE: [&str; 3] = ["cosserat", "cosserat_tan", "se3"];

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

/// A clamped–free column (EI₁ = 1 N m², EI₂ = 2 N m²), 1 m along x, pushed at its tip by a
/// dead force; shear and extension stiff (10⁶ N) so that the inextensible, unshearable
/// elastica is the reference to well below the 1e-3 tolerance (P/GA ≈ 4e-6).
fn column(model: &str, force: f64, elements: usize) -> String {
    format!(
        r#"
[[rods]]
name = "column"
model = "{model}"
shear_stiffness = [1.0e6, 1.0e6]
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "stiffness", ea = 1.0e6, ei1 = 1.0, ei2 = 2.0, gj = 0.77, linear_density = 0.1 }}
elements = {elements}
supports = [ {{ kind = "clamp", vertex = "start" }} ]
forces = [ {{ vertex = "end", force = [{}, 0.0, 0.0] }} ]
"#,
        -force
    )
}

#[test]
fn each_model_buckles_a_clamped_free_column_at_one_and_a_half_euler_loads_onto_the_elastica() {
    // Euler's first case: P_E = π²EI/(4L²); the buckled cantilever is half a pinned–pinned
    // elastica of length 2L: with k = sin(α/2), P/P_E = (2K(k)/π)², the tip deflects by
    // 2kL/K(k) across and sits at L(2E(k)/K(k) − 1) along the axis.
    let ratio = 1.5;
    let p_e = std::f64::consts::PI.powi(2) / 4.0;
    let (mut lo, mut hi) = (1e-9_f64, 0.999_f64);
    for _ in 0..200 {
        let k = 0.5 * (lo + hi);
        if (2.0 * elliptic_ke(k * k).0 / std::f64::consts::PI).powi(2) < ratio {
            lo = k;
        } else {
            hi = k;
        }
    }
    let k = 0.5 * (lo + hi);
    let (kk, ee) = elliptic_ke(k * k);
    let (across, along) = (2.0 * k / kk, 2.0 * ee / kk - 1.0);
    for model in SHEARABLE {
        let s = Session::new(scene(&column(model, ratio * p_e, 60))).unwrap();
        let res = s.results(0, None, 1.0, 1);
        assert!(res.converged && res.stable, "{model}: {:?}", res.structures);
        assert!(
            res.structures[0].stability.followed_unstable_mode,
            "{model}: the straight column should have been left along its unstable mode"
        );
        let tip = *res.rods[0].positions.last().unwrap();
        let sim_across = (tip[1] * tip[1] + tip[2] * tip[2]).sqrt();
        eprintln!(
            "{model}: tip ({:.6}, {sim_across:.6}) vs elastica ({along:.6}, {across:.6})",
            tip[0]
        );
        assert!(
            (tip[0] - along).abs() < 1e-3 && (sim_across - across).abs() < 1e-3,
            "{model}: tip {tip:?} vs elastica ({along}, {across})"
        );
        // The buckled plane is the soft one (EI₁ bends along m₁).
        assert!(res.rods[0].relative_force_imbalance < 1e-9);
    }
}

/// A 1 m PMMA-like cable, d = 4 mm, clamped at both ends (shear stiffness from the section).
fn push_scene(model: &str) -> String {
    format!(
        r#"
[[rods]]
name = "column"
model = "{model}"
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.004 }}
material = {{ young = 3.0e9, poisson = 0.35, density = 1140.0 }}
elements = 40
supports = [ {{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }} ]
"#
    )
}

#[test]
fn each_model_pushed_past_buckling_by_moving_a_clamp_ends_on_the_clamped_elastica() {
    for model in SHEARABLE {
        let mut s = Session::new(scene(&push_scene(model))).unwrap();
        let steps = 10;
        for k in 1..=steps {
            let r = s
                .move_support_by(
                    0,
                    1,
                    Vector3::new(0.0, 0.0, 1e-3 / steps as f64),
                    Vector3::new(-0.005, 0.0, 0.0),
                )
                .unwrap();
            assert!(r.converged, "{model} step {k}: {r:?}");
            assert!(
                r.stable,
                "{model} step {k}: unstable equilibrium returned: {r:?}"
            );
        }
        let res = s.results(steps, None, 1.0, 1);
        let rod = &res.rods[0];
        let deflection = rod
            .positions
            .iter()
            .map(|p| (p[1] * p[1] + p[2] * p[2]).sqrt())
            .fold(0.0, f64::max);
        let exact = clamped_elastica_deflection(1.0, 0.05);
        let rel = deflection / exact - 1.0;
        eprintln!("{model}: deflection {deflection:.6} vs elastica {exact:.6} ({rel:+.2e})");
        assert!(
            rel.abs() < 5e-3,
            "{model}: deflection {deflection} vs elastica {exact}"
        );
        // The end clamp's reaction is the axial load of the buckled column, at least P_E of
        // the clamped–clamped column 4π²EI/L².
        let ei = 3.0e9 * std::f64::consts::PI * 0.004_f64.powi(4) / 64.0;
        let p = -rod.supports[1].force[0];
        assert!(p > 4.0 * std::f64::consts::PI.powi(2) * ei, "{model}: {p}");
        assert!(rod.relative_force_imbalance < 1e-9 && rod.relative_moment_imbalance < 1e-9);
    }
}

/// A sagging cable, clamped at its start and pinned at its end.
fn sag_scene(model: &str) -> String {
    format!(
        r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
name = "cable"
model = "{model}"
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.6 }}
section = {{ shape = "circle", diameter = 0.004 }}
material = {{ young = 1.0e8, poisson = 0.4, density = 1400.0 }}
elements = 24
supports = [ {{ kind = "clamp", vertex = "start" }}, {{ kind = "pin", vertex = "end" }} ]
"#
    )
}

fn distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(a, b)| {
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn each_model_moved_and_moved_back_returns_to_its_equilibrium() {
    for model in SHEARABLE {
        let mut s = Session::new(scene(&sag_scene(model))).unwrap();
        let start = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        let there = Vector3::new(-0.1, 0.08, 0.05);
        let turn = Vector3::new(0.0, 0.3, -0.4);
        assert!(
            s.move_support_by(0, 1, Vector3::zeros(), there)
                .unwrap()
                .converged
        );
        assert!(
            s.move_support_by(0, 0, turn, Vector3::zeros())
                .unwrap()
                .converged
        );
        let moved = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        assert!(
            distance(&start, &moved) > 0.05,
            "{model}: the moves did nothing"
        );
        assert!(
            s.move_support_by(0, 0, -turn, Vector3::zeros())
                .unwrap()
                .converged
        );
        assert!(
            s.move_support_by(0, 1, Vector3::zeros(), -there)
                .unwrap()
                .converged
        );
        let back = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        let d = distance(&start, &back);
        assert!(d < 1e-9 * 0.6, "{model}: back at {d:e} m from the start");
    }
}

#[test]
fn each_model_takes_a_clip_added_in_a_session_and_its_saved_scene_round_trips() {
    for model in SHEARABLE {
        let mut s = Session::new(scene(&sag_scene(model))).unwrap();
        let r = s
            .move_support_by(0, 1, Vector3::zeros(), Vector3::new(-0.05, 0.04, 0.06))
            .unwrap();
        assert!(r.converged);
        let before = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        let r = s
            .add_support(
                0,
                SupportSpec {
                    kind: SupportKind::Clip,
                    vertex: None,
                    at: Some(0.31),
                    axis: None,
                },
            )
            .unwrap();
        assert!(r.converged, "{model}: {r:?}");
        let here = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        // The clip holds the cable where it was: a new vertex at s = 0.31 on the old shape,
        // and the rest nearly unchanged (the clip's edge keeps its rest length).
        assert_eq!(here.len(), before.len() + 1);
        let saved = s.saved();
        let mut again = Session::new(saved).unwrap();
        for k in 1..=again.motion_steps() {
            assert!(again.run_motion_step(k).converged);
        }
        let there = again.results(0, None, 1.0, 1).rods[0].positions.clone();
        let d = distance(&here, &there);
        assert!(d < 1e-9 * 0.6, "{model}: saved scene differs by {d:e} m");
        // Removing the clip drops its vertex again and re-solves from the current shape: back
        // to the equilibrium before the clip.
        let r = s.remove_support(0, 2).unwrap();
        assert!(r.converged, "{model}: {r:?}");
        let without = s.results(0, None, 1.0, 1).rods[0].positions.clone();
        let d = distance(&before, &without);
        assert!(
            d < 1e-9 * 0.6,
            "{model}: without the clip, {d:e} m from before"
        );
    }
}

fn error_of(text: &str) -> String {
    match scene(text).compile() {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

const ROD: &str = r#"
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
"#;

#[test]
fn what_the_shearable_models_do_not_take_is_refused_by_name() {
    let cases: [(&str, &str); 7] = [
        (
            "model = \"cosserat\"\nsupports = [ { kind = \"clamp\", vertex = \"start\" }, { kind = \"slider\", vertex = \"end\" } ]",
            "rods[0].supports[1].kind",
        ),
        (
            "model = \"se3\"\nsupports = [ { kind = \"clamp\", vertex = \"start\" }, { kind = \"twist_hold\", vertex = \"end\" } ]",
            "rods[0].supports[1].kind",
        ),
        (
            "model = \"se3\"\nsupports = [ { kind = \"clamp\", vertex = \"start\" } ]\nforces = [ { vertex = \"end\", force = [0.0, 1.0, 0.0], follower = true } ]",
            "rods[0].forces[0].follower",
        ),
        (
            "model = \"cosserat\"\nshear_stiffness = [0.0, 1.0]\nsupports = [ { kind = \"clamp\", vertex = \"start\" } ]",
            "rods[0].shear_stiffness[0]",
        ),
        (
            "model = \"cosserat\"\nshear_stiffness = [1.0, nan]\nsupports = [ { kind = \"clamp\", vertex = \"start\" } ]",
            "rods[0].shear_stiffness[1]",
        ),
        (
            "shear_stiffness = [1.0, 1.0]\nsupports = [ { kind = \"clamp\", vertex = \"start\" } ]",
            "rods[0].shear_stiffness",
        ),
        (
            "model = \"se3\"\nsupports = [ { kind = \"pin\", vertex = \"start\" } ]",
            "rigid",
        ),
    ];
    for (extra, expected) in cases {
        let text = format!("[[rods]]\n{ROD}{extra}\n");
        let e = error_of(&text);
        assert!(e.contains(expected), "{extra}\n→ {e}");
    }
    // A stiffness section has no shear stiffness to derive.
    let e = error_of(
        r#"
[[rods]]
model = "cosserat"
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "stiffness", ea = 1.0e6, ei1 = 1.0, ei2 = 1.0, gj = 0.77, linear_density = 0.1 }
supports = [ { kind = "clamp", vertex = "start" } ]
"#,
    );
    assert!(
        e.contains("rods[0].shear_stiffness") && e.contains("missing"),
        "{e}"
    );
    // Joints join discrete elastic rods only.
    let e = error_of(&format!(
        "[[rods]]\nname = \"a\"\nmodel = \"se3\"\n{ROD}supports = [ {{ kind = \"clamp\", vertex = \"start\" }} ]\n\
         [[rods]]\nname = \"b\"\ncenterline = {{ kind = \"straight\", start = [1.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}\n\
         section = {{ shape = \"circle\", diameter = 0.004 }}\nmaterial = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}\n\
         [[joints]]\nends = [ {{ rod = \"a\", end = \"end\" }}, {{ rod = \"b\", end = \"start\" }} ]\n"
    ));
    assert!(
        e.contains("joints[0].ends[0].rod") && e.contains("se3"),
        "{e}"
    );
    // An unknown model name is a parse error that lists the valid ones.
    let bad: Result<Scene, _> = toml::from_str(&format!(
        "[[rods]]\n{ROD}model = \"timoshenko\"\nsupports = [ {{ kind = \"clamp\", vertex = \"start\" }} ]\n"
    ));
    let e = bad.unwrap_err().to_string();
    assert!(e.contains("timoshenko") && e.contains("cosserat"), "{e}");
}

#[test]
fn a_move_to_a_pose_within_round_off_of_the_current_orientation_is_a_pure_translation() {
    // The page sends the support's orientation back as it got it: R·R⁻¹ is the identity only
    // to round-off, where `Rotation3::scaled_axis` may give NaN; the move must still converge.
    use nalgebra::Rotation3;
    use slender_core::scene::SupportPose;
    for model in ["der", "cosserat", "se3"] {
        let mut s = Session::new(scene(&sag_scene(model))).unwrap();
        let turn = Rotation3::new(Vector3::new(0.3, -0.2, 0.7));
        assert!(
            s.move_support(
                0,
                0,
                SupportPose {
                    position: s.pose(0, 0).unwrap().position,
                    rotation: turn,
                }
            )
            .unwrap()
            .converged
        );
        let cur = s.pose(0, 0).unwrap();
        let noisy = Rotation3::new(Vector3::new(1e-17, 0.0, 0.0)) * cur.rotation;
        let r = s
            .move_support(
                0,
                0,
                SupportPose {
                    position: cur.position + Vector3::new(0.0, 0.01, 0.0),
                    rotation: noisy,
                },
            )
            .unwrap();
        assert!(r.converged, "{model}: {r:?}");
        assert!(r.relative_residual.is_finite());
    }
}
