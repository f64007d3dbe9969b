//! Shell strips on obstacles in scene files, solved by `Session`: a flat cable lying on a box
//! and hanging over its edge (no gap closes, the box and the clamp carry the weight computed
//! here from the scene's data, each contact listed under the box as the strip's), and bad
//! input naming the field.

use slender_core::scene::{Scene, Session};

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

const H: f64 = 0.2e-3;

/// The flat cable of the shell-cantilever example (L = 0.3 m, w = 0.03 m, h = 0.2 mm,
/// ρ = 1000 kg/m³), clamped at x = 0 in y = 0, over `obstacles` (TOML tables), with `extra`
/// keys in its `[[shells]]` table.
fn strip_scene(extra: &str, obstacles: &str) -> String {
    format!(
        r#"
gravity = [0.0, -9.81, 0.0]

[[shells]]
name = "strip"
length = 0.3
width = 0.03
thickness = {H}
material = {{ young = 10530e6, poisson = 0.3, density = 1000.0 }}
elements = 30
width_elements = 2
grading = {{ kind = "uniform" }}
{extra}

{obstacles}
"#
    )
}

#[test]
fn flat_cable_over_a_box_edge_rests_on_the_box_and_balances() {
    // The box's top 2 mm below the strip's mid-surface (plus h/2), its edge at x = 0.25 m:
    // the strip comes down onto the top (beam theory: 15 cm from the clamp) and hangs over
    // the edge.
    let top = -0.002 - 0.5 * H;
    let text = strip_scene(
        "",
        &format!(
            r#"[[obstacles]]
name = "box"
shape = {{ kind = "box", center = [0.1, {}, 0.0], size = [0.3, 0.1, 0.1] }}

[contact]
activation = 1e-6
"#,
            top - 0.05
        ),
    );
    let session = Session::new(scene(&text)).expect("compiles");
    let step = session.results(0, None, 1.0, 1);
    assert!(step.converged, "{:?}", step.shells[0].report.status);
    let strip = &step.shells[0];
    let weight = 1000.0 * H * 0.03 * 0.3 * 9.81;
    let min_gap = step.min_gap.expect("a min gap");
    assert!(min_gap > 0.0 && min_gap < 1e-6, "min gap {min_gap:e}");
    assert_eq!(strip.min_gap, Some(min_gap));
    let contacts = &step.obstacles[0].contacts;
    assert!(contacts.len() >= 6, "{} contacts", contacts.len());
    let mut total = [0.0, -weight, 0.0];
    for c in contacts {
        assert!(c.shell && c.rod == "strip", "{c:?}");
        assert!(c.gap > 0.0 && c.gap < 1e-6, "{c:?}");
        // On the top face (x ≤ 0.25 m, the mid-surface h/2 + gap above it) or at its edge.
        assert!(c.position[0] <= 0.25 + 1e-3, "{c:?}");
        assert!(c.position[1] >= top + 0.5 * H, "{c:?}");
        for (i, t) in total.iter_mut().enumerate() {
            *t += c.normal_force[i] + c.friction_force[i];
        }
    }
    let box_force = step.obstacles[0].force;
    let strip_contacts = strip.contact_force.expect("contact force");
    for i in 0..3 {
        assert!((box_force[i] - strip_contacts[i]).abs() <= 1e-15 + 1e-12 * weight);
        total[i] += strip.clamp_force[i];
    }
    let err = norm(total) / weight;
    println!(
        "strip over a box edge: {} contacts, min gap {min_gap:.3e} m, box force {box_force:?} N, clamp {:?} N, |clamp + box + weight| / weight = {err:.2e}, iterations {}",
        contacts.len(),
        strip.clamp_force,
        strip.report.iterations
    );
    assert!(err <= 1e-6, "imbalance {err:e}");
    assert!(strip.relative_force_imbalance <= 1e-6);
    // The box carries most of the weight (the strip lies on it), the clamp the rest.
    assert!(
        box_force[1] > 0.5 * weight && box_force[1] < weight,
        "{box_force:?}"
    );
}

#[test]
fn bad_input_names_the_field() {
    let floor = |y: f64| {
        format!(
            r#"[[obstacles]]
shape = {{ kind = "plane", point = [0.0, {y}, 0.0], normal = [0.0, 1.0, 0.0] }}
"#
        )
    };
    let error = |text: String| -> String {
        match Session::new(scene(&text)) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e.to_string(),
        }
    };
    // The strip's mid-surface starts closer to the floor than h/2.
    let e = error(strip_scene("", &floor(-0.5 * H)));
    assert!(
        e.starts_with("obstacles[0]:") && e.contains("strip") && e.contains("half-thickness"),
        "{e}"
    );
    // A clamp posed inside the floor.
    let e = error(strip_scene(
        r#"clamps = [{ edge = "start", offset = [0.0, -0.05, 0.0] }]"#,
        &floor(-0.01),
    ));
    assert!(e.starts_with("shells[0].clamps[0]:"), "{e}");
    // B-spline strips do not take contact.
    let e = error(strip_scene(r#"model = "bspline""#, &floor(-0.01)));
    assert!(
        e.starts_with("shells[0].model:") && e.contains("midedge"),
        "{e}"
    );
    // Self-contact acts on rods only.
    let e = error(strip_scene(
        "",
        &format!("{}\n[contact]\nself_contact = true\n", floor(-0.01)),
    ));
    assert!(e.starts_with("contact.self_contact:"), "{e}");
    // The strips' barrier stiffness must be positive.
    let e = error(strip_scene(
        "",
        &format!("{}\n[contact]\nshell_stiffness = -1.0\n", floor(-0.01)),
    ));
    assert!(
        e.starts_with("contact.shell_stiffness:") && e.contains("N/m³"),
        "{e}"
    );
    // A strip alone with a floor compiles (its activation distance comes from its length).
    Session::new(scene(&strip_scene("", &floor(-0.01)))).expect("a strip over a floor");
}
