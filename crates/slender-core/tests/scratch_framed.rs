use slender_core::cosserat::CosseratBuilder;
use slender_core::framed::ShearStiffness;
use slender_core::geometry::Vec3;
use slender_core::lie::DarbouxMeasure;
use slender_core::rod::{Grading, RestCurve, RodBuilder, RodProperties, SectionStiffness};
use slender_core::se3::Se3Builder;
use slender_core::solver::{EquilibriumSolver, SolverParams};

fn props() -> RodProperties {
    RodProperties {
        stiffness: SectionStiffness::isotropic(1.6e7, 1.0, 0.77),
        linear_density: 1273.0 * std::f64::consts::PI * 0.25e-3 * 0.25e-3,
    }
}
fn line() -> RestCurve {
    RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    }
}
fn ratio(p: &[Vec3]) -> f64 {
    let (a, b) = (p[0], p[p.len() - 1]);
    (a.y - b.y) / (b.x - a.x)
}

#[test]
fn scratch() {
    let p = props();
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    for &gamma in &[1.0, 61.3, 1000.0] {
        let g = gamma * 1.0 / p.linear_density;
        for &n in &[5usize, 20, 100] {
            let grading = Grading::BoundaryLayer { gamma };
            let rod = RodBuilder::new(line(), p)
                .elements(n)
                .grading(grading)
                .first_director(Vec3::z())
                .clamp_start()
                .gravity(Vec3::new(0.0, -g, 0.0))
                .build()
                .unwrap();
            let t = std::time::Instant::now();
            let sol = EquilibriumSolver::new(&rod, rod.rest_state(), SolverParams::default())
                .solve(&rod, rod.rest_state(), 0.0, 1.0);
            let dt = t.elapsed().as_secs_f64();
            eprintln!(
                "DER   Γ={gamma} N={n}: {:.8} it {} steps {} {:?} {:.2}ms",
                ratio(sol.state.positions()),
                sol.report.iterations,
                sol.report.load_steps,
                sol.report.converged(),
                dt * 1e3
            );
            for m in [DarbouxMeasure::Sine, DarbouxMeasure::Tangent] {
                let rod = CosseratBuilder::new(line(), p, shear)
                    .darboux(m)
                    .elements(n)
                    .grading(grading)
                    .first_director(Vec3::z())
                    .clamp_start()
                    .gravity(Vec3::new(0.0, -g, 0.0))
                    .build()
                    .unwrap();
                let t = std::time::Instant::now();
                let sol = EquilibriumSolver::new(&rod, rod.rest_state(), SolverParams::default())
                    .solve(&rod, rod.rest_state(), 0.0, 1.0);
                let dt = t.elapsed().as_secs_f64();
                eprintln!(
                    "COS{m:?} Γ={gamma} N={n}: {:.8} it {} steps {} {:?} {:.2}ms {:?}",
                    ratio(sol.state.positions()),
                    sol.report.iterations,
                    sol.report.load_steps,
                    sol.report.converged(),
                    dt * 1e3,
                    sol.report.inertia
                );
            }
            let rod = Se3Builder::new(line(), p, shear)
                .elements(n)
                .grading(grading)
                .first_director(Vec3::z())
                .clamp_start()
                .gravity(Vec3::new(0.0, -g, 0.0))
                .build()
                .unwrap();
            let t = std::time::Instant::now();
            let sol = EquilibriumSolver::new(&rod, rod.rest_state(), SolverParams::default())
                .solve(&rod, rod.rest_state(), 0.0, 1.0);
            let dt = t.elapsed().as_secs_f64();
            eprintln!(
                "SE3   Γ={gamma} N={n}: {:.8} it {} steps {} {:?} {:.2}ms {:?}",
                ratio(sol.state.positions()),
                sol.report.iterations,
                sol.report.load_steps,
                sol.report.converged(),
                dt * 1e3,
                sol.report.status
            );
        }
    }
}

fn trace<
    P: slender_core::solver::EquilibriumProblem<Hessian = slender_core::linalg::SymmetricBandMatrix>,
>(
    p: &P,
    start: &P::State,
    load: f64,
    iters: usize,
) {
    use slender_core::linalg::{BandLdlt, SymmetricFactor};
    let n = p.n_free();
    let mut s = start.clone();
    let mut trial = s.clone();
    let mut g = vec![0.0; n];
    let mut a = vec![0.0; n];
    let mut h = p.new_hessian();
    let mut f = BandLdlt::new();
    for it in 0..iters {
        let info = p.assemble(&s, load, &mut g, &mut h, &mut a);
        let res = g
            .iter()
            .enumerate()
            .map(|(i, x)| x.abs() / p.force_length(i))
            .fold(0.0, f64::max);
        let inertia = f.factorize(&h, 0.0);
        let mut dx: Vec<f64> = g.iter().map(|x| -x).collect();
        f.solve_in_place(&mut dx);
        let slope: f64 = g.iter().zip(&dx).map(|(a, b)| a * b).sum();
        let amax = p.max_step(&s, &dx);
        let mut alpha = amax;
        let mut k = 0;
        loop {
            p.displace(&s, &dx, alpha, &mut trial);
            let e = p.energy(&trial, load);
            if e <= info.energy + 1e-4 * alpha * slope || k > 40 {
                break;
            }
            alpha *= 0.5;
            k += 1;
        }
        eprintln!("it {it}: E {:.6e} res {res:.3e} ext {:.3e} inertia {:?} slope {slope:.3e} amax {amax:.3e} alpha {alpha:.3e} backtracks {k}", info.energy, info.external_force, inertia.map(|i| i.negative));
        std::mem::swap(&mut s, &mut trial);
    }
}

#[test]
fn scratch_trace() {
    let p = props();
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    let gamma = 61.3;
    let g = gamma * 1.0 / p.linear_density;
    let n: usize = std::env::var("N").map(|v| v.parse().unwrap()).unwrap_or(5);
    let grading = Grading::BoundaryLayer { gamma };
    if std::env::var("M").as_deref() == Ok("se3") {
        let rod = Se3Builder::new(line(), p, shear)
            .elements(n)
            .grading(grading)
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(Vec3::new(0.0, -g, 0.0))
            .build()
            .unwrap();
        trace(&rod, rod.rest_state(), 1.0, 25);
    } else {
        let rod = CosseratBuilder::new(line(), p, shear)
            .elements(n)
            .grading(grading)
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(Vec3::new(0.0, -g, 0.0))
            .build()
            .unwrap();
        trace(&rod, rod.rest_state(), 1.0, 25);
    }
}

#[test]
fn scratch_timing() {
    use slender_core::solver::EquilibriumProblem;
    let p = props();
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    let g = 61.3 / p.linear_density;
    let n = 100;
    let grading = Grading::BoundaryLayer { gamma: 61.3 };
    let cos = CosseratBuilder::new(line(), p, shear)
        .elements(n)
        .grading(grading)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(Vec3::new(0.0, -g, 0.0))
        .build()
        .unwrap();
    let se3 = Se3Builder::new(line(), p, shear)
        .elements(n)
        .grading(grading)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(Vec3::new(0.0, -g, 0.0))
        .build()
        .unwrap();
    let s = cos.rest_state().clone();
    let nn = cos.n_free();
    let (mut gr, mut ab) = (vec![0.0; nn], vec![0.0; nn]);
    let mut h = cos.new_hessian();
    let t = std::time::Instant::now();
    for _ in 0..100 {
        cos.assemble(&s, 1.0, &mut gr, &mut h, &mut ab);
    }
    eprintln!(
        "cosserat assembly {:.1} us",
        t.elapsed().as_secs_f64() * 1e4
    );
    let t = std::time::Instant::now();
    for _ in 0..100 {
        std::hint::black_box(cos.energy(&s, 1.0));
    }
    eprintln!("cosserat energy {:.1} us", t.elapsed().as_secs_f64() * 1e4);
    let mut out = s.clone();
    let dx = vec![1e-3; nn];
    let t = std::time::Instant::now();
    for _ in 0..100 {
        cos.displace(&s, &dx, 1.0, &mut out);
    }
    eprintln!(
        "cosserat displace {:.1} us",
        t.elapsed().as_secs_f64() * 1e4
    );
    let s = se3.rest_state().clone();
    let nn = se3.n_free();
    let (mut gr, mut ab) = (vec![0.0; nn], vec![0.0; nn]);
    let mut h = se3.new_hessian();
    let t = std::time::Instant::now();
    for _ in 0..100 {
        se3.assemble(&s, 1.0, &mut gr, &mut h, &mut ab);
    }
    eprintln!("se3 assembly {:.1} us", t.elapsed().as_secs_f64() * 1e4);
    let t = std::time::Instant::now();
    for _ in 0..100 {
        std::hint::black_box(se3.energy(&s, 1.0));
    }
    eprintln!("se3 energy {:.1} us", t.elapsed().as_secs_f64() * 1e4);
}

#[test]
fn scratch_solve_timing() {
    let p = props();
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    let g = 61.3 / p.linear_density;
    let n = 100;
    let grading = Grading::BoundaryLayer { gamma: 61.3 };
    let cos = CosseratBuilder::new(line(), p, shear)
        .elements(n)
        .grading(grading)
        .first_director(Vec3::z())
        .clamp_start()
        .gravity(Vec3::new(0.0, -g, 0.0))
        .build()
        .unwrap();
    for lam in [true, false] {
        let params = SolverParams {
            compute_lambda_min: lam,
            ..Default::default()
        };
        let mut solver = EquilibriumSolver::new(&cos, cos.rest_state(), params);
        let t = std::time::Instant::now();
        let sol = solver.solve(&cos, cos.rest_state(), 0.0, 1.0);
        eprintln!(
            "lambda {lam}: {:.2} ms it {} {:?}",
            t.elapsed().as_secs_f64() * 1e3,
            sol.report.iterations,
            sol.report.lambda_min_normalized
        );
    }
    trace(&cos, cos.rest_state(), 1.0, 16);
}

#[test]
fn scratch_se3_lambda() {
    let p = props();
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    for (gamma, n) in [(1000.0, 5usize), (1000.0, 100), (61.3, 100)] {
        let g = gamma / p.linear_density;
        let grading = Grading::BoundaryLayer { gamma };
        let se3 = Se3Builder::new(line(), p, shear)
            .elements(n)
            .grading(grading)
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(Vec3::new(0.0, -g, 0.0))
            .build()
            .unwrap();
        for lam in [true, false] {
            let params = SolverParams {
                compute_lambda_min: lam,
                ..Default::default()
            };
            let mut solver = EquilibriumSolver::new(&se3, se3.rest_state(), params);
            let t = std::time::Instant::now();
            let sol = solver.solve(&se3, se3.rest_state(), 0.0, 1.0);
            eprintln!(
                "se3 Γ={gamma} N={n} lambda {lam}: {:.2} ms it {} {:?}",
                t.elapsed().as_secs_f64() * 1e3,
                sol.report.iterations,
                sol.report.lambda_min_normalized
            );
        }
    }
}
