// Throw-away probe: the mid-edge cantilever at n_L = 8 on other gradings.
use slender_core::rod::Grading;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::log_space;
use slender_validation::cantilever::master_curve::master_ratio;
use slender_validation::cantilever::shell_acceptance::acceptance_case;
use slender_validation::shell_model::ShellModel;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model: ShellModel = args[1].parse().unwrap();
    let n: usize = args[2].parse().unwrap();
    let nw: usize = args[3].parse().unwrap();
    for g in log_space(0.1, 1e3, 13) {
        let mut c = acceptance_case(model, n, g);
        c.n_width = nw;
        c.grading = match args[4].as_str() {
            "bl" => Grading::BoundaryLayer { gamma: g },
            "u" => Grading::Uniform,
            e => Grading::Power {
                exponent: e.parse().unwrap(),
            },
        };
        let r = c.run(&SolverParams::default()).unwrap();
        println!(
            "Γ {g:.3}: {:+.3} % ({} it)",
            100.0 * (r.ratio / master_ratio(g).unwrap() - 1.0),
            r.report.iterations
        );
    }
}
