//! Time stepping of scenes with contact (`[time]` with `[[obstacles]]`, `[contact]`): a stiff
//! rod dropped flat onto a frictionless floor falls freely — the scheme's exact discrete free
//! fall, ½ g t² for the energy-conserving scheme and ½ g t (t + h) for backward Euler — until
//! the barrier's activation distance, never penetrates, and then bounces back to its height
//! (energy-conserving) or comes to rest on the floor carrying its weight (backward Euler);
//! what time stepping with contact refuses is named.

use crate::common;
use common::dropped_rod::{drop, scene, weight, D, G, L};

/// The discrete elastic rod lying flat at `z0` over the floor (see
/// [`common::dropped_rod::drop_scene`]).
fn drop_scene(z0: f64, mu: f64, contact: &str, time: &str) -> String {
    common::dropped_rod::drop_scene("der", z0, mu, contact, time)
}

#[test]
fn a_rod_dropped_on_a_frictionless_floor_falls_freely_never_penetrates_and_bounces_back() {
    // Energy-conserving: the impact's kinetic energy is stored in the barrier at the lowest
    // point, κ ĝ² ln(ĝ/g) ≈ q h per length, i.e. ln(ĝ/g) ≈ 1.19 h/ĝ: a drop of a few ĝ
    // (here 5 mm onto ĝ = 1 mm: g ≈ 2.6e-6 m). Measured: with ĝ = 2 mm, a 2 cm drop's step
    // at the lowest point (g ≈ 5e-8 m) does not converge.
    let (h, activation) = (0.005, 1e-3);
    let z0 = 0.5 * D + h;
    let dt = 1e-4;
    let text = drop_scene(
        z0,
        0.0,
        &format!("activation = {activation}"),
        &format!("dt = {dt}\nduration = 0.08\nscheme = \"energy_conserving\""),
    );
    let (samples, last) = drop(&text);
    let mut free_fall_error: f64 = 0.0;
    let mut free_steps = 0;
    for s in &samples {
        assert!(s.gap > 0.0, "t = {}: gap {:e}", s.t, s.gap);
        // Before the barrier is active the rod falls freely.
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
        "energy-conserving drop from {h} m: free fall over {free_steps} steps within {free_fall_error:.2e} m of z0 − ½ g t², lowest gap {lowest:.3e} m, back up to {:.6} of the drop height, min gap reported {:?}",
        (rebound - 0.5 * D) / h,
        last.min_gap
    );
    assert!(free_steps > 50);
    assert!(free_fall_error <= 1e-12, "{free_fall_error:e}");
    assert!(lowest > 0.0 && lowest < activation);
    // Frictionless and energy-conserving: it bounces back up to nearly its drop height.
    assert!(
        ((rebound - 0.5 * D) / h - 1.0).abs() < 1e-2,
        "rebound {rebound}"
    );
}

#[test]
fn a_rod_dropped_on_a_floor_with_backward_euler_comes_to_rest_carrying_its_weight() {
    let h = 0.02;
    let z0 = 0.5 * D + h;
    let dt = 1e-3;
    let activation = 1e-6 * L; // the default
    for mu in [0.0, 0.4] {
        let text = drop_scene(
            z0,
            mu,
            "",
            &format!("dt = {dt}\nduration = 0.3\nscheme = \"backward_euler\""),
        );
        let (samples, last) = drop(&text);
        // Backward Euler's discrete free fall: z_n = z0 − ½ g t_n (t_n + h), exactly.
        let mut free_fall_error: f64 = 0.0;
        for s in &samples {
            assert!(s.gap > 0.0, "μ = {mu}, t = {}: gap {:e}", s.t, s.gap);
            let exact = z0 - 0.5 * G * s.t * (s.t + dt);
            if exact - 0.5 * D > activation + G * dt * (s.t + dt) {
                free_fall_error = free_fall_error.max((s.z - exact).abs());
            }
        }
        let floor = &last.obstacles[0];
        let (gap, fz) = (last.min_gap.unwrap(), floor.force[2]);
        let kinetic = last.time.as_ref().unwrap().energy.kinetic;
        println!(
            "backward Euler drop, μ = {mu}: free fall within {free_fall_error:.2e} m of z0 − ½ g t (t + h), at rest: {} contacts, gap {gap:.3e} m (ĝ {activation:.1e}), floor force / weight = {:.12}, kinetic {kinetic:.2e} J, applied {:?}, imbalance {:e}",
            floor.contacts.len(),
            fz / weight(),
            last.rods[0].applied_force, last.rods[0].relative_force_imbalance
        );
        assert!(free_fall_error <= 1e-12, "{free_fall_error:e}");
        assert!(gap > 0.0 && gap < activation, "{gap:e}");
        assert_eq!(floor.contacts.len(), 11, "every vertex on the floor");
        assert!((fz / weight() - 1.0).abs() < 1e-6, "{fz} vs {}", weight());
        assert!(floor.force[0].abs() + floor.force[1].abs() < 1e-9 * weight());
    }
}

#[test]
fn time_stepping_with_contact_refuses_the_midpoint_rule() {
    let text = drop_scene(
        0.1,
        0.0,
        "",
        "dt = 0.001\nduration = 0.1\nscheme = \"midpoint\"",
    );
    let e = scene(&text).compile().expect_err("refused");
    println!("{}: {}", e.path, e.message);
    assert_eq!(e.path, "time.scheme");
    assert!(e.message.contains("backward_euler"), "{}", e.message);
}
