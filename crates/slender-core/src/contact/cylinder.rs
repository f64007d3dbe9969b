//! A rigid round bar: an infinite circular cylinder (a bracket, a pipe, a drum).

use nalgebra::{Matrix3, Vector3};

use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// The solid cylinder of radius `radius` around the line through `point` along `axis`.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    point: Vector3<f64>,
    axis: Vector3<f64>,
    radius: f64,
    friction: f64,
}

impl Cylinder {
    /// Cylinder around the line through `point` (m) along `axis` (any length > 0), radius
    /// `radius` (m, > 0), Coulomb coefficient `friction` (≥ 0).
    pub fn new(
        point: Vector3<f64>,
        axis: Vector3<f64>,
        radius: f64,
        friction: f64,
    ) -> Result<Self, ModelError> {
        let point = super::finite_point("point", point)?;
        let axis = super::unit_direction("axis", axis)?;
        crate::error::require_positive("radius", radius)?;
        crate::error::require_non_negative("friction", friction)?;
        Ok(Self {
            point,
            axis,
            radius,
            friction,
        })
    }

    /// The part of `v` across the axis.
    fn across(&self, v: &Vector3<f64>) -> Vector3<f64> {
        v - self.axis * self.axis.dot(v)
    }
}

impl Obstacle for Cylinder {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        let r = self.across(&(p - self.point));
        let len = r.norm();
        let (normal, curvature) = if len > 0.0 {
            let n = r / len;
            let a = self.axis;
            // ∂n/∂p = (I − a aᵀ − n nᵀ)/|r|: only the direction across both n and the axis bends.
            (
                n,
                (Matrix3::identity() - a * a.transpose() - n * n.transpose()) / len,
            )
        } else {
            (self.across(&Vector3::x()).normalize(), Matrix3::zeros())
        };
        SurfacePoint {
            distance: len - self.radius,
            normal,
            normal_derivative: curvature,
        }
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        super::ball_time_of_impact(
            self.across(&(p - self.point)),
            self.across(dp),
            self.radius + clearance,
        )
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        // Infinite along its axis unless the axis is a coordinate direction.
        let mut lo = Vector3::repeat(f64::NEG_INFINITY);
        let mut hi = Vector3::repeat(f64::INFINITY);
        for k in 0..3 {
            if self.axis[k] == 0.0 {
                lo[k] = self.point[k] - self.radius;
                hi[k] = self.point[k] + self.radius;
            }
        }
        (lo, hi)
    }
}
