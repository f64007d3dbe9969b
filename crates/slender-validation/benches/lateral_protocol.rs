//! Speed of one run of the seed's lateral-buckling protocol (issues 4 and 13): rotate the
//! clamp by σ = 0.2, ramp gravity in m_ls = 5 stages, rotate the clamp back in 5 stages,
//! re-equilibrate; and of one Γ_c bisection on the Hessian inertia. Ω_shell, square elements,
//! the benchmark's solver settings (`lateral_sweep::solver_params`), both shell models.
//!
//! Run with `cargo bench -p slender-validation --bench lateral_protocol`. Results are in
//! BENCHMARKS.md at the workspace root.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use slender_validation::lateral_sweep::{solver_params, LateralBucklingCase};
use slender_validation::materials::OMEGA_SHELL;
use slender_validation::shell_model::ShellModel;

fn case(model: ShellModel, width_ratio: f64, n_length: usize) -> LateralBucklingCase {
    LateralBucklingCase {
        material: OMEGA_SHELL,
        width_ratio,
        n_length,
        model,
    }
}

fn protocol(c: &mut Criterion) {
    let params = solver_params();
    let mut g = c.benchmark_group("protocol_sigma0.2_mls5");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for model in ShellModel::ALL {
        for (w, n, gamma) in [
            (0.1, 8, 20.0),
            (0.3, 15, 20.0),
            (0.1, 30, 20.0),
            (1.0, 8, 35.0),
        ] {
            g.bench_function(format!("{model}/w{w}_n{n}_gamma{gamma}"), |b| {
                b.iter(|| {
                    let out = case(model, w, n)
                        .protocol(black_box(gamma), 0.2, 5, &params)
                        .expect("valid");
                    assert!(out.converged);
                    out.tip_deviation
                })
            });
        }
    }
    g.finish();
}

fn critical_gamma(c: &mut Criterion) {
    let params = solver_params();
    let mut g = c.benchmark_group("critical_gamma_bisection");
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for (model, n) in [(ShellModel::Midedge, 15), (ShellModel::Bspline, 8)] {
        g.bench_function(format!("{model}/w0.5_n{n}"), |b| {
            b.iter(|| {
                case(model, 0.5, n)
                    .critical_gamma(2.0, 200.0, 1e-3, &params)
                    .expect("valid")
            })
        });
    }
    g.finish();
}

criterion_group!(benches, protocol, critical_gamma);
criterion_main!(benches);
