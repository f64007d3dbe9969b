//! Lateral buckling of a heavy strip (seed §5): Γ_c from the Hessian inertia along the planar
//! branch against the libshell reference of design.md §3.3 (MidedgeAngleTan + StVK, square
//! elements, ν = 0.35, computed by a different code) and the Vlasov-beam band (§1.3), and the
//! seed's protocol on both sides of Γ_c. Run in release.

use slender_core::solver::SolverParams;
use slender_validation::lateral_sweep::LateralBucklingCase;
use slender_validation::materials::OMEGA_SHELL;

fn case(width_ratio: f64, n_length: usize) -> LateralBucklingCase {
    LateralBucklingCase {
        material: OMEGA_SHELL,
        width_ratio,
        n_length,
    }
}

#[test]
fn critical_gamma_by_inertia_matches_libshell_and_the_vlasov_band() {
    let params = SolverParams::default();
    // (w/L, n_L, libshell Γ_c, Vlasov band with B = E w h³/12 … D w)
    for (w, n, libshell, band) in [
        (0.1, 8, 13.17, (14.79, 15.79)),
        (0.1, 15, 14.04, (14.79, 15.79)),
        (0.5, 8, 17.64, (19.95, 21.30)),
    ] {
        let gc = case(w, n)
            .critical_gamma(5.0, 60.0, 1e-3, &params)
            .expect("valid")
            .expect("bracketed and converged");
        let vs_libshell = gc / libshell - 1.0;
        let vs_band = gc / band.0 - 1.0;
        eprintln!(
            "w/L = {w}, n_L = {n}: Γ_c = {gc:.3} ({:+.2} % vs libshell {libshell}, {:+.2} % vs Vlasov {})",
            100.0 * vs_libshell,
            100.0 * vs_band,
            band.0
        );
        assert!(
            vs_libshell.abs() < 0.05,
            "Γ_c = {gc} vs libshell {libshell}"
        );
        assert!(
            gc < band.1 * 1.02 && gc > band.0 * 0.8,
            "Γ_c = {gc} vs Vlasov band {band:?}"
        );
    }
}

#[test]
fn seed_protocol_agrees_with_the_inertia_on_both_sides_of_the_critical_gamma() {
    let params = SolverParams::default();
    let c = case(0.1, 8);
    let gc = c
        .critical_gamma(5.0, 60.0, 1e-2, &params)
        .expect("valid")
        .expect("bracketed");
    let below = c.protocol(0.8 * gc, 0.2, 5, &params).expect("valid");
    let above = c.protocol(1.25 * gc, 0.2, 5, &params).expect("valid");
    eprintln!(
        "Γ_c = {gc:.3}: protocol tip y/L = {:.3e} at 0.8 Γ_c (converged {}, relative residual {:.1e}), {:.3e} at 1.25 Γ_c (converged {}, {:.1e})",
        below.tip_deviation,
        below.converged,
        below.report.relative_residual,
        above.tip_deviation,
        above.converged,
        above.report.relative_residual
    );
    // Measured: below Γ_c the last re-equilibration stalls at a residual ~20× the round-off
    // floor after 300 iterations (relative residual ~5e-5): the state is planar to 1e-8 L, so
    // the decision is unaffected, but the stage is reported as not converged.
    assert!(above.converged);
    assert!(below.report.relative_residual < 1e-4);
    assert!(below.tip_deviation.abs() < 1e-4, "{}", below.tip_deviation);
    assert!(above.tip_deviation.abs() > 1e-4, "{}", above.tip_deviation);
    assert_eq!(
        above.report.stable(),
        Some(true),
        "the buckled state must be stable"
    );
}

#[test]
fn acceptance_checks_pass() {
    let checks =
        slender_validation::lateral_sweep::lateral_buckling_checks(&SolverParams::default())
            .expect("valid");
    for c in &checks {
        eprintln!(
            "{} {}: {:.4} (target {})",
            if c.passed { "PASS" } else { "FAIL" },
            c.description,
            c.measured,
            c.target
        );
    }
    assert!(checks.iter().all(|c| c.passed));
}

#[test]
fn vlasov_band_matches_design_table_and_exists_over_the_aspect_ratios() {
    use slender_validation::lateral_sweep::vlasov_band;
    // design.md §1.3 (ν = 0.35): Γ_c = 14.79 (beam B) … 15.79 (plate B) at w/L = 0.1.
    let (beam, plate) = vlasov_band(0.35, 0.1).expect("band");
    assert!((beam / 14.79 - 1.0).abs() < 5e-3 && (plate / 15.79 - 1.0).abs() < 5e-3);
    for w in [0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0] {
        let band = vlasov_band(0.35, w);
        assert!(band.is_some_and(|(b, p)| b < p), "w/L = {w}: {band:?}");
    }
}
