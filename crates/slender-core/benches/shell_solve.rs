//! Speed of the shell solver (issue 4): a cold shell cantilever at n_L = 30, w/L = 0.1
//! (goal ≤ 100 ms), from building the model to the converged equilibrium with its stability
//! eigenvalue.
//!
//! Run with `cargo bench -p slender-core --bench shell_solve`. Results are summarized in
//! BENCHMARKS.md at the workspace root.
//!
//! Problem: Ω_combined of seed Table 2 (L = 0.1 m, h = 0.2 mm, E = 10530 MPa, ρ = 1000 kg/m³)
//! with ν = 0, w/L = 0.1, 30 × 3 elements graded s = L(i/n)², Γ_shell = 61.3, gravity −y.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use slender_core::assembly::TermSet;
use slender_core::geometry::Vec3;
use slender_core::linalg::{SparseLdlt, SymmetricFactor};
use slender_core::rod::Grading;
use slender_core::shell::{rod_predictor, Shell, ShellBuilder, ShellProperties};
use slender_core::solver::{EquilibriumProblem, EquilibriumSolver, Solution, SolverParams};

const GAMMA: f64 = 61.3;
const N_LENGTH: usize = 30;
const N_WIDTH: usize = 3;

fn shell() -> Shell {
    let p = ShellProperties {
        length: 0.1,
        width: 0.01,
        thickness: 0.2e-3,
        young: 10530e6,
        poisson: 0.0,
        density: 1000.0,
    };
    ShellBuilder::new(p)
        .elements(N_LENGTH, N_WIDTH)
        .grading(Grading::Power { exponent: 2.0 })
        .gravity(Vec3::new(0.0, -p.gravity_for_gamma(GAMMA), 0.0))
        .build()
        .expect("valid shell")
}

/// Cold solve: model build, rod predictor, shell Newton (with λ_min), fresh solver.
fn cold_with_predictor(params: &SolverParams) -> Solution<slender_core::shell::ShellState> {
    let shell = shell();
    let flat = shell.rest_state();
    let start = rod_predictor(&shell, 1.0, params)
        .expect("valid rod")
        .unwrap_or_else(|| flat.clone());
    let mut solver = EquilibriumSolver::new(&shell, &flat, *params);
    solver.solve(&shell, &start, 1.0, 1.0)
}

fn cold_solve(c: &mut Criterion) {
    let params = SolverParams::default();
    let sol = cold_with_predictor(&params);
    assert!(sol.report.converged(), "{:?}", sol.report.status);
    println!(
        "cold_shell_cantilever_n30: converged, {} Newton iterations, inertia {:?}, lambda_min_normalized = {:?}",
        sol.report.iterations, sol.report.inertia, sol.report.lambda_min_normalized
    );
    let mut group = c.benchmark_group("cold_shell_cantilever_n30_gamma61");
    group.bench_function("rod_predictor_then_newton", |b| {
        b.iter(|| cold_with_predictor(black_box(&params)))
    });
    // Load stepping from the flat strip, no predictor (hundreds of iterations, design §3.3).
    let shell = shell();
    let flat = shell.rest_state();
    let mut solver = EquilibriumSolver::new(&shell, &flat, params);
    let sol = solver.solve(&shell, &flat, 0.0, 1.0);
    println!(
        "cold_shell_cantilever_n30 from flat by load stepping: converged = {}, {} iterations in {} load steps",
        sol.report.converged(),
        sol.report.iterations,
        sol.report.load_steps
    );
    group.sample_size(10);
    group.bench_function("load_stepping_from_flat", |b| {
        b.iter(|| {
            let mut solver = EquilibriumSolver::new(&shell, &flat, params);
            solver.solve(black_box(&shell), black_box(&flat), 0.0, 1.0)
        })
    });
    group.finish();
}

fn kernels(c: &mut Criterion) {
    let shell = shell();
    let sol = cold_with_predictor(&SolverParams::default());
    let n = shell.n_free();
    let mut g = vec![0.0; n];
    let mut h = shell.new_hessian();
    println!(
        "shell n30: {n} free DOFs, {} stored Hessian entries",
        h.nnz()
    );
    c.bench_function("shell_assembly_n30", |b| {
        b.iter(|| {
            shell.assemble_terms(
                black_box(&sol.state),
                1.0,
                TermSet::ALL,
                Some(&mut g),
                Some(&mut h),
                None,
            )
        })
    });
    let mut ldlt = SparseLdlt::new();
    ldlt.factorize(&h, 0.0).expect("factorizes");
    c.bench_function("shell_sparse_ldlt_numeric_n30", |b| {
        b.iter(|| ldlt.factorize(black_box(&h), 0.0))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    targets = cold_solve, kernels
}
criterion_main!(benches);
