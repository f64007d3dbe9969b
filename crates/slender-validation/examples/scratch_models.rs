use slender_core::solver::SolverParams;
use slender_validation::cantilever::acceptance::convergence_slope;
use slender_validation::cantilever::{log_space, run_case_with, CantileverCase, MeshKind};
use slender_validation::materials::OMEGA_ROD;
use slender_validation::rod_model::RodModel;

fn main() {
    let p = SolverParams::default();
    let gammas = log_space(0.1, 1e4, 40);
    for model in RodModel::ALL {
        for (mesh, n, lo, hi) in [
            (MeshKind::Graded, 20, 0.1, 1e4),
            (MeshKind::Graded, 5, 10.0, 1e3),
            (MeshKind::Uniform, 5, 10.0, 1e3),
            (MeshKind::Uniform, 20, 0.1, 1e4),
        ] {
            let mut worst: f64 = 0.0;
            let mut at = 0.0;
            let mut its = 0;
            for &g in gammas
                .iter()
                .filter(|&&g| g >= lo * 0.999 && g <= hi * 1.001)
            {
                let r = run_case_with(
                    &CantileverCase {
                        material: OMEGA_ROD,
                        mesh,
                        n_elements: n,
                        gamma: g,
                    },
                    model,
                    &p,
                )
                .unwrap();
                if !r.converged {
                    println!("{model:?} {mesh:?} N={n} Γ={g} NOT CONVERGED {}", r.failure);
                }
                if r.rel_error.abs() > worst {
                    worst = r.rel_error.abs();
                    at = g;
                }
                its = its.max(r.iterations);
            }
            println!(
                "{:?} {:?} N={n}: worst {:.3} % at Γ={at:.3} (max it {its})",
                model,
                mesh,
                100.0 * worst
            );
        }
        for g in [1.0, 100.0] {
            let ns = [10, 20, 40, 80];
            let e: Vec<f64> = ns
                .iter()
                .map(|&n| {
                    run_case_with(
                        &CantileverCase {
                            material: OMEGA_ROD,
                            mesh: MeshKind::Graded,
                            n_elements: n,
                            gamma: g,
                        },
                        model,
                        &p,
                    )
                    .unwrap()
                    .rel_error
                })
                .collect();
            println!(
                "{model:?} slope Γ={g}: {:.3} errors {:?}",
                convergence_slope(&ns, &e),
                e
            );
        }
    }
}
