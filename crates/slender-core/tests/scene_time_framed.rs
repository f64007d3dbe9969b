//! Time stepping of scenes with Cosserat rods and SE(3) beams (`[time]`): the example
//! `tests/scenes/twisted_shaft.toml` (a clamped shaft struck by an end torque) against the
//! Saint-Venant torsion wave — the twist at arc length s averages Ts/(GJ) over a period,
//! peaks near 2Ts/(GJ) and first returns to rest at t = 4L/c, c = √(GJ/(ρJ)) —, with energy
//! conserved; the same scene with an SE(3) beam.

use nalgebra::UnitQuaternion;
use slender_core::scene::{Scene, TimeRun};

const SCENE: &str = include_str!("scenes/twisted_shaft.toml");

/// (times, twist of the last frame about x (rad), total energies, largest kinetic energy,
/// arc length of the last frame as a fraction of the length: a Cosserat rod's frames sit at
/// its edges' midpoints).
fn history(text: &str) -> (Vec<f64>, Vec<f64>, Vec<f64>, f64, f64) {
    let spec: Scene = toml::from_str(text).expect("scene");
    let compiled = spec.compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let (rest, at): (UnitQuaternion<f64>, f64) = {
        let s = run.state(0).members[0].as_framed().expect("a framed rod");
        let n = s.positions().len() - 1;
        let at = if s.frames().len() == n {
            1.0 - 0.5 / n as f64
        } else {
            1.0
        };
        (*s.frames().last().unwrap(), at)
    };
    let (mut t, mut twist, mut total) = (vec![], vec![], vec![]);
    let mut kinetic: f64 = 0.0;
    loop {
        let s = run.state(0).members[0].as_framed().unwrap();
        let clamp = s.positions()[0];
        assert!(clamp.norm() == 0.0, "the clamp moved: {clamp}");
        t.push(run.time());
        twist.push(
            (s.frames().last().unwrap() * rest.inverse())
                .scaled_axis()
                .x,
        );
        let e = run.energy();
        total.push(e.total);
        kinetic = kinetic.max(e.kinetic);
        if run.finished() {
            break;
        }
        let r = run.step();
        assert!(r.converged, "{r:?}");
    }
    (t, twist, total, kinetic, at)
}

fn check(text: &str, name: &str) {
    // The scene's data: d = 10 mm steel, L = 1 m, T = 5 N m.
    let (e, nu, rho, d, length, torque) = (2.0e11_f64, 0.3, 7850.0, 0.01_f64, 1.0, 5.0);
    let g = e / (2.0 * (1.0 + nu));
    let j = std::f64::consts::PI * d.powi(4) / 32.0;
    let period = 4.0 * length / (g / rho).sqrt();
    let (t, twist, total, kinetic, at) = history(text);
    // The static twist of the last frame, at arc length `at`·L.
    let static_twist = torque * at * length / (g * j);
    let dt = t[1] - t[0];
    // Mean over the first period (trapezoid).
    let n_period = (period / dt).round() as usize;
    let mean = twist[..=n_period]
        .windows(2)
        .map(|w| 0.5 * (w[0] + w[1]) * dt)
        .sum::<f64>()
        / (n_period as f64 * dt);
    let peak = twist.iter().cloned().fold(f64::MIN, f64::max);
    // First return to rest: the first minimum after the peak of the first period.
    let k_peak = (0..n_period)
        .max_by(|&a, &b| twist[a].total_cmp(&twist[b]))
        .unwrap();
    let k_back = (k_peak..t.len() - 1)
        .find(|&k| twist[k + 1] > twist[k])
        .unwrap();
    let back = t[k_back];
    let drift = total
        .iter()
        .map(|x| (x - total[0]).abs())
        .fold(0.0, f64::max)
        / kinetic;
    println!(
        "{name}: last frame's twist mean over a period {mean:.5} rad (Ts/GJ = {static_twist:.5}, \
         {:+.2e}), peak {peak:.5} rad (2Ts/GJ = {:.5}, {:+.2e}), back to rest at {back:.4e} s \
         (4L/c = {period:.4e} s, {:+.2e}); max |E - E0| / max kinetic = {drift:.2e}",
        mean / static_twist - 1.0,
        2.0 * static_twist,
        peak / (2.0 * static_twist) - 1.0,
        back / period - 1.0
    );
    assert!(
        (mean / static_twist - 1.0).abs() < 1e-2,
        "{name}: mean twist {mean}"
    );
    assert!(
        (peak / (2.0 * static_twist) - 1.0).abs() < 0.1,
        "{name}: peak twist {peak}"
    );
    assert!(
        (back / period - 1.0).abs() < 2e-2,
        "{name}: return at {back} s"
    );
    assert!(drift < 1e-6, "{name}: energy drift {drift:.2e}");
}

#[test]
fn a_shaft_struck_by_a_torque_twists_as_the_saint_venant_wave() {
    check(SCENE, "cosserat");
    check(
        &SCENE.replace("model = \"cosserat\"", "model = \"se3\""),
        "se3",
    );
}
