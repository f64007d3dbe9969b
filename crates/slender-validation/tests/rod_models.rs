//! The benchmarks on every rod model: the generic path gives the discrete elastic rod's results
//! bit for bit, every model solves the cantilever and decides the bend–twist points, and the
//! shear-tension limit that explains the shearable models' corner of the bend–twist grid is
//! where a tensioned Cosserat rod or SE(3) beam actually loses stability.

use slender_core::geometry::Vec3;
use slender_core::rod::RestCurve;
use slender_core::solver::{EquilibriumSolver, SolverParams};
use slender_validation::bend_twist::case::BendTwistCase;
use slender_validation::bend_twist::stability::{decide_by_stability, decide_by_stability_with};
use slender_validation::cantilever::master_curve::master_ratio;
use slender_validation::cantilever::{CantileverCase, MeshKind};
use slender_validation::materials::OMEGA_ROD;
use slender_validation::model_comparison::shear_tension_limit;
use slender_validation::rod_model::RodModel;

#[test]
fn model_names_round_trip() {
    for m in RodModel::ALL {
        assert_eq!(RodModel::from_name(m.name()), Some(m));
    }
    assert_eq!(RodModel::from_name("odin"), None);
}

#[test]
fn the_generic_path_is_the_discrete_elastic_rod_bit_for_bit() {
    let case = CantileverCase {
        material: OMEGA_ROD,
        mesh: MeshKind::Graded,
        n_elements: 12,
        gamma: 61.3,
    };
    let p = SolverParams::default();
    let a = case.run(&p).unwrap();
    let b = case.run_with(RodModel::Der, &p).unwrap();
    assert_eq!(a.ratio.to_bits(), b.ratio.to_bits());
    let bt = BendTwistCase::new(2.0, 0.5, 20.0);
    let (x, px) = decide_by_stability(&bt, &p).unwrap();
    let (y, py) = decide_by_stability_with(&bt, RodModel::Der, &p).unwrap();
    assert_eq!(x, y);
    assert_eq!(px, py);
}

#[test]
fn every_model_solves_the_cantilever_near_the_master_curve() {
    let p = SolverParams::default();
    for model in RodModel::ALL {
        for gamma in [0.5, 61.3, 2000.0] {
            let case = CantileverCase {
                material: OMEGA_ROD,
                mesh: MeshKind::Graded,
                n_elements: 50,
                gamma,
            };
            let run = case.run_with(model, &p).unwrap();
            assert!(run.report.converged(), "{model:?} Γ = {gamma}");
            let e = run.ratio / master_ratio(gamma).unwrap() - 1.0;
            assert!(e.abs() < 2e-3, "{model:?} Γ = {gamma}: error {e}");
        }
    }
}

#[test]
fn every_model_decides_a_2d_and_a_3d_point() {
    // The unstable window of the master curve at Y = 1; points well inside and outside it.
    let p = SolverParams::default();
    let c = OMEGA_ROD.properties.stiffness.gj / OMEGA_ROD.properties.stiffness.ei_min();
    let b = slender_validation::bend_twist::master_curve::critical_boundaries(1.0, c).unwrap();
    let (lo, hi) = (b.lower.unwrap(), b.upper.unwrap());
    for model in [RodModel::Cosserat, RodModel::Se3] {
        for (x, three_d) in [
            (0.5 * lo, false),
            ((lo * hi).sqrt(), true),
            (2.0 * hi, false),
        ] {
            let case = BendTwistCase::new(x, 1.0, 20.0);
            let (out, _) = decide_by_stability_with(&case, model, &p).unwrap();
            assert_eq!(
                out.three_dimensional(),
                Some(three_d),
                "{model:?} X = {x}: {out:?}"
            );
        }
    }
}

/// A straight rod of Ω_rod clamped at the top and pulled down by `tension` (N) at its free end
/// (uniform tension); true if the equilibrium is stable.
fn pulled_is_stable(model: RodModel, tension: f64) -> bool {
    use slender_core::cosserat::CosseratBuilder;
    use slender_core::rod::RodBuilder;
    use slender_core::se3::Se3Builder;
    let curve = RestCurve::Straight {
        start: [0.0; 3],
        direction: [0.0, 0.0, -1.0],
        length: 1.0,
    };
    let (n, force) = (10, Vec3::new(0.0, 0.0, -tension));
    let p = SolverParams::default();
    let report = match model {
        RodModel::Der => {
            let rod = RodBuilder::new(curve, OMEGA_ROD.properties)
                .elements(n)
                .clamp_start()
                .point_force(n, force)
                .build()
                .unwrap();
            EquilibriumSolver::new(&rod, rod.rest_state(), p)
                .solve(&rod, rod.rest_state(), 0.0, 1.0)
                .report
        }
        RodModel::Se3 => {
            let rod = Se3Builder::new(curve, OMEGA_ROD.properties, OMEGA_ROD.shear())
                .elements(n)
                .clamp_start()
                .point_force(n, force)
                .build()
                .unwrap();
            EquilibriumSolver::new(&rod, rod.rest_state(), p)
                .solve(&rod, rod.rest_state(), 0.0, 1.0)
                .report
        }
        _ => {
            let rod = CosseratBuilder::new(curve, OMEGA_ROD.properties, OMEGA_ROD.shear())
                .elements(n)
                .clamp_start()
                .point_force(n, force)
                .build()
                .unwrap();
            EquilibriumSolver::new(&rod, rod.rest_state(), p)
                .solve(&rod, rod.rest_state(), 0.0, 1.0)
                .report
        }
    };
    assert!(report.converged(), "{:?}", report.status);
    report.stable().unwrap()
}

#[test]
fn shearable_rods_lose_stability_in_tension_at_the_predicted_limit() {
    // W″(0) = λ(κGA λ − T) per length for frames turned from the chords: unstable once
    // T > κGA/(1 − κGA/EA). The Kirchhoff rod has no such mode.
    let limit = shear_tension_limit(&OMEGA_ROD);
    for model in [RodModel::Cosserat, RodModel::Se3] {
        assert!(
            pulled_is_stable(model, 0.95 * limit),
            "{model:?} below the limit"
        );
        assert!(
            !pulled_is_stable(model, 1.05 * limit),
            "{model:?} above the limit"
        );
    }
    assert!(pulled_is_stable(RodModel::Der, 2.0 * limit));
}
