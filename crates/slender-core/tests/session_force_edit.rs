//! Editing a point force in a session (`Session::set_force`): the warm re-solve from the last
//! equilibrium ends where a cold solve of the scene with the new force ends (a different path:
//! loads ramped from rest), for every rod model, across an interior clamp, for a change large
//! enough to need load steps; a small change of a weightless cantilever's tip force moves the
//! tip by beam theory's ΔF L³/(3EI); bad input names its field and changes nothing. A follower
//! force's edit ends where a cold solve ends too, and the force stays normal to the tip.
//! Adding a force at an arc length (snapped to the file's nearest vertex, across a vertex
//! inserted for a clip) and removing one end where cold solves of the edited files end.

use crate::common;

use common::max_distance;
use slender_core::scene::spec::VertexRef;
use slender_core::scene::{Scene, Session};

/// A 1 m cantilever (d = 6 mm, E = 1 GPa) of `model`, `elements` elements, clamped at the
/// start, tip force `force` (N) at the end (a follower if `follower`), gravity `g` (m/s²),
/// and `extra` supports after the clamp.
fn cantilever(model: &str, elements: usize, force: [f64; 3], g: f64, extra: &str) -> Scene {
    cantilever_with(model, elements, force, g, extra, false)
}

fn cantilever_with(
    model: &str,
    elements: usize,
    force: [f64; 3],
    g: f64,
    extra: &str,
    follower: bool,
) -> Scene {
    toml::from_str(&format!(
        r#"
gravity = [0.0, 0.0, {g}]
[[rods]]
name = "beam"
model = "{model}"
elements = {elements}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = 0.006 }}
material = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}
supports = [ {{ kind = "clamp", vertex = "start" }}{extra} ]
forces = [ {{ vertex = "end", force = {force:?}, follower = {follower} }} ]
"#
    ))
    .expect("the scene parses")
}

fn positions(s: &Session) -> Vec<[f64; 3]> {
    s.results(0, None, 1.0, 1).rods[0].positions.clone()
}

/// Edits the tip force of a session from `from` to `to` and compares with a cold solve at
/// `to`: returns the worst vertex distance (m), the structures the edit re-solved and the
/// tip after the edit.
fn edit_against_cold(
    model: &str,
    extra: &str,
    from: [f64; 3],
    to: [f64; 3],
) -> (f64, Vec<usize>, [f64; 3]) {
    let mut s = Session::new(cantilever(model, 20, from, -9.81, extra)).expect("solves");
    let r = s.set_force(0, 0, to).expect("a valid force");
    assert!(r.converged && r.stable, "{model}: {r:?}");
    let cold = Session::new(cantilever(model, 20, to, -9.81, extra)).expect("solves");
    assert_eq!(s.spec().rods[0].forces[0].force, to);
    let here = positions(&s);
    let d = max_distance(&here, &positions(&cold));
    eprintln!(
        "{model}{extra}: {from:?} → {to:?} N: {} iterations, {} load steps, {d:.1e} m from the cold solve",
        r.iterations, r.load_steps
    );
    (d, r.structures.to_vec(), *here.last().unwrap())
}

#[test]
fn a_force_edit_ends_where_a_cold_solve_with_that_force_ends() {
    for model in ["der", "cosserat", "se3"] {
        let (d, structures, _) =
            edit_against_cold(model, "", [0.0, 0.0, -0.01], [0.0, 0.02, -0.03]);
        assert!(d <= 1e-9, "{model}: {d:e} m from the cold solve");
        assert_eq!(structures, [0]);
    }
}

#[test]
fn a_force_beyond_an_interior_clamp_loads_the_part_that_carries_it() {
    // The clamp at vertex 10 splits the rod into two parts, two structures; the tip force is
    // on the second, and only that one is re-solved.
    let extra = r#", { kind = "clamp", vertex = 10 }"#;
    let (d, structures, _) = edit_against_cold("der", extra, [0.0, 0.0, -0.01], [0.0, 0.0, -0.2]);
    assert!(d <= 1e-9, "{d:e} m from the cold solve");
    assert_eq!(structures, [1]);
}

#[test]
fn a_large_force_change_ends_on_the_large_deflection_equilibrium() {
    // From a sag of centimetres to a tip turned far down (EI = 6.4e-2 N m², F L²/EI ≈ 31).
    let (d, _, tip) = edit_against_cold("der", "", [0.0, 0.0, -0.001], [0.0, 0.0, -2.0]);
    assert!(d <= 1e-9, "{d:e} m from the cold solve");
    assert!(tip[2] < -0.5 && tip[0] < 0.7, "tip {tip:?}");
}

#[test]
fn a_small_force_change_moves_the_tip_by_beam_theory() {
    // Weightless: the tip moves by ΔF L³/(3EI) for a small change (linear regime).
    let ei = 1.0e9 * std::f64::consts::PI * 0.006_f64.powi(4) / 64.0;
    let df = 1e-4;
    let mut s = Session::new(cantilever("der", 40, [0.0, 0.0, 0.0], 0.0, "")).expect("solves");
    let before = *positions(&s).last().unwrap();
    let r = s.set_force(0, 0, [0.0, 0.0, -df]).expect("a valid force");
    assert!(r.converged);
    let after = *positions(&s).last().unwrap();
    let expected = df / (3.0 * ei);
    let moved = before[2] - after[2];
    eprintln!("tip moved {moved:.6e} m, beam theory {expected:.6e} m");
    assert!(
        (moved - expected).abs() <= 1e-3 * expected,
        "tip moved {moved:e} m, beam theory {expected:e} m"
    );
}

#[test]
fn a_saved_scene_after_a_force_edit_solves_to_the_same_equilibrium() {
    let mut s = Session::new(cantilever("der", 20, [0.0, 0.0, -0.01], -9.81, "")).unwrap();
    s.set_force(0, 0, [0.01, 0.0, -0.05]).unwrap();
    let again = Session::new(s.saved()).expect("the saved scene solves");
    let d = max_distance(&positions(&s), &positions(&again));
    assert!(d <= 1e-9, "{d:e} m apart");
}

#[test]
fn bad_force_edits_name_the_field_and_change_nothing() {
    let mut s = Session::new(cantilever("der", 20, [0.0, 0.0, -0.01], -9.81, "")).unwrap();
    let before = positions(&s);
    for (rod, force, value, field) in [
        (1, 0, [0.0, 0.0, 1.0], "rods[1].forces[0]"),
        (0, 3, [0.0, 0.0, 1.0], "rods[0].forces[3]"),
        (0, 0, [0.0, f64::NAN, 1.0], "rods[0].forces[0].force"),
        (0, 0, [0.0, 0.0, 1e300], "rods[0].forces[0].force"),
    ] {
        let e = s.set_force(rod, force, value).unwrap_err();
        assert!(e.to_string().starts_with(field), "{e}");
    }
    assert_eq!(positions(&s), before);
    assert_eq!(s.spec().rods[0].forces[0].force, [0.0, 0.0, -0.01]);
}

/// The follower cantilever: `cantilever_with(…, follower = true)`.
fn follower_cantilever(elements: usize, force: [f64; 3], g: f64) -> Scene {
    cantilever_with("der", elements, force, g, "", true)
}

#[test]
fn a_follower_force_edit_ends_where_a_cold_solve_with_that_force_ends() {
    // From a small follower load to one that bends the cantilever far (F L²/EI ≈ 2.5) and
    // sideways: the edit turns the old and new forces with the tip along its path; the cold
    // solve ramps the new one from rest. Both end on the follower equilibrium.
    let (from, to) = ([0.0, 0.0, -0.01], [0.0, 0.1, -0.12]);
    let mut s = Session::new(follower_cantilever(20, from, -9.81)).expect("solves");
    let r = s.set_force(0, 0, to).expect("a valid force");
    assert!(r.converged && r.stable, "{r:?}");
    assert_eq!(s.spec().rods[0].forces[0].force, to);
    let cold = Session::new(follower_cantilever(20, to, -9.81)).expect("solves");
    let d = max_distance(&positions(&s), &positions(&cold));
    eprintln!(
        "follower {from:?} → {to:?} N: {} iterations, {} load steps, {d:.1e} m from the cold solve",
        r.iterations, r.load_steps
    );
    assert!(d <= 1e-9, "{d:e} m from the cold solve");
    // A dead force of the same value ends elsewhere: the edit did apply a follower.
    let dead = Session::new(cantilever("der", 20, to, -9.81, "")).expect("solves");
    let apart = max_distance(&positions(&s), &positions(&dead));
    assert!(apart > 1e-2, "{apart:e} m from the dead-force equilibrium");
    // And back: the saved scene solves to the same equilibrium.
    let again = Session::new(s.saved()).expect("the saved scene solves");
    assert!(max_distance(&positions(&s), &positions(&again)) <= 1e-9);
    // Removed (ramped to zero first): the cantilever under its weight alone.
    let r = s.remove_force(0, 0).expect("force 0 exists");
    assert!(r.converged, "{r:?}");
    let mut bare = follower_cantilever(20, to, -9.81);
    bare.rods[0].forces.clear();
    let d = max_distance(&positions(&s), &positions(&Session::new(bare).unwrap()));
    assert!(d <= 1e-9, "removed: {d:e} m from the cold solve without it");
}

#[test]
fn a_follower_force_edit_that_curls_the_cantilever_settles() {
    // The follower example (EI = 1 N m², weightless) from F L²/EI = 2 to 6: the tip turns
    // past a right angle. The plain lagged iteration diverges at this load; with the
    // Anderson mixing of `solver::lagged_loads` the edit and the cold solve both settle, on
    // the same equilibrium.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/follower_cantilever.toml"
    ))
    .unwrap();
    let scene = |f: f64| -> Scene {
        toml::from_str(&text.replace("[0.0, 2.0, 0.0]", &format!("[0.0, {f:?}, 0.0]"))).unwrap()
    };
    let mut s = Session::new(scene(2.0)).expect("solves");
    let r = s.set_force(0, 0, [0.0, 6.0, 0.0]).expect("a valid force");
    assert!(r.converged, "{r:?}");
    let cold = Session::new(scene(6.0)).expect("solves");
    assert!(cold.report(0).converged(), "{:?}", cold.report(0));
    let d = max_distance(&positions(&s), &positions(&cold));
    let tip = *positions(&s).last().unwrap();
    eprintln!(
        "curling follower edit: {} iterations, {} load steps, tip {tip:?}, {d:.1e} m from the cold solve",
        r.iterations, r.load_steps
    );
    assert!(d <= 1e-9, "{d:e} m from the cold solve");
    assert!(tip[0] < 0.1 && tip[1] > 0.7, "curled: {tip:?}");
}

#[test]
fn a_follower_force_beyond_a_clip_is_edited_on_the_part_that_carries_it() {
    // A clip at vertex 10 splits the rod into two members of one structure; the follower tip
    // force is on the second, at its own vertex numbering.
    let scene = |force| {
        cantilever_with(
            "der",
            20,
            force,
            -9.81,
            r#", { kind = "clip", vertex = 10 }"#,
            true,
        )
    };
    let to = [0.0, 0.08, -0.05];
    let mut s = Session::new(scene([0.0, 0.0, -0.01])).expect("solves");
    let r = s.set_force(0, 0, to).expect("a valid force");
    assert!(r.converged, "{r:?}");
    let cold = Session::new(scene(to)).expect("solves");
    let d = max_distance(&positions(&s), &positions(&cold));
    eprintln!("follower beyond a clip: {d:.1e} m from the cold solve");
    assert!(d <= 1e-9, "{d:e} m from the cold solve");
}

#[test]
fn an_edited_follower_force_stays_normal_to_the_tip_of_a_weightless_cantilever() {
    // Given at rest as +y on a cantilever along x, the follower stays normal to the tip's
    // tangent; weightless, the clamp carries it all: its reaction is the force, turned. A
    // dead +y force would leave a reaction along +y (its component along the bent tip's
    // tangent is sin φ ≈ 0.8 of it here).
    let ei = 1.0e9 * std::f64::consts::PI * 0.006_f64.powi(4) / 64.0;
    let mut s = Session::new(follower_cantilever(40, [0.0, ei, 0.0], 0.0)).expect("solves");
    let r = s
        .set_force(0, 0, [0.0, 2.5 * ei, 0.0])
        .expect("a valid force");
    assert!(r.converged, "{r:?}");
    let res = s.results(0, None, 1.0, 1);
    let p = &res.rods[0].positions;
    let n = p.len();
    let tip: Vec<f64> = (0..3).map(|k| p[n - 1][k] - p[n - 2][k]).collect();
    let norm = tip.iter().map(|x| x * x).sum::<f64>().sqrt();
    let reaction = res.rods[0].supports[0].force;
    let along: f64 = (0..3).map(|k| reaction[k] * tip[k] / norm).sum();
    let size = reaction.iter().map(|x| x * x).sum::<f64>().sqrt();
    eprintln!(
        "tip turned {:.3} rad; reaction {size:.6e} N (force {:.6e} N), along the tip {along:.2e} N",
        (tip[1] / norm).asin(),
        2.5 * ei
    );
    assert!((size - 2.5 * ei).abs() <= 1e-9 * size, "{size:e} N");
    // The force in space now, as the page draws it: the reaction's opposite.
    let now = s.force_now(0, 0).expect("force 0 exists");
    let off = (0..3)
        .map(|k| (now[k] + reaction[k]).abs())
        .fold(0.0, f64::max);
    assert!(
        off <= 1e-9 * size,
        "force now {now:?} N, reaction {reaction:?} N"
    );
    assert_eq!(s.force_now(0, 1), None);
    // The last edge's tangent stands for the tip's: the load turns with that edge's frame.
    assert!(along.abs() <= 1e-9 * size, "{along:e} N along the tip");
    assert!(tip[1] / norm > 0.5, "the tip has turned: {tip:?}");
}

#[test]
fn a_force_change_that_does_not_converge_keeps_the_equilibrium_and_puts_the_force_back() {
    // Two Newton iterations per load step and load steps of at least a quarter: the small
    // start converges, a tip force turning the weightless cantilever far down cannot. A dead
    // force and a follower one (its rest force and the state's frozen loads put back).
    for follower in [false, true] {
        let mut scene = cantilever_with("der", 20, [0.0, 0.0, -1e-7], 0.0, "", follower);
        scene.solver.max_iterations = 2;
        scene.solver.min_load_step = 0.25;
        let mut s = Session::new(scene.clone()).unwrap();
        assert!(s.report(0).converged());
        let before = s.results(0, None, 1.0, 1);
        let r = s
            .set_force(0, 0, [0.0, 0.0, -5.0])
            .expect("a valid request");
        assert!(!r.converged, "{r:?}");
        assert!(
            r.reason
                .as_deref()
                .unwrap_or("")
                .contains("did not converge"),
            "{r:?}"
        );
        assert_eq!(s.spec().rods[0].forces[0].force, [0.0, 0.0, -1e-7]);
        let after = s.results(0, None, 1.0, 1);
        assert_eq!(after.rods[0].positions, before.rods[0].positions);
        assert_eq!(after.rods[0].supports, before.rods[0].supports);
        // The model's force is back exactly, not as x + Δ − Δ (off by ~4e-16 N, 2e-9 of the
        // 2e-7 N below): a small edit that converges then ends where it ends in a session
        // that never tried the large one, to the round-off of their different warm starts
        // (~1e-15).
        let mut fresh = Session::new(scene).unwrap();
        for t in [&mut s, &mut fresh] {
            let r = t.set_force(0, 0, [0.0, 0.0, -2e-7]).unwrap();
            assert!(r.converged, "{r:?}");
        }
        let (here, there) = (positions(&s), positions(&fresh));
        let d = max_distance(&here, &there);
        let sag = -there.last().unwrap()[2];
        eprintln!(
            "after a failed edit (follower: {follower}): {d:.1e} m from a fresh session, tip sag {sag:.3e} m"
        );
        assert!(d <= 1e-12 * sag, "{d:e} m, tip sag {sag:e} m");
    }
}

/// The cantilever with a clip given by arc length (0.33 m: a vertex inserted between the
/// file's vertices 6 and 7, so the file's vertex 12 is the rod's vertex 13) and, besides the
/// tip force, the forces `more` (TOML entries).
fn clipped_with(model: &str, more: &str) -> Scene {
    let text = toml::to_string(&cantilever(
        model,
        20,
        [0.0, 0.0, -0.01],
        -9.81,
        r#", { kind = "clip", at = 0.33 }"#,
    ))
    .unwrap();
    let mut scene: Scene = toml::from_str(&text).unwrap();
    let extra: Scene = toml::from_str(&format!(
        "[[rods]]\nname = \"x\"\nelements = 1\ncenterline = {{ kind = \"straight\", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}\nsection = {{ shape = \"circle\", diameter = 0.006 }}\nmaterial = {{ young = 1.0e9, poisson = 0.4, density = 1400.0 }}\nforces = [{more}]\n"
    ))
    .unwrap();
    scene.rods[0]
        .forces
        .extend(extra.rods[0].forces.iter().cloned());
    scene
}

#[test]
fn an_added_force_ends_where_a_cold_solve_with_it_in_the_file_ends() {
    for model in ["der", "cosserat", "se3"] {
        let mut s = Session::new(clipped_with(model, "")).unwrap();
        // 0.62 m is nearest the file's vertex 12 (0.60 m), the rod's vertex 13.
        let r = s
            .add_force(0, 0.62, [0.0, 0.01, -0.04])
            .expect("a valid force");
        assert!(r.converged, "{model}: {r:?}");
        let added = &s.spec().rods[0].forces[1];
        assert_eq!(added.force, [0.0, 0.01, -0.04]);
        assert_eq!(added.vertex, VertexRef::Index(12), "{model}");
        assert_eq!(s.compiled().rods[0].force_vertices, [21, 13], "{model}");
        let cold = Session::new(clipped_with(
            model,
            "{ vertex = 12, force = [0.0, 0.01, -0.04] }",
        ))
        .unwrap();
        let d = max_distance(&positions(&s), &positions(&cold));
        eprintln!(
            "{model}: added force vs cold solve {d:.1e} m ({} iterations)",
            r.iterations
        );
        assert!(d <= 1e-9, "{model}: {d:e} m");
        // And removed: back to the scene without it.
        let r = s.remove_force(0, 1).expect("force 1 exists");
        assert!(r.converged, "{model}: {r:?}");
        assert_eq!(s.spec().rods[0].forces.len(), 1);
        let without = Session::new(clipped_with(model, "")).unwrap();
        let d = max_distance(&positions(&s), &positions(&without));
        eprintln!("{model}: removed again vs cold solve {d:.1e} m");
        assert!(d <= 1e-9, "{model}: {d:e} m");
    }
}

#[test]
fn removing_the_first_force_renumbers_the_rest() {
    let mut s = Session::new(clipped_with(
        "der",
        "{ vertex = 5, force = [0.0, -0.02, 0.0] }",
    ))
    .unwrap();
    let r = s.remove_force(0, 0).expect("force 0 exists");
    assert!(r.converged, "{r:?}");
    assert_eq!(s.spec().rods[0].forces.len(), 1);
    assert_eq!(s.spec().rods[0].forces[0].force, [0.0, -0.02, 0.0]);
    let mut cold = clipped_with("der", "{ vertex = 5, force = [0.0, -0.02, 0.0] }");
    cold.rods[0].forces.remove(0);
    let d = max_distance(&positions(&s), &positions(&Session::new(cold).unwrap()));
    assert!(d <= 1e-9, "{d:e} m");
    let again = Session::new(s.saved()).expect("the saved scene solves");
    assert!(max_distance(&positions(&s), &positions(&again)) <= 1e-9);
}

#[test]
fn bad_force_additions_and_removals_name_the_field_and_change_nothing() {
    let mut s = Session::new(clipped_with("der", "")).unwrap();
    let before = positions(&s);
    let errors = [
        s.add_force(2, 0.5, [0.0, 0.0, 1.0])
            .expect_err("no rod 2")
            .path,
        s.add_force(0, 1.5, [0.0, 0.0, 1.0])
            .expect_err("off the rod")
            .path,
        s.add_force(0, f64::NAN, [0.0, 0.0, 1.0])
            .expect_err("NaN at")
            .path,
        s.add_force(0, 0.5, [0.0, f64::INFINITY, 1.0])
            .expect_err("infinite")
            .path,
        s.remove_force(0, 4).expect_err("no force 4").path,
    ];
    assert_eq!(
        errors,
        [
            "rods[2]",
            "rods[0].forces.at",
            "rods[0].forces.at",
            "rods[0].forces[1].force",
            "rods[0].forces[4]"
        ]
    );
    assert_eq!(positions(&s), before);
    assert_eq!(s.spec().rods[0].forces.len(), 1);
}
