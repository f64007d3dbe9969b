use slender_core::solver::SolverParams;
use slender_validation::lateral_sweep::LateralBucklingCase;
use slender_validation::materials::OMEGA_SHELL;
use slender_validation::shell_model::ShellModel;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model: ShellModel = args[1].parse().unwrap();
    let w: f64 = args[2].parse().unwrap();
    let n: usize = args[3].parse().unwrap();
    let c = LateralBucklingCase {
        material: OMEGA_SHELL,
        width_ratio: w,
        n_length: n,
        model,
    };
    let gc = c
        .critical_gamma(5.0, 60.0, 1e-5, &SolverParams::default())
        .unwrap();
    println!("{model} w {w} n {n}: Γc {gc:?}");
    for g in [13.2, 13.4, 13.6] {
        let r = c.planar_report(g, &SolverParams::default()).unwrap();
        println!("Γ {g}: it {} inertia {:?}", r.iterations, r.inertia);
    }
}
