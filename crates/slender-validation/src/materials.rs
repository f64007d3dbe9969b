//! The seed's parameter sets (Table 1 for rods), as slender reads them.
//!
//! The printed units of Table 1 are not mutually consistent (design.md §B). The benchmarks
//! depend only on dimensionless groups — Γ (varied through gravity, as the seed does), GJ/EI
//! and EA·L²/EI — so the stiffnesses are used as printed, and the mass per length is read as:
//! * Ω_rod: ρ = 1273 kg/m³ with d = 0.5 mm a diameter;
//! * Ω_bundle: ρ = 2485 kg/m³ with the printed "d = 6 mm" a *radius*: only this reading gives
//!   Γ = ρ A g L³/EI ≈ 61.3 at earth gravity, as the seed states.

use serde::Serialize;

use slender_core::framed::ShearStiffness;
use slender_core::rod::{RodProperties, SectionStiffness};
use slender_core::shell::ShellProperties;

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

    /// Shear stiffness of the set for the shearable rod models: a solid circular section
    /// (see [`ShearStiffness::solid_circle`]).
    pub fn shear(&self) -> ShearStiffness {
        ShearStiffness::solid_circle(&self.properties.stiffness)
            .expect("the material sets have valid stiffnesses and Poisson ratios")
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

/// A named shell parameter set (seed Table 2); the width follows from the aspect ratio w/L.
///
/// The densities are printed in "kg/dm³" with values (1000, 1210) that only make sense as
/// kg/m³; Γ_shell = ρhgL³/D is varied through g, so the reading does not matter for Δy/Δx.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct ShellMaterialSet {
    /// Identifier used in files and plots (`shell`, `ips`, `combined`).
    pub name: &'static str,
    /// Label with the seed's notation.
    pub label: &'static str,
    /// Length L (m).
    pub length: f64,
    /// Thickness h (m).
    pub thickness: f64,
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson ratio ν.
    pub poisson: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
}

impl ShellMaterialSet {
    /// Shell properties at aspect ratio `width_ratio` = w/L.
    pub fn properties(&self, width_ratio: f64) -> ShellProperties {
        ShellProperties {
            length: self.length,
            width: width_ratio * self.length,
            thickness: self.thickness,
            young: self.young,
            poisson: self.poisson,
            density: self.density,
        }
    }

    /// The same set with another Poisson ratio (ν = 0 makes D·w = EI, so that the 1-D
    /// master curve is exact for the shell).
    pub fn with_poisson(self, poisson: f64) -> Self {
        Self { poisson, ..self }
    }
}

/// Ω_shell, Romero et al.'s proposal (seed Table 2): L = 1 m, h = 1 mm, E = 10530 MPa, ν = 0.35.
pub const OMEGA_SHELL: ShellMaterialSet = ShellMaterialSet {
    name: "shell",
    label: "Ω_shell",
    length: 1.0,
    thickness: 1e-3,
    young: 10530e6,
    poisson: 0.35,
    density: 1000.0,
};

/// Ω_IPS, the IPS defaults (seed Table 2): L = 0.1 m, h = 0.2 mm, E = 2380 MPa, ν = 0.36.
pub const OMEGA_IPS: ShellMaterialSet = ShellMaterialSet {
    name: "ips",
    label: "Ω_IPS",
    length: 0.1,
    thickness: 0.2e-3,
    young: 2380e6,
    poisson: 0.36,
    density: 1210.0,
};

/// Ω_combined (seed Table 2): L = 0.1 m, h = 0.2 mm, E = 10530 MPa, ν = 0.35 — the set of the
/// seed's Fig. 2 shell curves.
pub const OMEGA_COMBINED: ShellMaterialSet = ShellMaterialSet {
    name: "combined",
    label: "Ω_combined",
    length: 0.1,
    thickness: 0.2e-3,
    young: 10530e6,
    poisson: 0.35,
    density: 1000.0,
};

/// The three shell sets, in the order the seed lists them.
pub const SHELL_SETS: [ShellMaterialSet; 3] = [OMEGA_SHELL, OMEGA_IPS, OMEGA_COMBINED];

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
