//! Speed of one implicit time step (one core): a clamped 100-element rod swinging under
//! gravity with h = 1 ms, for each scheme (target to note: ≤ 1 ms per step); the same swing
//! of a 100-element discrete Cosserat rod (frames with rotary inertia).
//!
//! Run with `cargo bench -p slender-core --bench dynamics_step`. Each iteration is one
//! `TimeStepper::step` from one of ten snapshots of the first second of the swing (taken in
//! turn; cloning the snapshot is outside the timed part), so every scheme is timed on the
//! same states, all of them moving.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use slender_core::dynamics::{DynamicsParams, FlatDofs, Scheme, TimeStepper};
use slender_core::geometry::Vec3;
use slender_core::rod::{RestCurve, Rod, RodBuilder, RodProperties, SectionStiffness};

/// The README's cable (EA 9.21e5 N, EI 4.5e-2 N m², GJ 3.75e-2 N m², ρA 0.281 kg/m), 1 m,
/// clamped at the start, held horizontal under gravity and released (Γ ≈ 61).
fn swinging_rod() -> Rod {
    RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        RodProperties {
            stiffness: SectionStiffness::isotropic(9.21e5, 4.5e-2, 3.75e-2),
            linear_density: 0.281,
        },
    )
    .elements(100)
    .clamp_start()
    .gravity(Vec3::new(0.0, -9.81, 0.0))
    .build()
    .expect("valid rod")
}

/// One step of each scheme of `model` (released at rest from `rest`), timed from ten
/// snapshots of its first second, in the criterion group `name`.
fn bench_schemes<P: FlatDofs>(c: &mut Criterion, name: &str, model: &P, rest: P::State) {
    let mut group = c.benchmark_group(name);
    group.measurement_time(Duration::from_secs(5));
    for scheme in [
        Scheme::EnergyConserving,
        Scheme::ImplicitMidpoint,
        Scheme::BackwardEuler,
    ] {
        let params = DynamicsParams::new(1e-3).with_scheme(scheme);
        let mut stepper = TimeStepper::at_rest(model, rest.clone(), params).expect("valid params");
        let mut snapshots = Vec::new();
        for k in 0..1000 {
            let r = stepper.step();
            assert!(r.converged, "{scheme:?} {r:?}");
            if k % 100 == 50 {
                snapshots.push(stepper.clone());
            }
        }
        let mut next = 0;
        group.bench_function(format!("{scheme:?}"), |b| {
            b.iter_batched(
                || {
                    next = (next + 1) % snapshots.len();
                    snapshots[next].clone()
                },
                |mut s| {
                    let r = s.step();
                    assert!(r.converged, "{r:?}");
                    black_box(r.iterations)
                },
                BatchSize::SmallInput,
            )
        });
    }
    group.finish();
}

fn bench(c: &mut Criterion) {
    let rod = swinging_rod();
    bench_schemes(c, "dynamics_step_n100", &rod, rod.rest_state().clone());
}

/// The same cable lying on a rough plane (μ = 0.3) tilted past its friction angle (tan α =
/// 0.4): every vertex in contact, sliding. One step with friction (`step_with_friction`, the
/// stick/slide set settled), backward Euler, from snapshots of the slide.
fn bench_contact(c: &mut Criterion) {
    use slender_core::contact::{step_with_friction, ContactParams, ContactProblem, Plane};
    let (radius, g, alpha) = (0.006, 9.81, 0.4f64.atan());
    let activation = 1e-6;
    let rod = RodBuilder::new(
        RestCurve::Straight {
            start: [0.0, 0.0, radius + 0.5 * activation],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        RodProperties {
            stiffness: SectionStiffness::isotropic(9.21e5, 4.5e-2, 3.75e-2),
            linear_density: 0.281,
        },
    )
    .elements(100)
    .allow_rigid_motion()
    .gravity(Vec3::new(alpha.sin(), 0.0, -alpha.cos()) * g)
    .build()
    .expect("valid rod");
    let plane = Plane::new(Vec3::zeros(), Vec3::z(), 0.3).expect("plane");
    let params = ContactParams::for_line_load(radius, activation, 0.281 * g * alpha.cos());
    let start = rod.rest_state().clone();
    let problem = ContactProblem::new(&rod, vec![std::sync::Arc::new(plane)], params, &start)
        .expect("contact");
    problem.update_friction(&start, None);
    let dynamics = DynamicsParams::new(1e-3).with_scheme(Scheme::BackwardEuler);
    let mut stepper = TimeStepper::at_rest(&problem, start, dynamics).expect("stepper");
    let mut snapshots = Vec::new();
    for k in 0..200 {
        let r = step_with_friction(&mut stepper, &problem);
        assert!(r.converged, "{r:?}");
        if k % 20 == 10 {
            snapshots.push(stepper.clone());
        }
    }
    let mut next = 0;
    c.bench_function("dynamics_step_n100_on_rough_plane/BackwardEuler", |b| {
        b.iter_batched(
            || {
                next = (next + 1) % snapshots.len();
                snapshots[next].clone()
            },
            |mut s| {
                let r = step_with_friction(&mut s, &problem);
                assert!(r.converged, "{r:?}");
                black_box(r.iterations)
            },
            BatchSize::SmallInput,
        )
    });
}

/// The same cable as a 100-element discrete Cosserat rod (shear stiffness of the solid
/// circle), released under gravity; one step of each scheme from snapshots of its first
/// second, as for the discrete elastic rod.
fn bench_cosserat(c: &mut Criterion) {
    use slender_core::cosserat::CosseratBuilder;
    use slender_core::framed::ShearStiffness;
    let stiffness = SectionStiffness::isotropic(9.21e5, 4.5e-2, 3.75e-2);
    let rod = CosseratBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        RodProperties {
            stiffness,
            linear_density: 0.281,
        },
        ShearStiffness::solid_circle(&stiffness).expect("shear"),
    )
    .elements(100)
    .clamp_start()
    .gravity(Vec3::new(0.0, -9.81, 0.0))
    .build()
    .expect("valid rod");
    bench_schemes(
        c,
        "dynamics_step_cosserat_n100",
        &rod,
        rod.rest_state().clone(),
    );
}

criterion_group!(benches, bench, bench_contact, bench_cosserat);
criterion_main!(benches);
