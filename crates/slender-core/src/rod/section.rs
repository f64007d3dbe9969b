//! Cross-sections and materials, reduced to the four stiffnesses and the mass per length that
//! the rod model needs.

use serde::{Deserialize, Serialize};

use crate::error::{require_positive, ModelError};

/// Stiffnesses of a rod cross-section.
///
/// Bending stiffness `ei1` resists bending that moves the centerline along the first material
/// direction m₁ (rotation about m₂); `ei2` the bending along m₂. For a rectangle of width `w`
/// along m₁ and height `h` along m₂, `ei1 = E h w³/12` (the strong axis when w > h).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionStiffness {
    /// Axial stiffness EA (N).
    pub ea: f64,
    /// Bending stiffness about m₂, EI₁ (N m²).
    pub ei1: f64,
    /// Bending stiffness about m₁, EI₂ (N m²).
    pub ei2: f64,
    /// Torsional stiffness GJ (N m²).
    pub gj: f64,
}

impl SectionStiffness {
    /// Isotropic bending: `ei1 = ei2 = ei`.
    pub fn isotropic(ea: f64, ei: f64, gj: f64) -> Self {
        Self {
            ea,
            ei1: ei,
            ei2: ei,
            gj,
        }
    }

    /// Checks every stiffness is finite and > 0; the error names the field.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_positive("ea", self.ea)?;
        require_positive("ei1", self.ei1)?;
        require_positive("ei2", self.ei2)?;
        require_positive("gj", self.gj)?;
        Ok(())
    }

    /// The smaller bending stiffness (N m²): the one that sets the gravito-bending parameter.
    pub fn ei_min(&self) -> f64 {
        self.ei1.min(self.ei2)
    }

    /// Squared radius of gyration (m²) implied by the stiffnesses, (EI₁+EI₂)/EA, which equals
    /// (I₁+I₂)/A for a homogeneous section. Used for the rotational inertia of twist.
    pub fn gyration_radius_sq(&self) -> f64 {
        (self.ei1 + self.ei2) / self.ea
    }
}

/// Geometric cross-section shapes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "snake_case", deny_unknown_fields)]
pub enum CrossSection {
    /// Solid circle of diameter `diameter` (m).
    Circle {
        /// Diameter (m).
        diameter: f64,
    },
    /// Solid rectangle, `width` (m) along m₁ and `height` (m) along m₂.
    Rectangle {
        /// Extent along m₁ (m).
        width: f64,
        /// Extent along m₂ (m).
        height: f64,
    },
}

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson's ratio ν (dimensionless, in (−1, 0.5]).
    pub poisson: f64,
    /// Mass density ρ (kg/m³).
    pub density: f64,
}

impl Material {
    /// Shear modulus G = E / (2(1+ν)) (Pa).
    pub fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    fn validate(&self) -> Result<(), ModelError> {
        require_positive("young", self.young)?;
        require_positive("density", self.density)?;
        if !(self.poisson.is_finite() && self.poisson > -1.0 && self.poisson <= 0.5) {
            return Err(ModelError::parameter(
                "poisson",
                self.poisson,
                "finite and in (-1, 0.5]",
            ));
        }
        Ok(())
    }
}

impl CrossSection {
    /// Area (m²).
    pub fn area(&self) -> f64 {
        match *self {
            Self::Circle { diameter } => std::f64::consts::PI * diameter * diameter / 4.0,
            Self::Rectangle { width, height } => width * height,
        }
    }

    fn validate(&self) -> Result<(), ModelError> {
        match *self {
            Self::Circle { diameter } => require_positive("diameter", diameter).map(|_| ()),
            Self::Rectangle { width, height } => {
                require_positive("width", width)?;
                require_positive("height", height).map(|_| ())
            }
        }
    }

    /// Stiffnesses and mass per length (kg/m) of this section made of `material`.
    pub fn properties(&self, material: &Material) -> Result<RodProperties, ModelError> {
        self.validate()?;
        material.validate()?;
        let e = material.young;
        let g = material.shear_modulus();
        let stiffness = match *self {
            Self::Circle { diameter } => {
                let i = std::f64::consts::PI * diameter.powi(4) / 64.0;
                SectionStiffness::isotropic(e * self.area(), e * i, g * 2.0 * i)
            }
            Self::Rectangle { width, height } => {
                // Saint-Venant torsion constant of a rectangle (Roark's approximation, good to
                // < 1 % for any aspect ratio): J = a b³ [1/3 − 0.21 (b/a)(1 − (b/a)⁴/12)].
                let (a, b) = if width >= height {
                    (width, height)
                } else {
                    (height, width)
                };
                let r = b / a;
                let j = a * b.powi(3) * (1.0 / 3.0 - 0.21 * r * (1.0 - r.powi(4) / 12.0));
                SectionStiffness {
                    ea: e * width * height,
                    ei1: e * height * width.powi(3) / 12.0,
                    ei2: e * width * height.powi(3) / 12.0,
                    gj: g * j,
                }
            }
        };
        Ok(RodProperties {
            stiffness,
            linear_density: material.density * self.area(),
        })
    }
}

/// Everything the rod energies need from the section: stiffnesses and mass per length.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RodProperties {
    /// Section stiffnesses.
    pub stiffness: SectionStiffness,
    /// Mass per unit length ρA (kg/m).
    pub linear_density: f64,
}

impl RodProperties {
    /// Checks all fields; the error names the offending one.
    pub fn validate(&self) -> Result<(), ModelError> {
        self.stiffness.validate()?;
        require_positive("linear_density", self.linear_density)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_matches_closed_forms() {
        let m = Material {
            young: 2.0e11,
            poisson: 0.3,
            density: 7800.0,
        };
        let p = CrossSection::Circle { diameter: 0.01 }
            .properties(&m)
            .unwrap();
        let i = std::f64::consts::PI * 1e-8 / 64.0;
        assert!((p.stiffness.ei1 / (2.0e11 * i) - 1.0).abs() < 1e-14);
        assert!((p.stiffness.gj / p.stiffness.ei1 - 1.0 / 1.3).abs() < 1e-14);
        assert!(
            (p.linear_density / (7800.0 * std::f64::consts::PI * 1e-4 / 4.0) - 1.0).abs() < 1e-14
        );
    }

    #[test]
    fn thin_rectangle_torsion_tends_to_wh3_over_3() {
        let m = Material {
            young: 1.0,
            poisson: 0.0,
            density: 1.0,
        };
        let p = CrossSection::Rectangle {
            width: 1.0,
            height: 1e-3,
        }
        .properties(&m)
        .unwrap();
        let j_thin = 1e-9 / 3.0;
        assert!((p.stiffness.gj / (0.5 * j_thin) - 1.0).abs() < 1e-3);
        assert!(p.stiffness.ei1 > p.stiffness.ei2);
    }

    #[test]
    fn bad_values_name_the_field() {
        let m = Material {
            young: f64::NAN,
            poisson: 0.3,
            density: 1.0,
        };
        let err = CrossSection::Circle { diameter: 1.0 }
            .properties(&m)
            .unwrap_err();
        assert!(err.to_string().contains("young"));
        let s = SectionStiffness::isotropic(1.0, -1.0, 1.0);
        assert!(s.validate().unwrap_err().to_string().contains("ei1"));
    }
}
