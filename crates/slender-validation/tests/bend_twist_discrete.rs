//! The two discrete decision routes of the bend–twist benchmark against each other and against
//! physical expectations that do not need the master curve.

use slender_core::solver::SolverParams;
use slender_validation::bend_twist::case::BendTwistCase;
use slender_validation::bend_twist::protocol::{run_protocol, ProtocolSettings};
use slender_validation::bend_twist::stability::decide_by_stability;

fn both(x: f64, y: f64) -> (Option<bool>, Option<bool>, Option<f64>, f64, Option<f64>) {
    let case = BendTwistCase::new(x, y, 20.0);
    let params = SolverParams::default();
    let settings = ProtocolSettings::default();
    let (p, _) = run_protocol(&case, &settings, &params).unwrap();
    let (s, _) = decide_by_stability(&case, &params).unwrap();
    (
        s.three_dimensional(),
        p.combined(&settings),
        s.lambda_out_normalized,
        p.measures.xi_y,
        s.buckled.map(|b| b.xi_y),
    )
}

#[test]
fn short_arcs_stay_planar() {
    // Y < Y* (less than one turn): the planar state is stable for every X (design.md §1.2).
    for x in [0.2, 1.0, 5.0] {
        let (stab, prot, lam, xi_y, _) = both(x, 0.3);
        assert_eq!(stab, Some(false), "X = {x}");
        assert_eq!(prot, Some(false), "X = {x}");
        assert!(lam.unwrap() > 0.0);
        assert!(xi_y < 1e-8, "X = {x}: Ξ_y = {xi_y}");
    }
}

#[test]
fn a_coil_in_the_unstable_window_buckles_by_both_routes() {
    let (stab, prot, lam, xi_y, buckled) = both(0.5, 2.0);
    assert_eq!(stab, Some(true));
    assert_eq!(prot, Some(true));
    assert!(lam.unwrap() < 0.0);
    // The branch switch and the protocol find the same 3-D equilibrium.
    let b = buckled.expect("branch switch converged");
    assert!(
        (b / xi_y - 1.0).abs() < 1e-3,
        "buckled Ξ_y {b} vs protocol {xi_y}"
    );
}

#[test]
fn the_stability_margin_changes_sign_across_the_lower_boundary() {
    // Along Y = 2 the coil is stable at small X and unstable at X = 0.5: λ_min crosses zero
    // once in between, continuously.
    let xs = [0.2, 0.3, 0.4, 0.5];
    let lams: Vec<f64> = xs.iter().map(|&x| both(x, 2.0).2.unwrap()).collect();
    assert!(lams[0] > 0.0 && lams[3] < 0.0, "{lams:?}");
    let sign_changes = lams
        .windows(2)
        .filter(|w| (w[0] > 0.0) != (w[1] > 0.0))
        .count();
    assert_eq!(sign_changes, 1, "{lams:?}");
}

#[test]
fn invalid_points_are_errors_naming_the_field() {
    let case = BendTwistCase::new(f64::NAN, 1.0, 20.0);
    let err = decide_by_stability(&case, &SolverParams::default()).unwrap_err();
    assert!(err.to_string().contains('x'), "{err}");
    let case = BendTwistCase::new(1.0, -1.0, 20.0);
    let err = run_protocol(
        &case,
        &ProtocolSettings::default(),
        &SolverParams::default(),
    )
    .unwrap_err();
    assert!(err.to_string().contains('y'), "{err}");
}

#[test]
fn the_coil_buckles_supercritically_at_the_lower_boundary() {
    // Following the 3-D branch toward X_c1 its amplitude vanishes like √δ (A² linear in δ),
    // at the boundary up to the mesh's offset: a supercritical pitchfork, so the protocol
    // shows no hysteresis there.
    use slender_validation::bend_twist::criticality::criticality;
    let cs = criticality(1.5, 50.0, &SolverParams::default()).unwrap();
    let lower = cs.iter().find(|c| c.boundary == "lower").unwrap();
    assert_eq!(lower.kind, "supercritical", "{lower:?}");
    assert!(lower.delta_0.abs() < 0.005, "{lower:?}");
    let (_, a) = *lower.amplitudes.last().unwrap();
    assert!(
        a < 0.05,
        "amplitude {a} close to the boundary should be small"
    );
}
