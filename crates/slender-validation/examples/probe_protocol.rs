//! Profiling aid for the lateral-buckling protocol (issue 13): runs the seed's protocol
//! ([`LateralBucklingCase::protocol`]) of one Ω_shell strip at the sensitivity study's Γ/Γ_c
//! factors (Γ_c from the Kirchhoff-plate master curve, as the study places its grid) and prints
//! the Newton iterations, the tip deviation and the wall time of each run, one thread.
//!
//! ```text
//! cargo build --release -p slender-validation --example probe_protocol
//! ./target/release/examples/probe_protocol midedge|bspline W_OVER_L N_L M_LS SIGMA [FACTOR]
//! # e.g. the slow case of issue 13:
//! ./target/release/examples/probe_protocol midedge 0.5 30 3 0.2 1.07
//! ```
//!
//! Without FACTOR it runs the six factors 0.7, 0.85, 0.93, 1.07, 1.2 and 1.5. BENCHMARKS.md
//! ("Protocol speed, issue 13") lists the cases measured with it.

use slender_validation::lateral_buckling::{critical_gamma, MasterCurve};
use slender_validation::lateral_sweep::{solver_params, LateralBucklingCase};
use slender_validation::materials::OMEGA_SHELL;
use slender_validation::shell_model::ShellModel;

const USAGE: &str = "usage: probe_protocol midedge|bspline W_OVER_L N_L M_LS SIGMA [FACTOR]";

fn arg<T: std::str::FromStr>(args: &[String], i: usize, name: &str) -> T {
    args.get(i)
        .and_then(|a| a.parse().ok())
        .unwrap_or_else(|| panic!("{name}: missing or invalid\n{USAGE}"))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = match args.get(1).map(String::as_str) {
        Some("midedge") => ShellModel::Midedge,
        Some("bspline") => ShellModel::Bspline,
        _ => panic!("{USAGE}"),
    };
    let width_ratio: f64 = arg(&args, 2, "W_OVER_L");
    let n_length: usize = arg(&args, 3, "N_L");
    let load_steps: usize = arg(&args, 4, "M_LS");
    let sigma: f64 = arg(&args, 5, "SIGMA");
    let factors: Vec<f64> = if args.len() > 6 {
        vec![arg(&args, 6, "FACTOR")]
    } else {
        vec![0.7, 0.85, 0.93, 1.07, 1.2, 1.5]
    };
    let gamma_c = critical_gamma(
        width_ratio,
        OMEGA_SHELL.poisson,
        MasterCurve::KirchhoffPlate,
    )
    .expect("w/L within the master curve's range");
    let params = solver_params();
    let case = LateralBucklingCase {
        material: OMEGA_SHELL,
        width_ratio,
        n_length,
        model,
    };
    for f in factors {
        let start = std::time::Instant::now();
        let out = case
            .protocol(f * gamma_c, sigma, load_steps, &params)
            .expect("valid protocol parameters");
        println!(
            "f={f} gamma={:.2} conv={} its={} dev={:.3e} t={:.3}s",
            f * gamma_c,
            out.converged,
            out.iterations,
            out.tip_deviation,
            start.elapsed().as_secs_f64()
        );
    }
}
