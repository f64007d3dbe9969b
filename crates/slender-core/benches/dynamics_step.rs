//! Speed of one implicit time step (one core): a clamped 100-element rod swinging under
//! gravity with h = 1 ms, for each scheme (target to note: ≤ 1 ms per step).
//!
//! Run with `cargo bench -p slender-core --bench dynamics_step`. Each iteration is one
//! `TimeStepper::step` from one of ten snapshots of the first second of the swing (taken in
//! turn; cloning the snapshot is outside the timed part), so every scheme is timed on the
//! same states, all of them moving.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use slender_core::dynamics::{DynamicsParams, Scheme, TimeStepper};
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

fn bench(c: &mut Criterion) {
    let rod = swinging_rod();
    let mut group = c.benchmark_group("dynamics_step_n100");
    group.measurement_time(Duration::from_secs(5));
    for scheme in [
        Scheme::EnergyConserving,
        Scheme::ImplicitMidpoint,
        Scheme::BackwardEuler,
    ] {
        let params = DynamicsParams::new(1e-3).with_scheme(scheme);
        let mut stepper =
            TimeStepper::at_rest(&rod, rod.rest_state().clone(), params).expect("valid params");
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

criterion_group!(benches, bench);
criterion_main!(benches);
