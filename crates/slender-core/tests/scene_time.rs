//! Time stepping of scene files (`[time]`): a stiff pinned rod released at an angle swings
//! with the period of the rigid compound pendulum (elliptic integral, computed here from the
//! lumped masses; a scene that can move rigidly is accepted with `[time]` only); backward Euler and Rayleigh damping only lose energy; scenes without
//! `[time]` are untouched; bad tables and what time stepping does not cover are refused
//! naming the field.

use slender_core::scene::{Scene, Session, TimeRun};

use crate::common;
use common::elliptic_ke;

fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

const G: f64 = 9.81;

/// A steel rod (d = 10 mm, E = 200 GPa), `length` long, pinned at its top end, at rest at
/// angle `theta0` from the downward vertical in the x–z plane.
fn pendulum(length: f64, n: usize, theta0: f64, time: &str) -> String {
    let (s, c) = theta0.sin_cos();
    format!(
        r#"
gravity = [0.0, 0.0, -{G}]

[[rods]]
name = "pendulum"
elements = {n}
centerline = {{ kind = "straight", start = [0.0, 0.0, 0.0], direction = [{s}, 0.0, {mc}], length = {length} }}
section = {{ shape = "circle", diameter = 0.01 }}
material = {{ young = 2.0e11, poisson = 0.3, density = 7850.0 }}
supports = [{{ kind = "pin", vertex = "start" }}]

[time]
{time}
"#,
        mc = -c
    )
}

/// Times (s) at which `x` crosses zero, linearly interpolated.
fn zero_crossings(t: &[f64], x: &[f64]) -> Vec<f64> {
    (1..x.len())
        .filter(|&i| x[i - 1] * x[i] < 0.0)
        .map(|i| t[i - 1] + (t[i] - t[i - 1]) * x[i - 1] / (x[i - 1] - x[i]))
        .collect()
}

/// Runs a scene to its end: (times, tip x, total energies, kinetic energies).
fn history(spec: &Scene) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let compiled = spec.compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let (mut t, mut x, mut total, mut kinetic) = (vec![], vec![], vec![], vec![]);
    loop {
        let p = run.state(0).members[0].positions();
        t.push(run.time());
        x.push(p[p.len() - 1].x);
        let e = run.energy();
        total.push(e.total);
        kinetic.push(e.kinetic);
        if run.finished() {
            break;
        }
        let r = run.step();
        assert!(r.converged, "{r:?}");
    }
    (t, x, total, kinetic)
}

#[test]
fn a_stiff_pinned_rod_swings_with_the_period_of_the_rigid_pendulum() {
    let (length, n, theta0) = (0.5, 20, 0.3);
    let spec = scene(&pendulum(
        length,
        n,
        theta0,
        "dt = 0.001\nduration = 2.5\noutput_every = 1",
    ));
    let (t, x, total, kinetic) = history(&spec);
    let crossings = zero_crossings(&t, &x);
    assert!(crossings.len() >= 4, "{crossings:?}");
    let measured = 2.0 * (crossings[3] - crossings[0]) / 3.0;
    // The rigid compound pendulum of the rod's lumped masses (ρA h, halves at the ends):
    // T = 4 √(I / (M g d)) K(sin²(θ₀/2)), I = Σ mᵢ rᵢ², d = L/2 (exact for this lumping).
    let h = length / n as f64;
    let m = |i: usize| if i == 0 || i == n { 0.5 * h } else { h };
    let inertia: f64 = (0..=n).map(|i| m(i) * (i as f64 * h).powi(2)).sum();
    let mass: f64 = (0..=n).map(m).sum();
    let (k, _) = elliptic_ke((theta0 / 2.0).sin().powi(2));
    let reference = 4.0 * (inertia / (mass * G * length / 2.0)).sqrt() * k;
    let error = (measured - reference).abs() / reference;
    let drift = total.iter().map(|e| e.abs()).fold(0.0, f64::max)
        / kinetic.iter().copied().fold(0.0, f64::max);
    println!(
        "pinned rod, θ0 = {theta0}: period {measured:.6} s, rigid pendulum {reference:.6} s, \
         relative difference {error:.2e}; max |E - E0| / max kinetic {drift:.2e}"
    );
    assert!(error < 2e-4, "period {measured} vs {reference}");
    assert!(drift < 1e-5, "energy drift {drift:e}");
}

#[test]
fn backward_euler_and_rayleigh_damping_only_lose_energy() {
    for time in [
        "dt = 0.002\nduration = 0.5\nscheme = \"backward_euler\"",
        "dt = 0.002\nduration = 0.5\nscheme = \"midpoint\"\nrayleigh_mass = 2.0",
        "dt = 0.002\nduration = 0.5\nrayleigh_stiffness = 1e-4",
    ] {
        let spec = scene(&pendulum(0.5, 10, 0.5, time));
        let (_, _, total, kinetic) = history(&spec);
        let scale = kinetic.iter().copied().fold(0.0, f64::max);
        assert!(scale > 0.0);
        for w in total.windows(2) {
            assert!(w[1] <= w[0] + 1e-9 * scale, "{time}: energy rose {w:?}");
        }
        assert!(
            *total.last().unwrap() < -1e-3 * scale,
            "{time}: no energy lost ({})",
            total.last().unwrap()
        );
    }
}

#[test]
fn the_default_output_interval_gives_at_most_about_200_frames() {
    let spec = scene(&pendulum(0.5, 4, 0.3, "dt = 0.001\nduration = 1.0"));
    let t = spec.compile().unwrap().time.unwrap();
    assert_eq!(t.steps, 1000);
    assert_eq!(t.output_every, 5);
    assert_eq!(t.frames(), 201);
    // A duration that is not a multiple of dt is covered by whole steps.
    let spec = scene(&pendulum(0.5, 4, 0.3, "dt = 0.3\nduration = 1.0"));
    let t = spec.compile().unwrap().time.unwrap();
    assert_eq!((t.steps, t.output_every, t.frames()), (4, 1, 5));
}

#[test]
fn a_scene_without_time_is_unchanged() {
    let text = pendulum(0.5, 4, 0.3, "dt = 0.01\nduration = 0.1");
    // A pendulum is refused without [time] (it can move rigidly: no equilibrium to solve).
    let without = text.split("[time]").next().unwrap();
    let e = scene(without).compile().unwrap_err();
    assert_eq!(e.path, "rods[0].supports", "{e}");
    let spec = scene(&without.replace("\"pin\"", "\"clamp\""));
    assert!(spec.time.is_none());
    // The scene gains no key when saved, its results no frame time (and result.json no
    // "time" key: it is skipped when absent).
    assert!(!toml::to_string(&spec).unwrap().contains("[time]"));
    let compiled = spec.compile().unwrap();
    assert!(compiled.time.is_none());
    let step = Session::from_compiled(spec.clone(), compiled).results(0, None, 1.0, 1);
    assert!(step.time.is_none());
    assert!(TimeRun::new(&spec.compile().unwrap()).is_err());
    // The Session solves equilibria and ignores [time]: the time-stepped pendulum is refused
    // there as it is without [time].
    assert!(Session::new(scene(&text)).is_err());
}

fn error_path(text: &str) -> String {
    match scene(text).compile() {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => {
            println!("{e}");
            e.path
        }
    }
}

#[test]
fn bad_time_tables_and_what_time_stepping_does_not_cover_are_refused_naming_the_field() {
    let p = |time: &str| pendulum(0.5, 4, 0.3, time);
    assert_eq!(error_path(&p("dt = 0.0\nduration = 1.0")), "time.dt");
    assert_eq!(error_path(&p("dt = -1e-3\nduration = 1.0")), "time.dt");
    assert_eq!(error_path(&p("dt = nan\nduration = 1.0")), "time.dt");
    assert_eq!(error_path(&p("dt = inf\nduration = 1.0")), "time.dt");
    assert_eq!(error_path(&p("dt = 0.1\nduration = 0.05")), "time.duration");
    assert_eq!(error_path(&p("dt = 0.1\nduration = nan")), "time.duration");
    assert_eq!(
        error_path(&p("dt = 1e-12\nduration = 1.0")),
        "time.duration"
    );
    assert_eq!(
        error_path(&p("dt = 0.1\nduration = 1.0\nrayleigh_mass = -1.0")),
        "time.rayleigh_mass"
    );
    assert_eq!(
        error_path(&p("dt = 0.1\nduration = 1.0\nrayleigh_stiffness = nan")),
        "time.rayleigh_stiffness"
    );
    assert_eq!(
        error_path(&p("dt = 0.1\nduration = 1.0\noutput_every = 0")),
        "time.output_every"
    );
    assert!(scene(&p("dt = 0.1\nduration = 1.0")).compile().is_ok());
    // Unknown keys and schemes are parse errors.
    for bad in [
        "dt = 0.1\nduration = 1.0\ndtt = 1.0",
        "dt = 0.1\nduration = 1.0\nscheme = \"rk4\"",
        "duration = 1.0",
    ] {
        assert!(toml::from_str::<Scene>(&p(bad)).is_err(), "{bad}");
    }
    let ok = p("dt = 0.1\nduration = 1.0");
    // Every rod model is stepped (a Cosserat rod or SE(3) beam needs a clamp or three pins,
    // with or without [time]).
    for model in ["cosserat", "cosserat_tan", "se3"] {
        let clamped = ok
            .replace(
                "name = \"pendulum\"",
                &format!("name = \"pendulum\"\nmodel = \"{model}\""),
            )
            .replace("kind = \"pin\"", "kind = \"clamp\"");
        assert!(scene(&clamped).compile().is_ok(), "{model}");
    }
    let follower = ok.replace(
        "supports = [",
        "forces = [{ vertex = \"end\", force = [0.0, 0.0, 1.0], follower = true }]\nsupports = [",
    );
    assert_eq!(error_path(&follower), "rods[0].forces[0].follower");
    let motion = format!("{ok}\n[[motion]]\nrod = 0\nsupport = 0\ntranslate = [0.1, 0.0, 0.0]\n");
    assert_eq!(error_path(&motion), "motion");
    let shells = format!(
        "{ok}\n[[shells]]\nlength = 0.2\nwidth = 0.02\nthickness = 0.001\nmaterial = {{ young = 1e9, poisson = 0.3, density = 1000.0 }}\n"
    );
    assert_eq!(error_path(&shells), "shells");
}
