use slender_core::cosserat::CosseratBuilder;
use slender_core::framed::ShearStiffness;
use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, RodProperties, SectionStiffness};
use slender_core::se3::Se3Builder;
use slender_core::solver::{EquilibriumSolver, SolverParams};
fn main() {
    let p = RodProperties {
        stiffness: SectionStiffness::isotropic(9.21e5, 4.5e-2, 3.75e-2),
        linear_density: 2485.0 * std::f64::consts::PI * 36e-6,
    };
    let shear = ShearStiffness::solid_circle(&p.stiffness).unwrap();
    let g = Vec3::new(0.0, -61.3 * 4.5e-2 / p.linear_density, 0.0);
    let line = RestCurve::Straight {
        start: [0.0; 3],
        direction: [1.0, 0.0, 0.0],
        length: 1.0,
    };
    let which = std::env::args().nth(1).unwrap_or("se3".into());
    let reps = 300;
    if which == "der" {
        let rod = slender_core::rod::RodBuilder::new(line, p)
            .elements(100)
            .grading(Grading::BoundaryLayer { gamma: 61.3 })
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(g)
            .build()
            .unwrap();
        let mut solver = EquilibriumSolver::new(
            &rod,
            rod.rest_state(),
            SolverParams {
                compute_lambda_min: std::env::var("NOLAM").is_err(),
                ..Default::default()
            },
        );
        let t = std::time::Instant::now();
        for _ in 0..reps {
            let mut s = rod.rest_state().clone();
            solver.solve_in_place(&rod, &mut s, 0.0, 1.0);
        }
        println!(
            "der {:.3} ms",
            t.elapsed().as_secs_f64() * 1e3 / reps as f64
        );
    } else if which == "se3" {
        let rod = Se3Builder::new(line, p, shear)
            .elements(100)
            .grading(Grading::BoundaryLayer { gamma: 61.3 })
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(g)
            .build()
            .unwrap();
        let mut solver = EquilibriumSolver::new(
            &rod,
            rod.rest_state(),
            SolverParams {
                compute_lambda_min: std::env::var("NOLAM").is_err(),
                ..Default::default()
            },
        );
        let t = std::time::Instant::now();
        let r = solver.solve(&rod, rod.rest_state(), 0.0, 1.0).report;
        println!(
            "it {} steps {} rejected {} snaps {}",
            r.iterations, r.load_steps, r.rejected_steps, r.snaps
        );
        for _ in 0..reps {
            let mut s = rod.rest_state().clone();
            solver.solve_in_place(&rod, &mut s, 0.0, 1.0);
        }
        println!(
            "se3 {:.3} ms",
            t.elapsed().as_secs_f64() * 1e3 / reps as f64
        );
    } else {
        let rod = CosseratBuilder::new(line, p, shear)
            .elements(100)
            .grading(Grading::BoundaryLayer { gamma: 61.3 })
            .first_director(Vec3::z())
            .clamp_start()
            .gravity(g)
            .build()
            .unwrap();
        let mut solver = EquilibriumSolver::new(
            &rod,
            rod.rest_state(),
            SolverParams {
                compute_lambda_min: std::env::var("NOLAM").is_err(),
                ..Default::default()
            },
        );
        let t = std::time::Instant::now();
        let r = solver.solve(&rod, rod.rest_state(), 0.0, 1.0).report;
        println!(
            "it {} steps {} rejected {} snaps {}",
            r.iterations, r.load_steps, r.rejected_steps, r.snaps
        );
        for _ in 0..reps {
            let mut s = rod.rest_state().clone();
            solver.solve_in_place(&rod, &mut s, 0.0, 1.0);
        }
        println!(
            "cosserat {:.3} ms",
            t.elapsed().as_secs_f64() * 1e3 / reps as f64
        );
    }
}
