//! Cable–cable contact reported per pair of segments (`segment_contacts` of the results): a
//! cantilevered cable sagging onto a second cable clamped at both ends across it. Each cable
//! must balance on its own — its weight, its clamps' reactions and the pair forces the other
//! cable applies to it — which checks the reported pair forces (the structure's balance alone
//! would not: they cancel in it). In an equilibrium solve and, damped to rest, in a time run.

use slender_core::scene::{Scene, SceneStep, Session, TimeRun};

const G: f64 = 9.81;
const D: f64 = 0.008;
const RHO: f64 = 1500.0;
const L: f64 = 0.6;

fn scene(time: &str) -> Scene {
    let text = format!(
        r#"
gravity = [0.0, 0.0, -{G}]

[[rods]]
name = "upper"
elements = 30
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.112], direction = [1.0, 0.0, 0.0], length = {L} }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 5.0e8, poisson = 0.4, density = {RHO} }}
supports = [{{ kind = "clamp", vertex = "start" }}]

[[rods]]
name = "lower"
elements = 30
centerline = {{ kind = "straight", start = [0.31, -0.295, 0.1], direction = [0.0, 1.0, 0.0], length = {L} }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 5.0e8, poisson = 0.4, density = {RHO} }}
supports = [{{ kind = "clamp", vertex = "start" }}, {{ kind = "clamp", vertex = "end" }}]

[contact]
self_contact = true
activation = 1e-5
{time}
"#
    );
    toml::from_str(&text).expect("scene")
}

fn weight() -> f64 {
    RHO * std::f64::consts::PI * D * D / 4.0 * L * G
}

fn add(a: &mut [f64; 3], b: [f64; 3]) {
    for k in 0..3 {
        a[k] += b[k];
    }
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Per rod: |applied + supports + pair forces on it| / its weight, and the pair forces'
/// resultant on it (N).
fn rod_balances(step: &SceneStep) -> Vec<(String, f64, [f64; 3])> {
    let pairs = step
        .segment_contacts
        .as_ref()
        .expect("self-contact results");
    step.rods
        .iter()
        .map(|r| {
            let mut total = r.applied_force;
            for s in &r.supports {
                add(&mut total, s.force);
            }
            let mut on_rod = [0.0; 3];
            for p in pairs {
                if p.rod_a == r.name {
                    add(&mut on_rod, p.force_a);
                }
                if p.rod_b == r.name {
                    add(&mut on_rod, p.force_b);
                }
            }
            add(&mut total, on_rod);
            (r.name.clone(), norm(total) / weight(), on_rod)
        })
        .collect()
}

fn check(step: &SceneStep, tolerance: f64, what: &str) {
    let pairs = step
        .segment_contacts
        .as_ref()
        .expect("self-contact results");
    assert!(!pairs.is_empty(), "{what}: the cables do not touch");
    let activation = 1e-5;
    for p in pairs {
        assert!(p.gap > 0.0 && p.gap < activation, "{what}: gap {:e}", p.gap);
        assert_ne!(p.rod_a, p.rod_b, "{what}: a cable touches itself");
        // Equal and opposite (no held vertex is in contact here).
        let sum = [
            p.force_a[0] + p.force_b[0],
            p.force_a[1] + p.force_b[1],
            p.force_a[2] + p.force_b[2],
        ];
        assert!(norm(sum) <= 1e-12 * weight(), "{what}: {sum:?}");
        // The closest points are two radii apart, up to the gap.
        let d = norm([
            p.point_a[0] - p.point_b[0],
            p.point_a[1] - p.point_b[1],
            p.point_a[2] - p.point_b[2],
        ]);
        assert!(
            (d - D - p.gap).abs() < 1e-12,
            "{what}: {d} vs {}",
            D + p.gap
        );
    }
    let min = step.min_segment_gap.expect("a min segment gap");
    assert!(min > 0.0 && min < activation, "{what}: {min:e}");
    for (name, err, on_rod) in rod_balances(step) {
        println!(
            "{what}: {name}: {} pairs, pair force on it {:?} N ({:.3} of a cable's weight), |weight + clamps + pairs| / weight = {err:.2e}, min segment gap {min:.3e} m",
            pairs.len(),
            on_rod,
            norm(on_rod) / weight()
        );
        assert!(
            norm(on_rod) > 0.05 * weight(),
            "{what}: {name} carries nothing"
        );
        assert!(err <= tolerance, "{what}: {name} imbalance {err:e}");
    }
    // The upper cable is pushed up, the lower one down.
    let up = &rod_balances(step)[0].2;
    assert!(up[2] > 0.0, "{up:?}");
}

#[test]
fn two_cables_pressing_on_each_other_each_balance_with_the_reported_pair_forces() {
    let s = Session::new(scene("")).expect("compiles");
    let r = s.results(0, None, 1.0, 1);
    assert!(r.converged, "{:?}", s.report(0).status);
    assert_eq!(
        r.structures.len(),
        1,
        "with self-contact the cables are one structure"
    );
    check(&r, 1e-9, "equilibrium");
}

#[test]
fn two_cables_settling_onto_each_other_in_time_balance_with_the_pair_forces_at_rest() {
    let spec = scene(
        "[time]\ndt = 0.002\nduration = 2.0\nscheme = \"backward_euler\"\nrayleigh_mass = 20.0",
    );
    let compiled = spec.compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let mut touched = 0;
    while !run.finished() {
        let r = run.step();
        assert!(r.converged, "{:?}", r.failure);
        let gap = run.frame(0).min_segment_gap.unwrap_or(f64::INFINITY);
        assert!(gap > 0.0, "t = {}: the cables cross ({gap:e})", run.time());
        if gap < 1e-5 {
            touched += 1;
        }
    }
    assert!(touched > 10);
    let last = run.frame(1);
    println!(
        "time run: kinetic energy at the end {:.2e} J",
        last.time.as_ref().unwrap().energy.kinetic
    );
    check(&last, 1e-6, "time run at rest");
}
