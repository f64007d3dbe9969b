//! Speed of the rod solver against the figures the project promises (one core):
//! a cold N = 100 solve in ≤ 2 ms and a warm re-solve in ≤ 200 µs.
//!
//! Run with `cargo bench -p slender-core --bench rod_solve`. Results are summarized in
//! BENCHMARKS.md at the workspace root.
//!
//! Every benchmark reuses one `EquilibriumSolver` across iterations (solver creation is outside
//! the timed loop), except `cold_solve_n100_gamma61/new_solver_each_iter`, which includes it.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use slender_core::geometry::Vec3;
use slender_core::linalg::{BandLdlt, SymmetricBandMatrix};
use slender_core::rod::{
    Grading, RestCurve, Rod, RodBuilder, RodProperties, RodState, SectionStiffness,
};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, SolverParams};

/// Dimensionless gravity load Γ = ρA g L³ / EI.
const GAMMA: f64 = 61.3;
const ELEMENTS: usize = 100;
const EI: f64 = 4.5e-2;

/// Ω_bundle: EA 9.21e5 N, EI 4.5e-2 N m², GJ 3.75e-2 N m², ρA = 2485·π·(6 mm)² kg/m, L = 1 m.
fn properties() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(9.21e5, EI, 3.75e-2),
        linear_density: 2485.0 * std::f64::consts::PI * 36e-6,
    }
}

/// Cantilever of `ELEMENTS` boundary-layer-graded elements under gravity `scale`·g(Γ).
fn cantilever(scale: f64) -> Rod {
    let props = properties();
    let g = GAMMA * EI / props.linear_density; // L = 1 m
    RodBuilder::new(
        RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 1.0,
        },
        props,
    )
    .elements(ELEMENTS)
    .grading(Grading::BoundaryLayer { gamma: GAMMA })
    .first_director(Vec3::z())
    .clamp_start()
    .gravity(Vec3::new(0.0, -g * scale, 0.0))
    .build()
    .unwrap()
}

fn params(lambda: bool) -> SolverParams {
    SolverParams {
        compute_lambda_min: lambda,
        ..Default::default()
    }
}

fn label(lambda: bool) -> &'static str {
    if lambda {
        "with_lambda_min"
    } else {
        "no_lambda_min"
    }
}

/// Cold solve from the straight rest state, ramping the load factor 0 → 1 in one call.
fn converged_state(rod: &Rod, lambda: bool, what: &str) -> RodState {
    let start = rod.rest_state().clone();
    let mut solver = EquilibriumSolver::new(rod, &start, params(lambda));
    let sol = solver.solve(rod, &start, 0.0, 1.0);
    assert!(
        sol.report.converged(),
        "{what}: cold solve did not converge: {:?}",
        sol.report.status
    );
    sol.state
}

fn cold_solve(c: &mut Criterion) {
    let rod = cantilever(1.0);
    let start = rod.rest_state().clone();
    let mut group = c.benchmark_group("cold_solve_n100_gamma61");
    for lambda in [true, false] {
        let mut solver = EquilibriumSolver::new(&rod, &start, params(lambda));
        let sol = solver.solve(&rod, &start, 0.0, 1.0);
        assert!(
            sol.report.converged(),
            "cold solve did not converge: {:?}",
            sol.report.status
        );
        println!(
            "cold_solve_n100_gamma61/{}: converged, {} Newton iterations in {} load steps ({} rejected), lambda_min_normalized = {:?}",
            label(lambda),
            sol.report.iterations,
            sol.report.load_steps,
            sol.report.rejected_steps,
            sol.report.lambda_min_normalized,
        );
        group.bench_function(label(lambda), |b| {
            b.iter(|| solver.solve(black_box(&rod), black_box(&start), 0.0, 1.0))
        });
    }
    // Same as with_lambda_min, but the solver (its buffers) is created inside the timed loop.
    group.bench_function("new_solver_each_iter", |b| {
        b.iter(|| {
            let mut solver = EquilibriumSolver::new(&rod, &start, params(true));
            solver.solve(black_box(&rod), black_box(&start), 0.0, 1.0)
        })
    });
    group.finish();
}

fn warm_resolve(c: &mut Criterion) {
    let rod = cantilever(1.0);
    let rod2 = cantilever(1.01);
    let mut group = c.benchmark_group("warm_resolve_gravity_plus_1pct");
    for lambda in [true, false] {
        let converged = converged_state(&rod, lambda, "warm_resolve");
        let mut solver = EquilibriumSolver::new(&rod2, &converged, params(lambda));
        let sol = solver.solve(&rod2, &converged, 1.0, 1.0);
        assert!(
            sol.report.converged(),
            "warm re-solve did not converge: {:?}",
            sol.report.status
        );
        println!(
            "warm_resolve_gravity_plus_1pct/{}: converged, {} Newton iterations",
            label(lambda),
            sol.report.iterations,
        );
        group.bench_function(label(lambda), |b| {
            b.iter(|| solver.solve(black_box(&rod2), black_box(&converged), 1.0, 1.0))
        });
    }
    group.finish();
}

fn assembly_and_factorization(c: &mut Criterion) {
    let rod = cantilever(1.0);
    let state = converged_state(&rod, false, "assembly");
    let n = rod.n_free();
    let mut grad = vec![0.0; n];
    let mut abs = vec![0.0; n];
    let mut hess = SymmetricBandMatrix::new(n, rod.half_bandwidth());
    println!(
        "assembly_n100: {n} free DOFs, half-bandwidth {} (state from a converged cold solve)",
        rod.half_bandwidth()
    );

    c.bench_function("assembly_n100", |b| {
        b.iter(|| rod.assemble(black_box(&state), 1.0, &mut grad, &mut hess, &mut abs))
    });

    rod.assemble(&state, 1.0, &mut grad, &mut hess, &mut abs);
    let mut ldlt = BandLdlt::new();
    let inertia = ldlt
        .factorize(&hess, 0.0)
        .expect("Hessian at the equilibrium factors");
    println!("ldlt_factorize_n100: inertia at the equilibrium {inertia:?}");
    c.bench_function("ldlt_factorize_n100", |b| {
        b.iter(|| ldlt.factorize(black_box(&hess), 0.0).unwrap())
    });
}

fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sample_size(50)
}

criterion_group! {
    name = benches;
    config = config();
    targets = cold_solve, warm_resolve, assembly_and_factorization
}
criterion_main!(benches);
