//! Shell strips on obstacles in scene files, solved by `Session`: a flat cable lying on a box
//! and hanging over its edge (no gap closes, the box and the clamp carry the weight computed
//! here from the scene's data, each contact listed under the box as the strip's), a coarse
//! strip running through a thin bar between its vertices (reported) against a fine one resting
//! on it, a mesh blade poking through a face's interior (reported), a resting strip dragged
//! onto its contacts, and bad input naming the field.

use nalgebra::Vector3;
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
    strip_scene_of(H, 30, extra, obstacles)
}

/// [`strip_scene`] with thickness `h` (m) and `elements` along the length.
fn strip_scene_of(h: f64, elements: usize, extra: &str, obstacles: &str) -> String {
    format!(
        r#"
gravity = [0.0, -9.81, 0.0]

[[shells]]
name = "strip"
length = 0.3
width = 0.03
thickness = {h}
material = {{ young = 10530e6, poisson = 0.3, density = 1000.0 }}
elements = {elements}
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
fn a_strip_running_through_a_thin_bar_between_its_vertices_is_reported() {
    // A 0.3 m strip 1 mm thick clamped at x = 0: beam theory puts its sag under its own weight
    // at 11.3 mm at the tip and 5.7 mm at x = 0.1875 m, the middle of the third of four
    // elements. A bar of radius 4 mm across the whole width, its axis 9 mm below the rest
    // plane there, reaches up to 5 mm below it: the coarse strip's vertices are 3.75 cm away,
    // nothing holds its faces, and their mid-surface runs about 0.7 mm deep through the bar.
    let h = 1e-3;
    let (x_bar, y_bar, r_bar) = (0.1875, -0.009, 0.004);
    let text = |elements: usize| {
        strip_scene_of(
            h,
            elements,
            "",
            &format!(
                r#"[[obstacles]]
name = "bar"
shape = {{ kind = "cylinder", point = [{x_bar}, {y_bar}, 0.0], axis = [0.0, 0.0, 1.0], radius = {r_bar} }}

[contact]
activation = 1e-6
"#
            ),
        )
    };
    let coarse = Session::new(scene(&text(4))).expect("compiles");
    let step = coarse.results(0, None, 1.0, 1);
    assert!(step.converged, "{:?}", step.shells[0].report.status);
    assert!(
        step.obstacles[0].contacts.is_empty(),
        "no vertex is near the bar: {:?}",
        step.obstacles[0].contacts
    );
    let through = &step.edges_through_obstacles;
    println!("coarse strip: {through:?}");
    assert!(!through.is_empty());
    let faces = &step.shells[0].faces;
    for e in through {
        assert!(e.shell && e.rod == "strip" && e.obstacle == "bar", "{e:?}");
        // The face named is the strip's, with its vertices; it spans the bar's x.
        assert_eq!(e.vertices, faces[e.edge].to_vec(), "{e:?}");
        let xs: Vec<f64> = e
            .vertices
            .iter()
            .map(|&v| step.shells[0].positions[v][0])
            .collect();
        let (lo, hi) = xs
            .iter()
            .fold((1.0f64, -1.0f64), |(l, u), &x| (l.min(x), u.max(x)));
        assert!(lo < x_bar && x_bar < hi, "{e:?}: x from {lo} to {hi}");
        // The deepest point is inside the bar by `depth`, on the bar's top side.
        let r = ((e.position[0] - x_bar).powi(2) + (e.position[1] - y_bar).powi(2)).sqrt();
        assert!((r_bar - r - e.depth).abs() < 1e-9, "r = {r}, {e:?}");
        assert!(e.depth > 2e-4 && e.depth < 2e-3, "{e:?}");
        assert!(e.position[1] > y_bar, "{e:?}");
    }
    // Every face across the bar's line, on both rows of the width, is named.
    assert_eq!(through.len(), 4, "{through:?}");

    // 100 elements (3 mm apart, a chord's sagitta over the bar 0.28 mm, under h/2): the strip
    // rests on the bar and no face runs through it.
    let fine = Session::new(scene(&text(100))).expect("compiles");
    let step = fine.results(0, None, 1.0, 1);
    assert!(step.converged, "{:?}", step.shells[0].report.status);
    assert!(
        !step.obstacles[0].contacts.is_empty(),
        "the fine strip rests on the bar"
    );
    assert!(
        step.edges_through_obstacles.is_empty(),
        "{:?}",
        step.edges_through_obstacles
    );
}

#[test]
fn a_mesh_blade_poking_through_a_face_between_its_edges_is_reported() {
    // The coarse strip of the bar test (4 × 2 elements, sagging 5.7 mm at x = 0.1875 m) over
    // a mesh blade: one triangle in the plane z = 2.5 mm, 1 mm wide at its base 5 cm down,
    // its tip at x = 0.1875 m. That point lies inside one face (half way along the third
    // element, a sixth of the way across the second row) and 2.5 mm or more from every face
    // edge, so no face edge meets the blade: only the blade's own edges cross the face.
    let (x_tip, z_blade) = (0.1875, 0.0025);
    let text = |tip: f64| {
        strip_scene_of(
            1e-3,
            4,
            "",
            &format!(
                r#"[[obstacles]]
name = "blade"
shape = {{ kind = "mesh", vertices = [[{a}, -0.05, {z_blade}], [{b}, -0.05, {z_blade}], [{x_tip}, {tip}, {z_blade}]], triangles = [[0, 1, 2]] }}

[contact]
activation = 1e-6
"#,
                a = x_tip - 5e-4,
                b = x_tip + 5e-4,
            ),
        )
    };
    // The tip 4 mm below the rest plane: the strip sags past it (the face crosses the blade
    // 6.3 mm down).
    let step = Session::new(scene(&text(-0.004)))
        .expect("compiles")
        .results(0, None, 1.0, 1);
    assert!(step.converged, "{:?}", step.shells[0].report.status);
    assert!(step.obstacles[0].contacts.is_empty());
    let through = &step.edges_through_obstacles;
    println!("strip over the blade: {through:?}");
    assert_eq!(through.len(), 1, "{through:?}");
    let e = &through[0];
    assert!(
        e.shell && e.rod == "strip" && e.obstacle == "blade",
        "{e:?}"
    );
    assert_eq!(e.depth, 0.0);
    assert_eq!(e.vertices, step.shells[0].faces[e.edge].to_vec(), "{e:?}");
    // The crossing is on the blade (its plane, within its width at that height) and on the
    // face's plane, inside the face.
    let p = Vector3::from(e.position);
    assert!((p.z - z_blade).abs() < 1e-12, "{e:?}");
    assert!(
        (p.x - x_tip).abs() < 5e-4 * (-0.004 - p.y) / 0.046 + 1e-12,
        "{e:?}"
    );
    assert!(p.y < -0.004, "{e:?}");
    let [a, b, c] = [0, 1, 2].map(|k| Vector3::from(step.shells[0].positions[e.vertices[k]]));
    let normal = (b - a).cross(&(c - a)).normalize();
    assert!(normal.dot(&(p - a)).abs() < 1e-12, "{e:?}");
    for (u, v, w) in [(a, b, c), (b, c, a), (c, a, b)] {
        // p on the same side of each edge as the opposite corner.
        assert!(
            (v - u).cross(&(p - u)).dot(&(v - u).cross(&(w - u))) > 0.0,
            "{e:?}"
        );
    }

    // The tip 7.5 mm down, 1.8 mm below the sagged strip: nothing crosses.
    let step = Session::new(scene(&text(-0.0075)))
        .expect("compiles")
        .results(0, None, 1.0, 1);
    assert!(step.converged, "{:?}", step.shells[0].report.status);
    assert!(
        step.edges_through_obstacles.is_empty(),
        "{:?}",
        step.edges_through_obstacles
    );
}

/// The clamp of examples/flat_cable_on_bracket.toml (floor made frictionless) dragged 1 cm
/// down, pressing the strip onto the bracket and the floor it rests on: the first guess holds
/// the strip's rows where they touch (the move faded out along the length toward them, as
/// toward a support), so the drag converges in one load step (carried rigidly, the rows
/// stopped at the surfaces and the others not: 107 Newton iterations in 4 load steps).
/// Frictionless, the equilibrium does not depend on the path: the scene solved cold with both
/// obstacles 1 cm higher instead ends on the same shape, 1 cm higher.
#[test]
fn dragging_a_resting_strip_onto_its_contacts_holds_them_in_the_first_guess() {
    let mut base = scene(include_str!("../../../examples/flat_cable_on_bracket.toml"));
    base.motion.clear();
    base.obstacles[1].friction = 0.0;
    let mut s = Session::new(base.clone()).expect("compiles");
    let e = s
        .move_shell_clamp_by(0, 0, Vector3::zeros(), Vector3::new(0.0, -0.01, 0.0))
        .expect("edit");
    println!(
        "strip dragged down: {} Newton iterations, {} load steps",
        e.iterations, e.load_steps
    );
    assert!(e.converged, "{:?}", e.reason);
    assert_eq!(e.load_steps, 1);
    let a = s.results(0, None, 1.0, 1);
    assert!(
        !a.obstacles[1].contacts.is_empty(),
        "the strip rests on the floor"
    );

    let text = toml::to_string(&base).expect("toml");
    let raised = text
        .replacen("-0.045", "-0.035", 1)
        .replacen("-0.08", "-0.07", 1);
    let raised = scene(&raised);
    assert_ne!(raised, base, "the obstacles moved");
    let cold = Session::new(raised).expect("compiles");
    let b = cold.results(0, None, 1.0, 1);
    assert!(b.converged, "{:?}", b.shells[0].report.status);
    let diff = a.shells[0]
        .positions
        .iter()
        .zip(&b.shells[0].positions)
        .map(|(p, q)| {
            let d = Vector3::from(*p) - Vector3::from(*q) + Vector3::new(0.0, 0.01, 0.0);
            d.norm()
        })
        .fold(0.0, f64::max);
    println!("  cold solve with the obstacles raised: largest position difference {diff:.3e} m");
    assert!(diff < 1e-6, "{diff}");
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
