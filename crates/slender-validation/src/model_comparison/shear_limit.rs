//! Where the shearable rod models lose stability in tension.
//!
//! A straight shearable rod under tension T with frames turned by ψ from its chord has, per
//! length, W(ψ) = ½κGA λ² sin²ψ + ½EA(λ cos ψ − 1)² with λ = 1 + T/EA, so
//! W″(0) = λ(κGA λ − T): the straight state is unstable in shear once
//! T > κGA/(1 − κGA/EA). It is a property of the Cosserat (Reissner) rod with a linear
//! constitutive law at axial strains T/EA of tens of percent, not of the discretization; the
//! Kirchhoff rod has no such mode. The bend–twist coil hangs under a clamp tension ≈ ρAgL =
//! Γ EI/L², which exceeds the limit at the far corner of the (X, Y) grid.

use crate::materials::RodMaterialSet;

/// The tension (N) above which a straight shearable rod of `material` is unstable in shear
/// (infinite if κGA ≥ EA).
pub fn shear_tension_limit(material: &RodMaterialSet) -> f64 {
    let ga = material.shear().ga1.min(material.shear().ga2);
    let ea = material.properties.stiffness.ea;
    if ga >= ea {
        f64::INFINITY
    } else {
        ga / (1.0 - ga / ea)
    }
}

/// The clamp tension (N) of the bend–twist coil at Γ: its weight ρAgL = Γ EI/L².
pub fn coil_tension(material: &RodMaterialSet, gamma: f64) -> f64 {
    gamma * material.properties.stiffness.ei_min() / (material.length * material.length)
}
