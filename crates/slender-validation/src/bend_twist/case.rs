//! The bend–twist benchmark's rod (seed §4, design.md §1.2): a naturally circular rod of
//! radius R, clamped at the top with its tangent along gravity (−z), curling toward +x.
//!
//! X = (R/L)Γ^{1/3} and Y = L/(2πR), so Γ = (2πXY)³ and L/R = 2πY. The seed's eq. (1) has a
//! typo (its tangent at s = 0 is −x); we use r°(s) = R(1 − cos(s/R), 0, −sin(s/R)), whose
//! tangent at the clamp is −z as the text says.

use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve, Rod};
use slender_core::ModelError;

use crate::materials::{RodMaterialSet, OMEGA_ROD};
use crate::rod_model::RodSpec;

/// One point of the (X, Y) plane and its discretization.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct BendTwistCase {
    /// X = (R/L) Γ^{1/3} (> 0).
    pub x: f64,
    /// Y = L/(2πR), the number of turns of the rest coil (> 0).
    pub y: f64,
    /// Elements per unit Y (the seed uses 100).
    pub elements_per_turn: f64,
    /// Lower bound on the element count.
    pub min_elements: usize,
    /// Material set (Ω_rod in the seed).
    pub material: RodMaterialSet,
}

impl BendTwistCase {
    /// A case with Ω_rod and `elements_per_turn` elements per unit Y (at least 10).
    pub fn new(x: f64, y: f64, elements_per_turn: f64) -> Self {
        Self {
            x,
            y,
            elements_per_turn,
            min_elements: 10,
            material: OMEGA_ROD,
        }
    }

    /// Γ = (2πXY)³.
    pub fn gamma(&self) -> f64 {
        (2.0 * std::f64::consts::PI * self.x * self.y).powi(3)
    }

    /// Rest radius R = L/(2πY) (m).
    pub fn radius(&self) -> f64 {
        self.material.length / (2.0 * std::f64::consts::PI * self.y)
    }

    /// Number of elements: max(min_elements, round(elements_per_turn · Y)).
    pub fn n_elements(&self) -> usize {
        ((self.elements_per_turn * self.y).round() as usize).max(self.min_elements)
    }

    /// Magnitude of gravity (m/s²) that gives Γ.
    pub fn gravity(&self) -> f64 {
        self.material.gravity_for_gamma(self.gamma())
    }

    fn validate(&self) -> Result<(), ModelError> {
        for (name, v) in [
            ("x", self.x),
            ("y", self.y),
            ("elements_per_turn", self.elements_per_turn),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(ModelError::parameter(name, v, "finite and > 0"));
            }
        }
        Ok(())
    }

    /// The clamped coil with gravity `ramped` scaled by the load factor and `preload` always
    /// on (m/s²); see [`RodBuilder::preload_gravity`](slender_core::rod::RodBuilder::preload_gravity).
    pub fn build(&self, ramped: Vec3, preload: Vec3) -> Result<Rod, ModelError> {
        self.spec(ramped, preload, None)?.build_der()
    }

    /// The same rod with its motion restricted to its plane (xz): for the planar equilibrium.
    pub fn build_planar(&self, ramped: Vec3) -> Result<Rod, ModelError> {
        self.spec(ramped, Vec3::zeros(), Some(1))?.build_der()
    }

    /// The coil for any rod model (motion restricted to the plane ⊥ `planar_axis` if given).
    pub fn spec(
        &self,
        ramped: Vec3,
        preload: Vec3,
        planar_axis: Option<usize>,
    ) -> Result<RodSpec, ModelError> {
        self.validate()?;
        Ok(RodSpec {
            curve: RestCurve::Circle {
                start: [0.0; 3],
                tangent: [0.0, 0.0, -1.0],
                normal: [1.0, 0.0, 0.0],
                radius: self.radius(),
                length: self.material.length,
            },
            properties: self.material.properties,
            shear: self.material.shear(),
            elements: self.n_elements(),
            grading: Grading::Uniform,
            first_director: Vec3::x(),
            gravity: ramped,
            preload_gravity: preload,
            planar_axis,
            darboux: Default::default(),
        })
    }
}
