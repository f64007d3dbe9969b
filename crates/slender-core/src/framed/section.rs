//! The shear stiffnesses that rods with material frames add to the section's stiffnesses.

use serde::{Deserialize, Serialize};

use crate::error::{require_positive, ModelError};
use crate::rod::SectionStiffness;

/// Shear stiffnesses κGA of a section (N), for shear along the first and second material
/// directors d₁ and d₂ (the directions of `ei1` and `ei2`'s bending, see
/// [`SectionStiffness`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(deny_unknown_fields)]
pub struct ShearStiffness {
    /// Shear stiffness along d₁, κ₁GA (N).
    pub ga1: f64,
    /// Shear stiffness along d₂, κ₂GA (N).
    pub ga2: f64,
}

impl ShearStiffness {
    /// The same shear stiffness `ga` (N) in both directions.
    pub fn isotropic(ga: f64) -> Self {
        Self { ga1: ga, ga2: ga }
    }

    /// Checks both stiffnesses are finite and > 0 (a rod with zero shear stiffness has no
    /// stable equilibrium); the error names the field.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_positive("ga1", self.ga1)?;
        require_positive("ga2", self.ga2)?;
        Ok(())
    }

    /// The shear stiffness of a solid homogeneous circular section whose other stiffnesses
    /// are `s`: with J = I₁ + I₂, G/E = GJ/(EI₁ + EI₂), so GA = EA·GJ/(EI₁ + EI₂) and
    /// ν = E/(2G) − 1; Timoshenko's coefficient of a solid circle is κ = 6(1+ν)/(7+6ν).
    /// Errors if the stiffnesses are invalid or imply ν outside (−1, 0.5].
    pub fn solid_circle(s: &SectionStiffness) -> Result<Self, ModelError> {
        s.validate()?;
        let g_over_e = s.gj / (s.ei1 + s.ei2);
        let nu = 0.5 / g_over_e - 1.0;
        if !(nu > -1.0 && nu <= 0.5) {
            return Err(ModelError::parameter(
                "gj",
                s.gj,
                "such that the implied Poisson ratio (EI₁+EI₂)/(2GJ) − 1 is in (−1, 0.5]",
            ));
        }
        let kappa = 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
        Ok(Self::isotropic(kappa * s.ea * g_over_e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solid_circle_matches_timoshenko() {
        // Steel-like: E = 2e11, ν = 0.3, d = 1 cm.
        let (e, nu, d) = (2e11_f64, 0.3_f64, 0.01_f64);
        let g = e / (2.0 * (1.0 + nu));
        let a = std::f64::consts::PI * d * d / 4.0;
        let i = std::f64::consts::PI * d.powi(4) / 64.0;
        let s = SectionStiffness::isotropic(e * a, e * i, g * 2.0 * i);
        let shear = ShearStiffness::solid_circle(&s).unwrap();
        let kappa = 6.0 * 1.3 / (7.0 + 1.8);
        assert!((shear.ga1 / (kappa * g * a) - 1.0).abs() < 1e-14);
    }

    #[test]
    fn zero_shear_stiffness_is_rejected_by_name() {
        let e = ShearStiffness { ga1: 1.0, ga2: 0.0 }
            .validate()
            .unwrap_err();
        assert!(e.to_string().contains("ga2"));
    }
}
