//! The dropped rod of the time-stepped contact tests: a stiff steel rod lying flat over a
//! floor, its scene text and a run that samples every step.

use slender_core::scene::{Scene, SceneStep, TimeRun};

/// Gravity (m/s²).
pub const G: f64 = 9.81;
/// The rod: steel, L = 0.2 m, d = 10 mm, 10 elements, free, horizontal along x.
pub const L: f64 = 0.2;
/// Its diameter (m).
pub const D: f64 = 0.01;
/// Its density (kg/m³).
pub const RHO: f64 = 7850.0;

/// The rod's weight (N).
pub fn weight() -> f64 {
    RHO * std::f64::consts::PI * D * D / 4.0 * L * G
}

/// A scene from its text.
pub fn scene(text: &str) -> Scene {
    toml::from_str(text).expect("scene")
}

/// A rod of model `model` lying flat with its axis at `z0` over a floor z = 0 with Coulomb
/// coefficient `mu`; `contact` and `time` are the bodies of the `[contact]` and `[time]`
/// tables.
pub fn drop_scene(model: &str, z0: f64, mu: f64, contact: &str, time: &str) -> String {
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
pub struct Sample {
    pub t: f64,
    pub z: f64,
    pub gap: f64,
}

/// Runs a drop scene to its end, sampling every step (the gap from the positions here).
pub fn drop(text: &str) -> (Vec<Sample>, SceneStep) {
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
