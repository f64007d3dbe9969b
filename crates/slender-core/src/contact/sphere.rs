//! A rigid ball.

use nalgebra::{Matrix3, Vector3};

use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// The ball of centre `center` and radius `radius`.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    center: Vector3<f64>,
    radius: f64,
    friction: f64,
}

impl Sphere {
    /// Ball of centre `center` (m) and radius `radius` (m, > 0), Coulomb coefficient
    /// `friction` (≥ 0).
    pub fn new(center: Vector3<f64>, radius: f64, friction: f64) -> Result<Self, ModelError> {
        if center.iter().any(|v| !v.is_finite()) {
            return Err(ModelError::structure(
                "center",
                format!("must be finite, got {center:?}"),
            ));
        }
        crate::error::require_positive("radius", radius)?;
        crate::error::require_non_negative("friction", friction)?;
        Ok(Self {
            center,
            radius,
            friction,
        })
    }
}

impl Obstacle for Sphere {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        let r = p - self.center;
        let len = r.norm();
        // At the centre any direction is a closest one.
        let (normal, curvature) = if len > 0.0 {
            let n = r / len;
            (n, (Matrix3::identity() - n * n.transpose()) / len)
        } else {
            (Vector3::z(), Matrix3::zeros())
        };
        SurfacePoint {
            distance: len - self.radius,
            normal,
            normal_derivative: curvature,
        }
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        super::ball_time_of_impact(p - self.center, *dp, self.radius + clearance)
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        let r = Vector3::repeat(self.radius);
        (self.center - r, self.center + r)
    }
}
