// Throw-away probe: Γ_c and cantilever accuracy at n_L = 8 for the B-spline shell.
use slender_core::solver::SolverParams;
use slender_validation::cantilever::log_space;
use slender_validation::cantilever::shell_acceptance::{acceptance_case, shell_error_sweep};
use slender_validation::lateral_buckling::{critical_gamma, MasterCurve};
use slender_validation::lateral_sweep::LateralBucklingCase;
use slender_validation::materials::OMEGA_SHELL;
use slender_validation::shell_model::ShellModel;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model: ShellModel = args[1].parse().unwrap();
    let n: usize = args[2].parse().unwrap();
    let params = SolverParams::default();
    let t = std::time::Instant::now();
    for w in [0.1, 0.5, 1.0] {
        let c = LateralBucklingCase {
            material: OMEGA_SHELL,
            width_ratio: w,
            n_length: n,
            model,
        };
        let gc = c
            .critical_gamma(2.0, 200.0, 1e-5, &params)
            .unwrap()
            .unwrap();
        let m = critical_gamma(w, OMEGA_SHELL.poisson, MasterCurve::KirchhoffPlate).unwrap();
        println!(
            "w {w}: Γc {gc:.4} master {m:.4} err {:+.3} %",
            100.0 * (gc / m - 1.0)
        );
    }
    if args.len() > 3 {
        let pts = shell_error_sweep(model, n, &log_space(0.1, 1e3, 13), &params).unwrap();
        for p in pts {
            println!(
                "Γ {:.3}: {:+.3} % ({} it)",
                p.gamma,
                100.0 * p.rel_error,
                p.iterations
            );
        }
        let _ = acceptance_case(model, n, 1.0);
    }
    println!("{:.2}s", t.elapsed().as_secs_f64());
}
