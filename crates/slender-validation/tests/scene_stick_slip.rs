//! Romero's stick–slip test run as a scene file (`[time]` with a rough `[[obstacles]]` plane):
//! the same rods as the benchmark (`stick_slip::StickSlipCase`), written as scenes and stepped
//! by `scene::TimeRun`, scored against Coulomb's law with the benchmark's own closed form,
//! acceleration fit and targets — a rod on a slope steeper than atan μ slides with
//! g (sin α − μ cos α) to 1e-3, one on a gentler slope moves by at most 1e-9 of its length.
//! The same scenes with the rod modelled as a discrete Cosserat rod and as an SE(3) beam
//! (whose frames' rotary inertia the contact problem hands to the stepper) meet the same
//! targets.

use slender_core::scene::{Scene, TimeRun};
use slender_validation::stick_slip::fit::acceleration;
use slender_validation::stick_slip::sweep::{ACCELERATION_TARGET, DISPLACEMENT_TARGET};
use slender_validation::stick_slip::{exact_acceleration, StickSlipCase};

/// The benchmark's activation distance, as a fraction of the rod's length.
const ACTIVATION: f64 = 1e-6;

/// `case` as a scene: the rod along x at rest on the plane z = 0 (at the gap where the
/// barrier carries its normal load, as the benchmark starts it), gravity tilted by α so the
/// slope runs down along +x, backward Euler as in the benchmark; the rod's `model` as the
/// scene names it (`"der"`, `"cosserat"`, `"se3"`).
fn scene_text(case: &StickSlipCase, model: &str) -> String {
    let r = 0.5 * case.diameter;
    let activation = ACTIVATION * case.length;
    let rho_a = case.density * std::f64::consts::PI * r * r;
    // The barrier stiffness at which the normal load q cos α rests the rod at ĝ/2.
    let stiffness =
        rho_a * case.gravity * case.alpha.cos() / (activation * (0.5 + std::f64::consts::LN_2));
    let (s, c) = case.alpha.sin_cos();
    let g = case.gravity;
    format!(
        r#"
gravity = [{gx}, 0.0, {gz}]

[[rods]]
name = "rod"
model = "{model}"
elements = {n}
centerline = {{ kind = "straight", start = [0.0, 0.0, {z}], direction = [1.0, 0.0, 0.0], length = {l} }}
section = {{ shape = "circle", diameter = {d} }}
material = {{ young = {e}, poisson = 0.3, density = {rho} }}

[[obstacles]]
name = "slope"
friction = {mu}
shape = {{ kind = "plane", point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}

[contact]
activation = {activation}
stiffness = {stiffness}

[time]
dt = {dt}
duration = {duration}
scheme = "backward_euler"
output_every = 1
"#,
        gx = g * s,
        gz = -g * c,
        n = case.elements,
        z = r + 0.5 * activation,
        l = case.length,
        d = case.diameter,
        e = case.young,
        rho = case.density,
        mu = case.mu,
        dt = case.dt,
        duration = case.dt * case.steps as f64,
    )
}

/// What a scene run measured: largest centroid displacement (m), fitted acceleration down
/// the slope (m/s²), whether the last frame's contacts slide, Newton iterations.
struct SceneRun {
    displacement: f64,
    acceleration: f64,
    sliding: bool,
    iterations: usize,
}

fn run_scene(case: &StickSlipCase, model: &str) -> SceneRun {
    let spec: Scene = toml::from_str(&scene_text(case, model)).expect("scene");
    let compiled = spec.compile().expect("compiles");
    let mut run = TimeRun::new(&compiled).expect("starts");
    let centroid = |run: &TimeRun| {
        let p = run.state(0).members[0].positions();
        p.iter().sum::<nalgebra::Vector3<f64>>() / p.len() as f64
    };
    let c0 = centroid(&run);
    let mut samples = vec![(0.0, 0.0)];
    let (mut displacement, mut iterations) = (0.0f64, 0);
    while !run.finished() {
        let r = run.step();
        assert!(r.converged, "{:?}", r.failure);
        iterations += r.iterations;
        let d = centroid(&run) - c0;
        displacement = displacement.max(d.norm());
        samples.push((run.time(), d.x));
    }
    let last = run.frame(1);
    let contacts = &last.obstacles[0].contacts;
    assert!(!contacts.is_empty(), "the rod left the slope");
    SceneRun {
        displacement,
        acceleration: acceleration(&samples).expect("samples"),
        sliding: contacts.iter().all(|c| !c.sticking),
        iterations,
    }
}

/// Runs the two benchmark rods as `model` on slopes at 0.5, 0.99, 1.01 and 1.5 × atan μ
/// and checks Coulomb's law (see the module docs).
fn check_stick_slip(model: &str) {
    let base = StickSlipCase {
        mu: 0.3,
        alpha: 0.0,
        length: 1.0,
        elements: 20,
        diameter: 0.006,
        young: 1e9,
        density: 1400.0,
        gravity: 9.81,
        dt: 2e-3,
        steps: 60,
    };
    let rods = [
        base,
        StickSlipCase {
            young: 2e11,
            diameter: 0.002,
            density: 7800.0,
            length: 0.3,
            mu: 0.8,
            ..base
        },
    ];
    for rod in rods {
        for factor in [0.5, 0.99, 1.01, 1.5] {
            let case = StickSlipCase {
                alpha: (factor * rod.mu).atan(),
                ..rod
            };
            let r = run_scene(&case, model);
            let exact = exact_acceleration(case.gravity, case.alpha, case.mu);
            println!(
                "{model}, E = {:.0e}, μ = {}, tan α / μ = {factor}: sliding {}, displacement {:.3e} L, a = {:.9e} vs Coulomb {:.9e} (relative error {:.1e}), {} Newton iterations",
                case.young,
                case.mu,
                r.sliding,
                r.displacement / case.length,
                r.acceleration,
                exact.max(0.0),
                if exact > 0.0 { (r.acceleration - exact) / exact } else { 0.0 },
                r.iterations
            );
            if factor < 1.0 {
                assert!(!r.sliding, "slid below the threshold");
                assert!(
                    r.displacement <= DISPLACEMENT_TARGET * case.length,
                    "crept by {:e} L",
                    r.displacement / case.length
                );
            } else {
                assert!(r.sliding, "stuck above the threshold");
                let rel = (r.acceleration - exact) / exact;
                assert!(
                    rel.abs() <= ACCELERATION_TARGET,
                    "acceleration off by {rel:e}"
                );
            }
        }
    }
}

#[test]
fn a_rod_on_a_rough_slope_in_a_time_run_sticks_below_atan_mu_and_slides_at_coulombs_rate_above() {
    check_stick_slip("der");
}

#[test]
fn a_cosserat_rod_or_se3_beam_on_a_rough_slope_sticks_below_atan_mu_and_slides_at_coulombs_rate_above(
) {
    check_stick_slip("cosserat");
    check_stick_slip("se3");
}
