//! Where a bend–twist grid point can be trusted: the master curve is that of an inextensible
//! rod resolved by the mesh, so a point whose rod stretches by more than a few per cent, whose
//! mesh cuts the rest coil too coarsely, or whose smallest eigenvalue lies outside anything
//! bending and gravity can produce is *flagged* and left out of the score (issue 17, case 4),
//! never scored silently.
//!
//! All three tests use only the point's parameters and its λ_min, not the code's decision:
//!
//! * **axial strain** at the clamp, where the whole weight hangs: with a free lower end the
//!   clamp tension is ρAgL = Γ·EI/L² in every configuration, so ε = Γ·EI/(EA·L²). Its effect
//!   on the boundary is a relative shift of order ε in X (the stretched rod is longer); above
//!   [`MAX_AXIAL_STRAIN`] it is no longer small against the ±5 % band the score leaves out;
//! * **rest-curvature resolution**: an element of the coil turns by φ = 2πY/n; the discrete
//!   curvature 2 tan(φ/2)/ℓ overstates φ/ℓ by tan(φ/2)/(φ/2) − 1 ≈ φ²/12, flagged above
//!   [`MAX_CURVATURE_ERROR`];
//! * **eigenvalue range**: the bending operator is non-negative and gravity softens a mode by
//!   at most the clamp tension over the element length squared, so a physical λ_min ρAL⁴/EI is
//!   ≥ −4Γn² (n elements); anything below it is a stretching or round-off artefact.

use serde::{Deserialize, Serialize};

use super::sweep::BendTwistRecord;
use crate::materials::RodMaterialSet;

/// Largest clamp axial strain of a scored point.
pub const MAX_AXIAL_STRAIN: f64 = 0.02;

/// Largest relative error of the discrete rest curvature of a scored point.
pub const MAX_CURVATURE_ERROR: f64 = 0.02;

/// A grid point's regime measures and whether each stays within its limit.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Regime {
    /// Axial strain at the clamp, Γ·EI/(EA·L²).
    pub axial_strain: f64,
    /// Relative error of the discrete rest curvature, tan(φ/2)/(φ/2) − 1 with φ = 2πY/n.
    pub curvature_error: f64,
    /// Lower bound −4Γn² of a physical λ_min ρAL⁴/EI.
    pub lambda_floor: f64,
    /// Why the point is not scored (empty: it is).
    pub reasons: Vec<String>,
}

impl Regime {
    /// The measures of `r`, a point of a rod of `material`.
    pub fn of(r: &BendTwistRecord, material: &RodMaterialSet) -> Self {
        let k = &material.properties.stiffness;
        let axial_strain = r.gamma * k.ei_min() / (k.ea * material.length.powi(2));
        let phi = 2.0 * std::f64::consts::PI * r.y / r.n_elements as f64;
        let curvature_error = (0.5 * phi).tan() / (0.5 * phi) - 1.0;
        let n = r.n_elements as f64;
        let lambda_floor = -4.0 * r.gamma * n * n;
        let mut reasons = Vec::new();
        if axial_strain > MAX_AXIAL_STRAIN {
            reasons.push(format!(
                "out of regime: clamp axial strain {:.1} % > {:.0} % (the master curve is \
                 inextensible)",
                100.0 * axial_strain,
                100.0 * MAX_AXIAL_STRAIN
            ));
        }
        // tan(φ/2) is infinite (or negative) once an element turns by π or more.
        if phi >= std::f64::consts::PI || !(curvature_error <= MAX_CURVATURE_ERROR) {
            reasons.push(format!(
                "under-resolved: each element turns by {:.0}° (rest curvature off by {:.1} % \
                 > {:.0} %)",
                phi.to_degrees(),
                100.0 * curvature_error,
                100.0 * MAX_CURVATURE_ERROR
            ));
        }
        if let Some(l) = r.lambda_min {
            if l < lambda_floor {
                reasons.push(format!(
                    "λ_min ρAL⁴/EI = {l:.3e} below the physical bound −4Γn² = {lambda_floor:.3e}"
                ));
            }
        }
        Self {
            axial_strain,
            curvature_error,
            lambda_floor,
            reasons,
        }
    }

    /// True if the point is in the master curve's regime and resolved.
    pub fn trusted(&self) -> bool {
        self.reasons.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::OMEGA_ROD;

    fn record(x: f64, y: f64, n: usize, lambda_min: Option<f64>) -> BendTwistRecord {
        BendTwistRecord {
            x,
            y,
            gamma: (2.0 * std::f64::consts::PI * x * y).powi(3),
            n_elements: n,
            xi_y: 0.0,
            xi_tau: 0.0,
            protocol_converged: true,
            protocol_3d_y: Some(false),
            protocol_3d_tau: Some(false),
            protocol_3d: Some(false),
            protocol_negative: Some(0),
            planar_converged: true,
            lambda_min,
            stability_3d: Some(false),
            buckled_xi_y: None,
            buckled_xi_tau: None,
            x_c1: None,
            x_c2: None,
            truth_3d: false,
            iterations: 0,
            failure: String::new(),
        }
    }

    #[test]
    fn the_seed_corridor_is_trusted_and_the_stretched_corner_is_not() {
        // X·Y = 1 (Γ ≈ 248): ε = 1.6e-5, 20 elements per turn: 18° per element (0.8 %).
        let r = Regime::of(&record(1.0, 1.0, 20, Some(3.0)), &OMEGA_ROD);
        assert!(r.trusted(), "{:?}", r.reasons);
        assert!((r.axial_strain - 248.05021344239853 / 1.6e7).abs() < 1e-12);
        // X = Y = 10: Γ ≈ 2.5e8, ε ≈ 15.5 — the rod more than doubles its length.
        let r = Regime::of(&record(10.0, 10.0, 200, Some(3.0)), &OMEGA_ROD);
        assert_eq!(r.reasons.len(), 1, "{:?}", r.reasons);
        assert!(r.reasons[0].starts_with("out of regime"));
    }

    #[test]
    fn coarse_coils_and_impossible_eigenvalues_are_flagged() {
        // 10 elements per turn: 36° per element, curvature off by 3.4 %.
        let r = Regime::of(&record(0.5, 1.0, 10, Some(1.0)), &OMEGA_ROD);
        assert!(
            (r.curvature_error
                - ((0.1 * std::f64::consts::PI).tan() / (0.1 * std::f64::consts::PI) - 1.0))
                .abs()
                < 1e-15
        );
        assert!(
            r.reasons.iter().any(|s| s.starts_with("under-resolved")),
            "{:?}",
            r.reasons
        );
        // A λ_min far below −4Γn² (the issue's −1e12 at a moderate Γ).
        let r = Regime::of(&record(0.5, 1.0, 40, Some(-1e12)), &OMEGA_ROD);
        assert_eq!(r.reasons.len(), 1, "{:?}", r.reasons);
        assert!(r.reasons[0].starts_with("λ_min"));
        // Half a turn per element: tan(φ/2) blows up; flagged, not NaN-silent.
        let r = Regime::of(&record(0.5, 5.0, 10, None), &OMEGA_ROD);
        assert!(!r.trusted());
    }
}
