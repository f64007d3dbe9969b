//! The seed's parameter sets (Table 1 for rods), as slender reads them.
//!
//! The printed units of Table 1 are not mutually consistent (design.md §B). The benchmarks
//! depend only on dimensionless groups — Γ (varied through gravity, as the seed does), GJ/EI
//! and EA·L²/EI — so the stiffnesses are used as printed, and the mass per length is read as:
//! * Ω_rod: ρ = 1273 kg/m³ with d = 0.5 mm a diameter;
//! * Ω_bundle: ρ = 2485 kg/m³ with the printed "d = 6 mm" a *radius*: only this reading gives
//!   Γ = ρ A g L³/EI ≈ 61.3 at earth gravity, as the seed states.

use slender_core::rod::{RodProperties, SectionStiffness};

/// A named rod parameter set.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RodMaterialSet {
    /// Identifier used in files and plots (`rod`, `bundle`).
    pub name: &'static str,
    /// Label with the seed's notation.
    pub label: &'static str,
    /// Length L (m).
    pub length: f64,
    /// Stiffnesses and mass per length.
    pub properties: RodProperties,
}

impl RodMaterialSet {
    /// Gravitational acceleration (m/s²) that gives the gravito-bending parameter `gamma`:
    /// g = Γ·EI/(ρA L³).
    pub fn gravity_for_gamma(&self, gamma: f64) -> f64 {
        gamma * self.properties.stiffness.ei_min()
            / (self.properties.linear_density * self.length.powi(3))
    }

    /// Γ at a given gravitational acceleration g (m/s²).
    pub fn gamma_at_gravity(&self, g: f64) -> f64 {
        self.properties.linear_density * g * self.length.powi(3)
            / self.properties.stiffness.ei_min()
    }
}

/// Ω_rod, Romero et al.'s proposal (seed Table 1): EI = 1 N m², GJ = 0.77 N m², EA = 1.6e7 N.
pub const OMEGA_ROD: RodMaterialSet = RodMaterialSet {
    name: "rod",
    label: "Ω_rod",
    length: 1.0,
    properties: RodProperties {
        stiffness: SectionStiffness {
            ea: 1.6e7,
            ei1: 1.0,
            ei2: 1.0,
            gj: 0.77,
        },
        // 1273 kg/m³ · π (0.25 mm)²
        linear_density: 1273.0 * std::f64::consts::PI * 0.25e-3 * 0.25e-3,
    },
};

/// Ω_bundle, a measured cable bundle (seed Table 1): EI = 4.5e-2 N m², GJ = 3.75e-2 N m²,
/// EA = 9.21e5 N; Γ ≈ 61.3 at earth gravity.
pub const OMEGA_BUNDLE: RodMaterialSet = RodMaterialSet {
    name: "bundle",
    label: "Ω_bundle",
    length: 1.0,
    properties: RodProperties {
        stiffness: SectionStiffness {
            ea: 9.21e5,
            ei1: 4.5e-2,
            ei2: 4.5e-2,
            gj: 3.75e-2,
        },
        // 2485 kg/m³ · π (6 mm)²
        linear_density: 2485.0 * std::f64::consts::PI * 6e-3 * 6e-3,
    },
};

/// Both rod sets, in the order the seed lists them.
pub const ROD_SETS: [RodMaterialSet; 2] = [OMEGA_ROD, OMEGA_BUNDLE];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bundle_is_gamma_61_at_earth_gravity() {
        let gamma = OMEGA_BUNDLE.gamma_at_gravity(9.81);
        assert!((gamma - 61.3).abs() < 0.1, "Γ = {gamma}");
    }

    #[test]
    fn gravity_and_gamma_are_inverse() {
        for set in ROD_SETS {
            let g = set.gravity_for_gamma(123.0);
            assert!((set.gamma_at_gravity(g) / 123.0 - 1.0).abs() < 1e-14);
        }
    }
}
