//! Strain measures of an SE(3) beam state for output.

use nalgebra::{SVector, Vector3};

use crate::framed::FramedState;

use super::element::element_twist;
use super::model::Se3Rod;

/// The constant strain of one element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementStrain {
    /// The element.
    pub element: usize,
    /// ε = log(H_A⁻¹H_B)/L₀ = (translation rate, rotation rate): shear along d₁, d₂ and
    /// 1 + axial strain (dimensionless); curvature about d₁, d₂ and twist (1/m).
    pub strain: SVector<f64, 6>,
    /// The rest value of `strain`.
    pub rest: SVector<f64, 6>,
}

impl ElementStrain {
    /// Shear along d₁, d₂ and axial strain (dimensionless): the translation rate minus e₃.
    pub fn shear_extension(&self) -> Vector3<f64> {
        Vector3::new(self.strain[0], self.strain[1], self.strain[2] - 1.0)
    }

    /// Curvature about d₁, d₂ and twist (1/m).
    pub fn darboux(&self) -> Vector3<f64> {
        Vector3::new(self.strain[3], self.strain[4], self.strain[5])
    }
}

impl Se3Rod {
    /// The strain of every element of `s`.
    pub fn element_strains(&self, s: &FramedState) -> Vec<ElementStrain> {
        self.elements
            .iter()
            .map(|e| ElementStrain {
                element: e.element,
                strain: element_twist(s, e.element) / e.rest_length,
                rest: e.rest / e.rest_length,
            })
            .collect()
    }
}
