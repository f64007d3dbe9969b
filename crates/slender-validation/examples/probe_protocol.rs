// Throw-away probe: protocol iterations and time per model.
use slender_validation::lateral_sweep::{solver_params, LateralBucklingCase};
use slender_validation::materials::OMEGA_SHELL;
use slender_validation::shell_model::ShellModel;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model: ShellModel = args[1].parse().unwrap();
    let w: f64 = args[2].parse().unwrap();
    let n: usize = args[3].parse().unwrap();
    let gamma: f64 = args[4].parse().unwrap();
    let m: usize = args.get(5).map_or(5, |s| s.parse().unwrap());
    let params = solver_params();
    let case = LateralBucklingCase {
        material: OMEGA_SHELL,
        width_ratio: w,
        n_length: n,
        model,
    };
    let t = std::time::Instant::now();
    let out = case.protocol(gamma, 0.2, m, &params).unwrap();
    println!(
        "{model} w {w} n {n} Γ {gamma}: tip {:.3e} conv {} iterations {} {:.3}s",
        out.tip_deviation,
        out.converged,
        out.iterations,
        t.elapsed().as_secs_f64()
    );
}
