//! Speed of the discrete Cosserat rod and the SE(3) beam on the discrete elastic rod's
//! benchmark (`rod_solve.rs`): a cold N = 100 cantilever at Γ = 61.3 (Ω_bundle,
//! boundary-layer grading), solved from straight in one call, target ≤ 2 ms on one core; and
//! one assembly.
//!
//! Run with `cargo bench -p slender-core --bench framed_solve`. Results are summarized in
//! BENCHMARKS.md at the workspace root.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use slender_core::cosserat::CosseratBuilder;
use slender_core::framed::ShearStiffness;
use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, RodProperties, SectionStiffness};
use slender_core::se3::Se3Builder;
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};

const GAMMA: f64 = 61.3;
const ELEMENTS: usize = 100;
const EI: f64 = 4.5e-2;

/// Ω_bundle: EA 9.21e5 N, EI 4.5e-2 N m², GJ 3.75e-2 N m², ρA = 2485·π·(6 mm)² kg/m, L = 1 m;
/// κGA of a solid circle.
fn properties() -> (RodProperties, ShearStiffness) {
    let p = RodProperties {
        stiffness: SectionStiffness::isotropic(9.21e5, EI, 3.75e-2),
        linear_density: 2485.0 * std::f64::consts::PI * 36e-6,
    };
    (p, ShearStiffness::solid_circle(&p.stiffness).unwrap())
}

fn line() -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    }
}

fn gravity(p: &RodProperties) -> Vec3 {
    Vec3::new(0.0, -GAMMA * EI / p.linear_density, 0.0)
}

fn bench_model<P>(c: &mut Criterion, name: &str, rod: &P, rest: &P::State)
where
    P: EquilibriumProblem,
{
    let mut group = c.benchmark_group(format!("{name}_cold_solve_n100_gamma61"));
    for lambda in [true, false] {
        let params = SolverParams {
            compute_lambda_min: lambda,
            ..Default::default()
        };
        let mut solver = EquilibriumSolver::new(rod, rest, params);
        let report = solver.solve(rod, rest, 0.0, 1.0).report;
        assert!(report.converged(), "{name}: {:?}", report.status);
        eprintln!(
            "{name}: {} iterations, {} load steps",
            report.iterations, report.load_steps
        );
        let mut state = rest.clone();
        group.bench_function(
            if lambda {
                "with_lambda_min"
            } else {
                "no_lambda_min"
            },
            |b| {
                b.iter(|| {
                    state.clone_from(rest);
                    black_box(solver.solve_in_place(rod, &mut state, 0.0, 1.0));
                })
            },
        );
    }
    group.finish();
    let n = rod.n_free();
    let (mut g, mut a) = (vec![0.0; n], vec![0.0; n]);
    let mut h = rod.new_hessian();
    c.bench_function(&format!("{name}_assembly_n100"), |b| {
        b.iter(|| black_box(rod.assemble(rest, 1.0, &mut g, &mut h, &mut a)))
    });
}

fn benches(c: &mut Criterion) {
    let (p, shear) = properties();
    let cosserat = CosseratBuilder::new(line(), p, shear)
        .elements(ELEMENTS)
        .grading(Grading::BoundaryLayer { gamma: GAMMA })
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(gravity(&p))
        .build()
        .unwrap();
    bench_model(c, "cosserat", &cosserat, cosserat.rest_state());
    let se3 = Se3Builder::new(line(), p, shear)
        .elements(ELEMENTS)
        .grading(Grading::BoundaryLayer { gamma: GAMMA })
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(gravity(&p))
        .build()
        .unwrap();
    bench_model(c, "se3", &se3, se3.rest_state());
}

criterion_group! {
    name = framed;
    config = Criterion::default().measurement_time(Duration::from_secs(5)).sample_size(50);
    targets = benches
}
criterion_main!(framed);
