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
use slender_core::scene::TimeRun;

use crate::common;
use common::dropped_rod::{drop, drop_scene, scene, weight, D, G, L, RHO};

const MODELS: [&str; 2] = ["cosserat", "se3"];

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
                assert!(
                    s.gap > 0.0,
                    "{model}, μ = {mu}, t = {}: gap {:e}",
                    s.t,
                    s.gap
                );
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
            assert_eq!(
                floor.contacts.len(),
                11,
                "{model}: every vertex on the floor"
            );
            assert!(
                (fz / weight() - 1.0).abs() < 1e-6,
                "{model}: {fz} vs {}",
                weight()
            );
            assert!(floor.force[0].abs() + floor.force[1].abs() < 1e-9 * weight());
        }
    }
}

/// A clamped `model` rod (steel, L = 0.3 m, d = 4 mm, 12 elements) along x at z = 0, released
/// at t = 0 under gravity and a dead end force and moment that bend it both ways and twist
/// it, so that its frames turn about every axis; with `obstacles` appended.
fn swing_scene(model: &str, scheme: &str, obstacles: &str) -> String {
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]

[[rods]]
name = "swing"
model = "{model}"
elements = 12
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.3 }}
section = {{ shape = "circle", diameter = 0.004 }}
material = {{ young = 2.0e11, poisson = 0.3, density = 7850.0 }}
supports = [{{ kind = "clamp", vertex = "start" }}]
forces = [{{ vertex = "end", force = [0.0, 1.0, 0.0] }}]
moments = [{{ vertex = "end", moment = [0.5, 0.0, 0.5] }}]

[time]
dt = 2e-4
duration = 0.04
scheme = "{scheme}"
output_every = 1
{obstacles}
"#
    )
}

/// Positions (m) and frames of one member at one output step.
type Snapshot = (Vec<Vector3<f64>>, Vec<UnitQuaternion<f64>>);

/// Positions (m) and frames of structure 0's first member after every step of `text`.
fn trajectory(text: &str) -> Vec<Snapshot> {
    let compiled = scene(text).compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let mut out = Vec::new();
    loop {
        let s = run.state(0).members[0].as_framed().expect("a framed rod");
        out.push((s.positions().to_vec(), s.frames().to_vec()));
        if run.finished() {
            break;
        }
        let r = run.step();
        assert!(r.converged, "{r:?}");
    }
    out
}

#[test]
fn an_obstacle_that_is_never_touched_does_not_change_a_framed_rods_swing() {
    // The floor is 10 m below (its barrier never active), a sphere 1 m away: the run with
    // them is a ContactProblem stepped with friction, the run without them a plain
    // structure. Same motion to round-off means the contact problem hands the stepper the
    // same mass — the frames' rotary inertia with its chart — and adds nothing else.
    let far = r#"
[[obstacles]]
name = "floor"
friction = 0.5
shape = { kind = "plane", point = [0.0, 0.0, -10.0], normal = [0.0, 0.0, 1.0] }

[[obstacles]]
name = "ball"
shape = { kind = "sphere", center = [0.15, 1.0, 0.0], radius = 0.05 }
"#;
    for model in MODELS {
        for scheme in ["energy_conserving", "backward_euler"] {
            let free = trajectory(&swing_scene(model, scheme, ""));
            let near = trajectory(&swing_scene(model, scheme, far));
            assert_eq!(free.len(), near.len());
            let (mut dx, mut dq, mut swing, mut turn): (f64, f64, f64, f64) = (0.0, 0.0, 0.0, 0.0);
            for ((xa, qa), (xb, qb)) in free.iter().zip(&near) {
                for (a, b) in xa.iter().zip(xb) {
                    dx = dx.max((a - b).norm());
                }
                for (k, (a, b)) in qa.iter().zip(qb).enumerate() {
                    dq = dq.max(a.angle_to(b));
                    turn = turn.max(a.angle_to(&free[0].1[k]));
                }
                for (a, b) in xa.iter().zip(&free[0].0) {
                    swing = swing.max((a - b).norm());
                }
            }
            println!(
                "{model}, {scheme}: swing up to {swing:.3e} m and {turn:.3} rad; with the untouched obstacles positions differ by at most {dx:.2e} m, frames by {dq:.2e} rad"
            );
            assert!(swing > 0.01 && turn > 0.1, "{model}: the rod barely moved");
            assert!(
                dx <= 1e-12 * 0.3,
                "{model}, {scheme}: positions differ by {dx:e} m"
            );
            assert!(
                dq <= 1e-11,
                "{model}, {scheme}: frames differ by {dq:e} rad"
            );
        }
    }
}

/// The clamped shaft struck by an end torque (tests/scenes/twisted_shaft.toml: a Cosserat
/// rod, L = 1 m, d = 10 mm, T = 5 N m about its axis).
const SHAFT: &str = include_str!("scenes/twisted_shaft.toml");

/// Times (s) and twist (rad) of the shaft's last frame about x, after every step of `text`
/// (frame output every step), and the smallest floor gap (m) seen (∞ without obstacles).
fn twist_history(text: &str) -> (Vec<f64>, Vec<f64>, f64) {
    let compiled = scene(text).compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let rest = *run.state(0).members[0]
        .as_framed()
        .unwrap()
        .frames()
        .last()
        .unwrap();
    let (mut t, mut twist, mut gap) = (vec![], vec![], f64::INFINITY);
    loop {
        let s = run.state(0).members[0].as_framed().unwrap();
        t.push(run.time());
        twist.push(
            (s.frames().last().unwrap() * rest.inverse())
                .scaled_axis()
                .x,
        );
        if let Some(g) = run.frame(0).min_gap {
            gap = gap.min(g);
        }
        if run.finished() {
            break;
        }
        let r = run.step();
        assert!(r.converged, "{r:?}");
    }
    (t, twist, gap)
}

#[test]
fn a_shaft_lying_on_a_floor_twists_with_the_period_of_its_rotary_inertia() {
    // The shaft under gravity, lying on a floor with friction at the gap where the default
    // barrier carries its weight (ĝ/2 = 0.5 µm). The floor pushes on the centerline and
    // cannot twist it, so the torsion wave is the free shaft's: its period 4L/c,
    // c = √(GJ/(ρJ)), is set by the frames' rotary inertia ρJ, which only the stepper's
    // frames carry (the vertices' mass does not turn them).
    let (e, nu, rho, d, length, torque) = (2.0e11_f64, 0.3, 7850.0, 0.01_f64, 1.0, 5.0);
    let g_mod = e / (2.0 * (1.0 + nu));
    let j = std::f64::consts::PI * d.powi(4) / 32.0;
    let period = 4.0 * length / (g_mod / rho).sqrt();
    let free = SHAFT
        .replace("scheme = \"midpoint\"", "scheme = \"energy_conserving\"")
        .replace("output_every = 10", "output_every = 1");
    let on_floor = free.replace(
        "gravity = [0.0, 0.0, 0.0]",
        &format!("gravity = [0.0, 0.0, -{G}]"),
    ) + &format!(
        r#"
[[obstacles]]
name = "floor"
friction = 0.3
shape = {{ kind = "plane", point = [0.0, 0.0, {z}], normal = [0.0, 0.0, 1.0] }}
"#,
        z = -0.5 * d - 0.5e-6
    );
    let (t, free_twist, _) = twist_history(&free);
    let (t2, twist, gap) = twist_history(&on_floor);
    assert_eq!(t, t2);
    let peak = twist.iter().cloned().fold(f64::MIN, f64::max);
    let n = twist.len() - 1;
    // The static twist of the last frame, at arc length L − ℓ/2 (an edge's midpoint).
    let static_twist = torque * (1.0 - 0.5 / 40.0) * length / (g_mod * j);
    let dt = t[1] - t[0];
    let n_period = (period / dt).round() as usize;
    let mean = twist[..=n_period]
        .windows(2)
        .map(|w| 0.5 * (w[0] + w[1]) * dt)
        .sum::<f64>()
        / (n_period as f64 * dt);
    let k_peak = (0..n_period)
        .max_by(|&a, &b| twist[a].total_cmp(&twist[b]))
        .unwrap();
    let k_back = (k_peak..n).find(|&k| twist[k + 1] > twist[k]).unwrap();
    let back = t[k_back];
    let difference = twist
        .iter()
        .zip(&free_twist)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!(
        "shaft on a floor: twist back to rest at {back:.4e} s (4L/c = {period:.4e} s, {:+.2e}), mean over a period / (Ts/GJ) − 1 = {:+.2e}, peak {peak:.5} rad; differs from the free shaft's twist by at most {:.2e} of the peak; smallest floor gap {gap:.3e} m",
        back / period - 1.0,
        mean / static_twist - 1.0,
        difference / peak
    );
    assert!(gap > 0.0 && gap < 1e-6, "gap {gap:e}");
    assert!((back / period - 1.0).abs() < 2e-2, "return at {back} s");
    assert!(
        (mean / static_twist - 1.0).abs() < 1e-2,
        "mean twist {mean}"
    );
    assert!(difference <= 1e-3 * peak, "differs by {difference:e} rad");
}

/// Two `model` rods lying on a rough floor along x at y = ±5 cm and a third dropped across
/// them from `drop` m above, with self-contact (the section of [`drop_scene`]'s rod).
fn stack_scene(model: &str, drop: f64) -> String {
    let r = 0.5 * D;
    let rod = |name: &str, start: [f64; 3], direction: [f64; 3]| {
        format!(
            r#"
[[rods]]
name = "{name}"
model = "{model}"
elements = 10
centerline = {{ kind = "straight", start = {start:?}, direction = {direction:?}, length = {L} }}
section = {{ shape = "circle", diameter = {D} }}
material = {{ young = 2.0e11, poisson = 0.3, density = {RHO} }}
"#
        )
    };
    // Lower rods at ĝ/2 over the floor (the default activation is 1e-6 L).
    let z = r + 0.5e-6 * L;
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]
{}{}{}
[[obstacles]]
name = "floor"
friction = 0.5
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[contact]
self_contact = true

[time]
dt = 1e-3
duration = 0.3
scheme = "backward_euler"
"#,
        rod("left", [0.0, -0.05, z], [1.0, 0.0, 0.0]),
        rod("right", [0.0, 0.05, z], [1.0, 0.0, 0.0]),
        rod("top", [0.1, -0.5 * L, z + 2.0 * r + drop], [0.0, 1.0, 0.0]),
    )
}

#[test]
fn a_framed_rod_dropped_across_two_others_comes_to_rest_on_them() {
    for model in MODELS {
        let compiled = scene(&stack_scene(model, 0.002))
            .compile()
            .expect("compiles");
        let mut run = TimeRun::new(&compiled).expect("starts");
        let (mut min_gap, mut min_segment_gap) = (f64::INFINITY, f64::INFINITY);
        loop {
            let f = run.frame(0);
            min_gap = min_gap.min(f.min_gap.unwrap_or(f64::INFINITY));
            min_segment_gap = min_segment_gap.min(f.min_segment_gap.unwrap_or(f64::INFINITY));
            if run.finished() {
                break;
            }
            let r = run.step();
            assert!(r.converged, "{model}: {r:?}");
        }
        let last = run.frame(1);
        let mut on_top = Vector3::zeros();
        let contacts = last
            .segment_contacts
            .as_ref()
            .expect("self-contact results");
        for c in contacts {
            if c.rod_a == "top" {
                on_top += Vector3::from(c.force_a);
            }
            if c.rod_b == "top" {
                on_top += Vector3::from(c.force_b);
            }
        }
        let floor = Vector3::from(last.obstacles[0].force);
        let kinetic = last.time.as_ref().unwrap().energy.kinetic;
        println!(
            "{model}: stack at rest after 0.3 s: {} segment contacts carry the top rod's weight to {:+.2e}, the floor all three to {:+.2e}, smallest gaps seen: floor {min_gap:.3e} m, segments {min_segment_gap:.3e} m, kinetic {kinetic:.2e} J",
            contacts.len(),
            on_top.z / weight() - 1.0,
            floor.z / (3.0 * weight()) - 1.0,
        );
        assert!(min_gap > 0.0 && min_segment_gap > 0.0);
        assert!(
            !contacts.is_empty(),
            "{model}: the top rod does not rest on the others"
        );
        assert!(
            (on_top.z / weight() - 1.0).abs() < 1e-6,
            "{model}: {on_top:?}"
        );
        assert!(
            (floor.z / (3.0 * weight()) - 1.0).abs() < 1e-6,
            "{model}: {floor:?}"
        );
        assert!(
            kinetic < 1e-12 * weight() * L,
            "{model}: still moving ({kinetic:e} J)"
        );
    }
}

/// tests/scenes/cosserat_cable_dropped_on_bracket.toml.
const DROPPED_CABLE: &str = include_str!("scenes/cosserat_cable_dropped_on_bracket.toml");

#[test]
fn the_cosserat_cable_dropped_on_a_bracket_scene_comes_to_rest_balanced_on_both_obstacles() {
    // The scene's data: L = 0.8 m, d = 8 mm, ρ = 1500 kg/m³, radius 4 mm, tray μ = 0.4.
    let (length, d, rho, mu) = (0.8_f64, 0.008_f64, 1500.0, 0.4);
    let weight = rho * std::f64::consts::PI * d * d / 4.0 * length * G;
    for model in MODELS {
        let text = DROPPED_CABLE.replace("model = \"cosserat\"", &format!("model = \"{model}\""));
        let compiled = scene(&text).compile().expect("compiles");
        let mut run = TimeRun::new(&compiled).expect("starts");
        let mut lowest: f64 = f64::INFINITY;
        while !run.finished() {
            let r = run.step();
            assert!(r.converged, "{model}: {r:?}");
            lowest = lowest.min(run.frame(0).min_gap.unwrap_or(f64::INFINITY));
        }
        let last = run.frame(1);
        let rod = &last.rods[0];
        let clamp = Vector3::from(rod.supports[0].force);
        let obstacles: Vector3<f64> = last.obstacles.iter().map(|o| Vector3::from(o.force)).sum();
        let imbalance = (clamp + obstacles + Vector3::new(0.0, 0.0, -weight)).norm();
        let mut cone: f64 = 0.0;
        for c in &last.obstacles[1].contacts {
            let (n, f) = (
                Vector3::from(c.normal_force),
                Vector3::from(c.friction_force),
            );
            cone = cone.max(f.norm() / (mu * n.norm()));
        }
        let kinetic = last.time.as_ref().unwrap().energy.kinetic;
        println!(
            "{model} cable on bracket and tray at t = 2 s: {} + {} contacts, clamp {:.4} N, bracket {:.4} N, tray {:.4} N of weight {weight:.4} N, imbalance {:.2e} of it, largest |friction|/(μ f_n) {cone:.4}, lowest gap over the run {lowest:.3e} m, kinetic {kinetic:.2e} J",
            last.obstacles[0].contacts.len(),
            last.obstacles[1].contacts.len(),
            clamp.z,
            last.obstacles[0].force[2],
            last.obstacles[1].force[2],
            imbalance / weight
        );
        assert!(lowest > 0.0, "{model}: a gap closed ({lowest:e} m)");
        assert!(
            last.obstacles.iter().all(|o| !o.contacts.is_empty()),
            "{model}: the cable does not rest on both obstacles"
        );
        assert!(
            imbalance <= 1e-6 * weight,
            "{model}: imbalance {imbalance:e} N"
        );
        assert!(
            cone <= 1.0 + 1e-9,
            "{model}: friction outside the cone ({cone})"
        );
    }
}
