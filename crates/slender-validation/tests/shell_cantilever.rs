//! Shell cantilever against the 1-D heavy-elastica master curve (computed in-code by
//! multiple shooting, independently of both models). With ν = 0, D·w = EI exactly, so the
//! master curve is the exact reference for the strip (design.md §1.1, §3.3). Both shell
//! models. Run in release.

use slender_core::solver::SolverParams;
use slender_validation::cantilever::shell_acceptance::{
    acceptance_case, shell_error_sweep, worst_percent,
};
use slender_validation::cantilever::shell_cantilever_checks;
use slender_validation::cantilever::sweep::log_space;
use slender_validation::shell_model::ShellModel;

const MIDEDGE: ShellModel = ShellModel::Midedge;

fn print(points: &[slender_validation::cantilever::shell_acceptance::ShellErrorPoint]) {
    for p in points {
        eprintln!(
            "n_L = {:2}, Γ = {:8.3}: error {:+.3} %, {} iterations, {:.1} ms",
            p.n_length,
            p.gamma,
            100.0 * p.rel_error,
            p.iterations,
            1e3 * p.seconds
        );
    }
}

#[test]
fn fifteen_elements_within_one_percent_up_to_gamma_100() {
    let points = shell_error_sweep(
        MIDEDGE,
        15,
        &log_space(0.1, 100.0, 10),
        &SolverParams::default(),
    )
    .expect("valid cases");
    print(&points);
    let worst = worst_percent(&points, 0.1, 100.0);
    assert!(worst <= 1.0, "worst error {worst} %");
}

#[test]
fn eight_elements_within_two_percent_over_the_cable_range() {
    let points = shell_error_sweep(
        MIDEDGE,
        8,
        &log_space(10.0, 1e3, 9),
        &SolverParams::default(),
    )
    .expect("valid cases");
    print(&points);
    let worst = worst_percent(&points, 10.0, 1e3);
    assert!(worst <= 2.0, "worst error {worst} %");
}

#[test]
fn eight_elements_below_the_cable_range() {
    // Measured: +2.1 % at Γ ≤ 1 (the coarse tip elements of the quadratic grading; a uniform
    // 8 × 2 mesh gives +1.5 %, as libshell does in design.md §3.3). The 2 % target over
    // Γ ≤ 10³ is therefore missed by 0.15 points at small Γ; `shell_cantilever_checks` reports
    // it as FAIL. Here we only guard against regressions beyond the measured figure.
    let points = shell_error_sweep(
        MIDEDGE,
        8,
        &log_space(0.1, 10.0, 5),
        &SolverParams::default(),
    )
    .expect("valid cases");
    print(&points);
    let worst = worst_percent(&points, 0.1, 10.0);
    assert!(worst <= 2.5, "worst error {worst} %");
}

#[test]
fn cold_load_stepping_from_the_flat_strip_reaches_the_same_equilibrium() {
    // Without the rod predictor the solver ramps gravity itself (hundreds of iterations,
    // design.md §3.3); both routes must end on the same equilibrium.
    let case = acceptance_case(MIDEDGE, 8, 100.0);
    let params = SolverParams::default();
    let warm = case.run_with(&params, true).expect("valid");
    let cold = case.run_with(&params, false).expect("valid");
    assert!(warm.report.converged() && cold.report.converged());
    eprintln!(
        "Γ = 100, 8 × 2: predictor {} iterations / {:.1} ms; load stepping {} iterations / {:.1} ms",
        warm.report.iterations,
        1e3 * warm.seconds,
        cold.report.iterations,
        1e3 * cold.seconds
    );
    assert!(
        (warm.ratio - cold.ratio).abs() <= 1e-6 * warm.ratio,
        "{} vs {}",
        warm.ratio,
        cold.ratio
    );
}

#[test]
fn checks_report_measured_figures() {
    let checks =
        shell_cantilever_checks(&ShellModel::ALL, &SolverParams::default()).expect("valid");
    for c in &checks {
        eprintln!(
            "{} {}: {:.3} (target {})",
            if c.passed { "PASS" } else { "FAIL" },
            c.description,
            c.measured,
            c.target
        );
        assert!(c.measured.is_finite(), "{}", c.description);
    }
    // Mid-edge: 15 × 2 within 1 % and 8 × 2 over the cable range pass; its 8 × 2 over
    // Γ ≤ 10³ misses by 0.15 points (see above). B-spline: 8 × 1 within 1 % over Γ ≤ 10³.
    assert_eq!(checks.len(), 4);
    assert!(checks[0].passed && checks[2].passed && checks[3].passed);
}

#[test]
fn bspline_eight_elements_within_one_percent_up_to_gamma_1000() {
    // The C¹ shell's target (issue 13): n_L = 8 (one element across) within 1 % of the master
    // curve for Γ ≤ 10³, on the boundary-layer grading for each Γ.
    let points = shell_error_sweep(
        ShellModel::Bspline,
        8,
        &log_space(0.1, 1e3, 13),
        &SolverParams::default(),
    )
    .expect("valid cases");
    print(&points);
    let worst = worst_percent(&points, 0.1, 1e3);
    assert!(worst <= 1.0, "worst error {worst} %");
}

#[test]
fn bspline_converges_from_the_flat_strip_in_a_few_dozen_iterations() {
    // No predictor: the mixed-integration-point Newton takes full gravity from the flat strip.
    for gamma in [1.0, 61.3, 1e3] {
        let run = acceptance_case(ShellModel::Bspline, 8, gamma)
            .run(&SolverParams::default())
            .expect("valid");
        eprintln!(
            "Γ = {gamma}: {} iterations in {} load steps",
            run.report.iterations, run.report.load_steps
        );
        assert!(run.report.converged());
        assert!(run.report.iterations <= 60, "{}", run.report.iterations);
    }
}
