//! A cable running through a ring (a `torus` obstacle: a sliding clip), against the closed
//! forms of a taut rope over a pulley. The cable (1 m, weightless, clamped at both ends) runs
//! straight through a ring at its middle; the clamps are then dragged up, in 1 cm moves as in
//! `slender view`, so that the ring holds the cable down in a V.
//!
//! * Frictionless: the tension passes the ring unchanged (each leg carries the same axial
//!   force, where a clip holding the middle vertex would leave the legs stretched unequally),
//!   and it is the tension of the stretched V: EA (|A − P| + |P − B| − L)/L with P where the
//!   cable touches the ring.
//! * With friction μ, a clamp dragged outward makes the cable slide over the ring toward it:
//!   the contacts' friction sits on Coulomb's cone against the motion, and the pulled leg
//!   carries more. (The capstan ratio e^{μθ} is not checked: one or two vertices touch a ring
//!   this thin, and where they sit across the tube's section tilts the ring's force along the
//!   cable by more than the 11 % friction adds here.)
//! * A clamp moved 5 cm in one edit: the solver's first guess (the supports' motion blended
//!   into the cable) would carry the middle vertex through the ring's tube to a feasible state
//!   on its far side; the guess is capped like a step, and the cable stays in the ring.

use slender_core::geometry::Vec3;
use slender_core::scene::{Scene, SceneStep, Session};

/// Cable: d = 1 mm, E = 100 MPa.
const D: f64 = 0.001;
const E: f64 = 1.0e8;
/// Ring: centre circle radius and tube radius (hole 10 mm, the cable's axis through its centre).
const RING: f64 = 0.015;
const TUBE: f64 = 0.005;

fn axial_stiffness() -> f64 {
    E * std::f64::consts::PI * D * D / 4.0
}

/// 200 elements (5 mm, below the 11 mm the ring's tube and the cable's radius span). The
/// barrier is stiff enough for the ring's point load (the default rests the cable's weight,
/// and this cable is weightless).
fn ring_scene(mu: f64) -> Scene {
    toml::from_str(&format!(
        r#"
[[rods]]
name = "cable"
elements = 200
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 1.0 }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = {E}, poisson = 0.4, density = 1000.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }}]
[[obstacles]]
name = "ring"
friction = {mu}
shape = {{ kind = "torus", center = [0.5, 0.0, 0.0], axis = [1.0, 0.0, 0.0], radius = {RING}, tube_radius = {TUBE} }}
[contact]
activation = 1e-4
stiffness = 1e5
"#
    ))
    .expect("scene")
}

fn sub(a: [f64; 3], b: [f64; 3]) -> Vec3 {
    Vec3::new(a[0] - b[0], a[1] - b[1], a[2] - b[2])
}

/// Drags support `support` by `dz` along z and `dx` along x in 1 cm moves.
fn drag(s: &mut Session, support: usize, dx: f64, dz: f64) {
    let moves = (dx.abs().max(dz.abs()) / 0.01).round() as usize;
    for _ in 0..moves {
        let r = s
            .move_support_by(
                0,
                support,
                Vec3::zeros(),
                Vec3::new(dx / moves as f64, 0.0, dz / moves as f64),
            )
            .expect("edit");
        assert!(r.converged, "{r:?}");
    }
}

/// What the ring holds: the vertices touching it (first and last), its normal force (N), and
/// the mean axial force (N) of each leg's middle half (clear of the clamps' and the ring's
/// bending).
struct V {
    first: usize,
    last: usize,
    normal: f64,
    left: f64,
    right: f64,
}

fn v_of(step: &SceneStep) -> V {
    let ring = &step.obstacles[0];
    assert!(!ring.contacts.is_empty(), "the ring holds the cable");
    let first = ring.contacts.iter().map(|c| c.vertex).min().unwrap();
    let last = ring.contacts.iter().map(|c| c.vertex).max().unwrap();
    let normal = ring
        .contacts
        .iter()
        .map(|c| Vec3::from(c.normal_force))
        .sum::<Vec3>()
        .norm();
    let rod = &step.rods[0];
    let ea = axial_stiffness();
    let mean = |from: usize, to: usize| {
        rod.edge_strain[from..to]
            .iter()
            .map(|e| ea * e)
            .sum::<f64>()
            / (to - from) as f64
    };
    let n = rod.edge_strain.len();
    V {
        first,
        last,
        normal,
        left: mean(first / 4, 3 * first / 4),
        right: mean(last + (n - last) / 4, last + 3 * (n - last) / 4),
    }
}

#[test]
fn a_frictionless_ring_passes_the_tension_of_the_stretched_v() {
    let mut s = Session::new(ring_scene(0.0)).expect("compiles");
    drag(&mut s, 0, 0.0, 0.05);
    drag(&mut s, 1, 0.0, 0.03);
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged && r.stable);
    let v = v_of(&r);
    let rod = &r.rods[0];
    let (a, b) = (rod.positions[0], *rod.positions.last().unwrap());
    let p = rod.positions[v.first];
    let stretched = sub(p, a).norm() + sub(b, p).norm();
    let string = axial_stiffness() * (stretched - 1.0);
    let gap = r.min_gap.expect("a gap");
    println!(
        "frictionless V: contact at vertices {}..={} ({p:?}), ring force {:.6} N, N left {:.6} N, right {:.6} N, string {string:.6} N, min gap {gap:.3e} m",
        v.first, v.last, v.normal, v.left, v.right
    );
    // The ring holds the cable from above, at the top of its hole.
    assert!(
        p[2] > RING - TUBE - D && p[2] < RING - TUBE,
        "contact height {}",
        p[2]
    );
    assert!(gap > 0.0 && gap < 1e-4, "min gap {gap}");
    // The pulley: the same tension on both legs (a clip holding vertex 100 at the same point
    // would leave them at 0.26 N and 0.07 N), up to what vertex contact allows: the touching
    // vertex sits up to half an edge h from the top of the tube's section (radius
    // ρ = tube + cable radius), so the ring's force F may lean along the cable by up to
    // h/(2ρ) and carry that much of F as an axial force.
    let h = 1.0 / 200.0;
    let lean = v.normal * h / (2.0 * (TUBE + D / 2.0));
    assert!(
        (v.left - v.right).abs() <= lean && (v.left - v.right).abs() < 2e-2 * v.left,
        "legs at {} N and {} N (vertex contact allows {lean} N)",
        v.left,
        v.right
    );
    // The stretched V's tension. The bends at the clamps (held level while the legs slope)
    // and at the ring make the cable's path longer than the chords |A − P| + |P − B| by
    // about 5e-5 m, 2 % of the stretch: hence the tolerance.
    let mean = 0.5 * (v.left + v.right);
    assert!(
        (mean - string).abs() < 2e-2 * string,
        "{mean} N vs {string} N"
    );
}

#[test]
fn a_rough_ring_resists_the_cable_sliding_through_it() {
    let mu = 0.3;
    let mut s = Session::new(ring_scene(mu)).expect("compiles");
    drag(&mut s, 0, 0.0, 0.1);
    drag(&mut s, 1, 0.0, 0.1);
    // Pull the end clamp outward: the cable slides over the ring toward it.
    drag(&mut s, 1, 0.02, 0.0);
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged, "{:?}", s.report(0).status);
    let v = v_of(&r);
    println!(
        "rough V, sliding: contacts {}..={}, ring force {:.5} N, N in {:.6} N, out {:.6} N",
        v.first, v.last, v.normal, v.left, v.right
    );
    for c in &r.obstacles[0].contacts {
        let (ft, fn_) = (
            Vec3::from(c.friction_force),
            Vec3::from(c.normal_force).norm(),
        );
        // Sliding: Coulomb's cone at its edge, the friction on the cable against its motion
        // (toward the start clamp).
        assert!(
            (ft.norm() / fn_ - mu).abs() < 1e-6 * mu,
            "friction {ft:?}, normal {fn_}"
        );
        assert!(ft.x < 0.0, "friction {ft:?} does not hold the cable back");
    }
    // The friction holds back part of the pull: the leg being pulled carries more.
    assert!(v.right > 1.05 * v.left, "{} N vs {} N", v.right, v.left);
}

#[test]
fn a_clamp_jumped_past_the_ring_leaves_the_cable_in_it() {
    let mut s = Session::new(ring_scene(0.0)).expect("compiles");
    // 5 cm up in one edit: the blended first guess would lift the middle 2.5 cm, over the
    // ring's tube (its hole reaches 1 cm above the cable).
    let r = s
        .move_support_by(0, 0, Vec3::zeros(), Vec3::new(0.0, 0.0, 0.05))
        .expect("edit");
    assert!(r.converged, "{r:?}");
    let step = s.results(0, None, 1.0, 1);
    // Where the cable crosses the ring's plane x = 0.5: inside the hole.
    let rod = &step.rods[0];
    let j = (0..rod.positions.len() - 1)
        .find(|&j| rod.positions[j][0] <= 0.5 && rod.positions[j + 1][0] > 0.5)
        .expect("the cable crosses the ring's plane");
    let (p, q) = (rod.positions[j], rod.positions[j + 1]);
    let t = (0.5 - p[0]) / (q[0] - p[0]);
    let z = p[2] + t * (q[2] - p[2]);
    println!("crossing the ring's plane at z = {z:.6} m");
    assert!(z.abs() < RING - TUBE, "the cable left the ring: z = {z}");
    assert_eq!(
        step.obstacles[0].contacts.len(),
        1,
        "the ring holds it down"
    );
}

#[test]
fn a_barrier_far_too_soft_gives_up_within_its_iteration_budget() {
    // The rings' example with its barrier 10⁴ times softer (1 N/m² instead of 1e4): the
    // cable's weight then closes the gaps to round-off, every load step of the first push
    // needs some fifteen Newton iterations and never grows, and without a budget the edit
    // crawled through ~16 000 load steps (minutes). Now it stops at the solver's budget of
    // Newton iterations, says so, and keeps the last equilibrium.
    let text = include_str!("../../../examples/cable_through_rings.toml");
    assert!(text.contains("\nstiffness = 1.0e4"));
    let scene: Scene =
        toml::from_str(&text.replace("\nstiffness = 1.0e4", "\nstiffness = 1.0")).expect("scene");
    let budget = scene.solver.max_total_iterations;
    let mut s = Session::new(scene).expect("compiles");
    assert!(s.report(0).converged(), "the cable hangs through the rings");
    let before = s.results(0, None, 1.0, 1).rods[0].positions.clone();
    let r = s
        .move_support_by(0, 1, Vec3::zeros(), Vec3::new(-0.025, 0.0, 0.0))
        .expect("edit");
    assert!(!r.converged, "{r:?}");
    let reason = r.reason.unwrap_or_default();
    assert!(
        reason.contains("max_total_iterations")
            && reason.contains(&budget.to_string())
            && reason.contains("try a larger `[contact] stiffness` than the 1e0 used"),
        "{reason}"
    );
    // Within one load step's Newton solve of the budget (contact re-solves add none here:
    // the rings are frictionless).
    assert!(r.iterations < budget + 400, "{} iterations", r.iterations);
    assert_eq!(
        s.results(0, None, 1.0, 1).rods[0].positions,
        before,
        "the last equilibrium is kept"
    );
}
