//! A rigid plane: the simplest obstacle, and the one Romero's stick–slip test slides on.

use nalgebra::{Matrix3, Vector3};

use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// The half-space below the plane through `point` with outward unit normal `normal`.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    point: Vector3<f64>,
    normal: Vector3<f64>,
    friction: f64,
}

impl Plane {
    /// Plane through `point` (m) with outward normal `normal` (any length > 0; normalized here)
    /// and Coulomb coefficient `friction` (≥ 0).
    pub fn new(
        point: Vector3<f64>,
        normal: Vector3<f64>,
        friction: f64,
    ) -> Result<Self, ModelError> {
        if point.iter().any(|v| !v.is_finite()) {
            return Err(ModelError::InvalidStructure {
                field: "point".into(),
                reason: format!("must be finite, got {point:?}"),
            });
        }
        let length = normal.norm();
        if !(length.is_finite() && length > 0.0) {
            return Err(ModelError::InvalidStructure {
                field: "normal".into(),
                reason: format!("must be finite and non-zero, got {normal:?}"),
            });
        }
        if !(friction.is_finite() && friction >= 0.0) {
            return Err(ModelError::parameter(
                "friction",
                friction,
                "finite and ≥ 0",
            ));
        }
        Ok(Self {
            point,
            normal: normal / length,
            friction,
        })
    }

    /// Outward unit normal.
    pub fn normal(&self) -> Vector3<f64> {
        self.normal
    }

    /// A point of the plane (m).
    pub fn point(&self) -> Vector3<f64> {
        self.point
    }
}

impl Obstacle for Plane {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        SurfacePoint {
            distance: (p - self.point).dot(&self.normal),
            normal: self.normal,
            normal_derivative: Matrix3::zeros(),
        }
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        // The distance is linear along the segment.
        let approach = -dp.dot(&self.normal);
        let room = (p - self.point).dot(&self.normal) - clearance;
        if approach <= room.max(0.0) {
            1.0
        } else {
            (room / approach).max(0.0)
        }
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        (
            Vector3::repeat(f64::NEG_INFINITY),
            Vector3::repeat(f64::INFINITY),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_is_signed_along_the_normal() {
        let plane = Plane::new(
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(0.0, 0.0, 2.0),
            0.3,
        )
        .unwrap();
        let s = plane.surface(&Vector3::new(5.0, -2.0, 1.5));
        assert_eq!(s.distance, 0.5);
        assert_eq!(
            s.closest(&Vector3::new(5.0, -2.0, 1.5)),
            Vector3::new(5.0, -2.0, 1.0)
        );
        assert_eq!(plane.surface(&Vector3::new(0.0, 0.0, 0.0)).distance, -1.0);
    }

    #[test]
    fn bad_input_names_the_field() {
        let zero = Plane::new(Vector3::zeros(), Vector3::zeros(), 0.1).unwrap_err();
        assert!(zero.to_string().contains("normal"), "{zero}");
        let mu = Plane::new(Vector3::zeros(), Vector3::z(), -0.1).unwrap_err();
        assert!(mu.to_string().contains("friction"), "{mu}");
    }
}
