//! Time stepping of Cosserat rods and SE(3) beams in contact (`[time]` with `[[obstacles]]`
//! and `[contact]`), against references that do not come from the contact code:
//!
//! - a stiff rod dropped flat onto a floor falls as the scheme's exact discrete free fall
//!   (½ g t² for the energy-conserving scheme, ½ g t (t + h) for backward Euler) until the
//!   barrier's activation distance, never closes a gap, and at rest under backward Euler the
//!   floor carries its weight;
//! - an obstacle that is never touched does not change the motion: a clamped rod's released
//!   swing — bending and torsion, so the frames' rotary inertia acts — above a far-away
//!   floor is the swing without the floor to round-off;
//! - a clamped shaft lying on a frictionless floor, struck by an end torque, twists as the
//!   Saint-Venant torsion wave, whose period 4L/c, c = √(GJ/(ρJ)), is set by the frames'
//!   rotary inertia ρJ: the contact problem hands it to the stepper.

use nalgebra::{UnitQuaternion, Vector3};
use slender_core::scene::{Scene, SceneStep, TimeRun};

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

const G: f64 = 9.81;
/// The dropped rod: steel, L = 0.2 m, d = 10 mm, 10 elements, free, horizontal along x.
const L: f64 = 0.2;
const D: f64 = 0.01;
const RHO: f64 = 7850.0;
const MODELS: [&str; 2] = ["cosserat", "se3"];

/// The rod's weight (N).
fn weight() -> f64 {
    RHO * std::f64::consts::PI * D * D / 4.0 * L * G
}

/// A `model` rod lying flat with its axis at `z0` over a floor z = 0 with Coulomb
/// coefficient `mu`.
fn drop_scene(model: &str, z0: f64, mu: f64, contact: &str, time: &str) -> String {
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]

[[rods]]
name = "rod"
model = "{model}"
elements = 10
centerline = {{ kind = "straight", start = [0.0, 0.0, {z0}], direction = [1.0, 0.0, 0.0], length = {L} }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 2.0e11, poisson = 0.3, density = {RHO} }}

[[obstacles]]
name = "floor"
friction = {mu}
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[contact]
{contact}

[time]
{time}
"#
    )
}

/// One sample of a drop: time (s), centroid height (m), lowest gap (m).
struct Sample {
    t: f64,
    z: f64,
    gap: f64,
}

/// Runs a drop scene to its end, sampling every step (the gap from the positions here).
fn drop(text: &str) -> (Vec<Sample>, SceneStep) {
    let compiled = scene(text).compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let mut samples = Vec::new();
    loop {
        let p = run.state(0).members[0].positions();
        samples.push(Sample {
            t: run.time(),
            z: p.iter().map(|x| x.z).sum::<f64>() / p.len() as f64,
            gap: p
                .iter()
                .map(|x| x.z - 0.5 * D)
                .fold(f64::INFINITY, f64::min),
        });
        if run.finished() {
            break;
        }
        let r = run.step();
        assert!(r.converged, "{r:?}");
    }
    let last = run.frame(1);
    (samples, last)
}

#[test]
fn a_framed_rod_dropped_on_a_frictionless_floor_falls_freely_never_penetrates_and_bounces_back() {
    // As the discrete elastic rod's drop (scene_time_contact.rs): 5 mm onto ĝ = 1 mm.
    let (h, activation) = (0.005, 1e-3);
    let z0 = 0.5 * D + h;
    let dt = 1e-4;
    for model in MODELS {
        let text = drop_scene(
            model,
            z0,
            0.0,
            &format!("activation = {activation}"),
            &format!("dt = {dt}\nduration = 0.08\nscheme = \"energy_conserving\""),
        );
        let (samples, _) = drop(&text);
        let mut free_fall_error: f64 = 0.0;
        let mut free_steps = 0;
        for s in &samples {
            assert!(s.gap > 0.0, "{model}, t = {}: gap {:e}", s.t, s.gap);
            let exact = z0 - 0.5 * G * s.t * s.t;
            if exact - 0.5 * D > activation {
                free_fall_error = free_fall_error.max((s.z - exact).abs());
                free_steps += 1;
            }
        }
        let lowest = samples.iter().map(|s| s.gap).fold(f64::INFINITY, f64::min);
        let impact = (2.0 * (h - activation) / G).sqrt();
        let rebound = samples
            .iter()
            .filter(|s| s.t > 2.0 * impact)
            .map(|s| s.z)
            .fold(f64::NEG_INFINITY, f64::max);
        println!(
            "{model}, energy-conserving drop from {h} m: free fall over {free_steps} steps within {free_fall_error:.2e} m of z0 − ½ g t², lowest gap {lowest:.3e} m, back up to {:.6} of the drop height",
            (rebound - 0.5 * D) / h,
        );
        assert!(free_steps > 50);
        assert!(free_fall_error <= 1e-12, "{model}: {free_fall_error:e}");
        assert!(lowest > 0.0 && lowest < activation, "{model}: {lowest:e}");
        assert!(
            ((rebound - 0.5 * D) / h - 1.0).abs() < 1e-2,
            "{model}: rebound {rebound}"
        );
    }
}

#[test]
fn a_framed_rod_dropped_on_a_floor_with_backward_euler_comes_to_rest_carrying_its_weight() {
    let h = 0.02;
    let z0 = 0.5 * D + h;
    let dt = 1e-3;
    let activation = 1e-6 * L; // the default
    for model in MODELS {
        for mu in [0.0, 0.4] {
            let text = drop_scene(
                model,
                z0,
                mu,
                "",
                &format!("dt = {dt}\nduration = 0.3\nscheme = \"backward_euler\""),
            );
            let (samples, last) = drop(&text);
            // Backward Euler's discrete free fall: z_n = z0 − ½ g t_n (t_n + h), exactly.
            let mut free_fall_error: f64 = 0.0;
            for s in &samples {
                assert!(s.gap > 0.0, "{model}, μ = {mu}, t = {}: gap {:e}", s.t, s.gap);
                let exact = z0 - 0.5 * G * s.t * (s.t + dt);
                if exact - 0.5 * D > activation + G * dt * (s.t + dt) {
                    free_fall_error = free_fall_error.max((s.z - exact).abs());
                }
            }
            let floor = &last.obstacles[0];
            let (gap, fz) = (last.min_gap.unwrap(), floor.force[2]);
            let kinetic = last.time.as_ref().unwrap().energy.kinetic;
            println!(
                "{model}, backward Euler drop, μ = {mu}: free fall within {free_fall_error:.2e} m of z0 − ½ g t (t + h), at rest: {} contacts, gap {gap:.3e} m (ĝ {activation:.1e}), floor force / weight − 1 = {:.2e}, kinetic {kinetic:.2e} J",
                floor.contacts.len(),
                fz / weight() - 1.0,
            );
            assert!(free_fall_error <= 1e-12, "{model}: {free_fall_error:e}");
            assert!(gap > 0.0 && gap < activation, "{model}: {gap:e}");
            assert_eq!(floor.contacts.len(), 11, "{model}: every vertex on the floor");
            assert!(
                (fz / weight() - 1.0).abs() < 1e-6,
                "{model}: {fz} vs {}",
                weight()
            );
            assert!(floor.force[0].abs() + floor.force[1].abs() < 1e-9 * weight());
        }
    }
}
