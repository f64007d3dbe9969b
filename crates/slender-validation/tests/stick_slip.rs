//! Stick–slip (Romero's fourth benchmark) against Coulomb's law: below the threshold
//! (tan α = 0.99 μ) the rod does not move by more than 1e-9 of its length; above it
//! (tan α = 1.01 μ) it slides with g (sin α − μ cos α) to 1e-3 — whatever its stiffness.

use slender_validation::stick_slip::StickSlipCase;

/// Rods over several decades of stiffness and of Γ = ρ A g L³ / EI.
fn rods() -> Vec<StickSlipCase> {
    let base = StickSlipCase {
        mu: 0.3,
        alpha: 0.0,
        length: 1.0,
        elements: 20,
        diameter: 0.006,
        young: 1e9,
        density: 1400.0,
        gravity: 9.81,
        dt: 2e-3,
        steps: 60,
    };
    vec![
        base,
        StickSlipCase { young: 1e6, ..base },
        StickSlipCase {
            young: 2e11,
            diameter: 0.002,
            density: 7800.0,
            length: 0.3,
            mu: 0.8,
            ..base
        },
    ]
}

#[test]
fn sticks_below_the_threshold_and_slides_at_coulombs_rate_above() {
    for rod in rods() {
        let gamma = rod.density * rod.gravity * 64.0 * rod.length.powi(3)
            / (rod.young * rod.diameter.powi(2) * 16.0);
        for factor in [0.99, 1.01] {
            let case = StickSlipCase {
                alpha: (factor * rod.mu).atan(),
                ..rod
            };
            let r = case.run().unwrap();
            assert!(r.converged, "{:?}", r.failure);
            println!(
                "Γ = {gamma:.3e}, E = {:.0e}, μ = {}, tan α / μ = {factor}: slid {}, displacement {:.3e} L, a = {:.6e} vs {:.6e}, {} iterations",
                rod.young,
                rod.mu,
                r.slid,
                r.displacement / rod.length,
                r.acceleration,
                r.exact,
                r.iterations
            );
            if factor < 1.0 {
                assert!(!r.slid, "slid below the threshold");
                assert!(
                    r.displacement <= 1e-9 * rod.length,
                    "crept by {:e} L",
                    r.displacement / rod.length
                );
            } else {
                assert!(r.slid, "stuck above the threshold");
                let rel = (r.acceleration - r.exact) / r.exact;
                assert!(rel.abs() <= 1e-3, "acceleration off by {rel:e}");
            }
        }
    }
}

#[test]
fn bad_input_names_the_field() {
    let rod = rods()[0];
    for (case, field) in [
        (StickSlipCase { alpha: 2.0, ..rod }, "alpha"),
        (StickSlipCase { mu: -0.1, ..rod }, "friction"),
        (StickSlipCase { young: 0.0, ..rod }, "young"),
        (StickSlipCase { dt: 0.0, ..rod }, "dt"),
    ] {
        let e = case.run().unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
}
