//! A rigid box (a bracket, a panel's edge, a housing): a cuboid of any pose.

use nalgebra::{Matrix3, Rotation3, Vector3};

use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// The box of centre `center`, half-extents `half` along its axes, turned by `rotation`.
#[derive(Clone, Debug, PartialEq)]
pub struct Cuboid {
    center: Vector3<f64>,
    half: Vector3<f64>,
    rotation: Rotation3<f64>,
    friction: f64,
}

impl Cuboid {
    /// Box of centre `center` (m), edge lengths `size` (m, each > 0) along its own axes,
    /// oriented by `rotation` (its axes are the rotation's columns), Coulomb coefficient
    /// `friction` (≥ 0).
    pub fn new(
        center: Vector3<f64>,
        size: Vector3<f64>,
        rotation: Rotation3<f64>,
        friction: f64,
    ) -> Result<Self, ModelError> {
        if center.iter().any(|v| !v.is_finite()) {
            return Err(ModelError::structure(
                "center",
                format!("must be finite, got {center:?}"),
            ));
        }
        for (k, name) in ["size[0]", "size[1]", "size[2]"].iter().enumerate() {
            crate::error::require_positive(name, size[k])?;
        }
        if rotation.matrix().iter().any(|v| !v.is_finite()) {
            return Err(ModelError::structure("rotation", "must be finite"));
        }
        crate::error::require_non_negative("friction", friction)?;
        Ok(Self {
            center,
            half: size * 0.5,
            rotation,
            friction,
        })
    }

    /// `p` in the box's frame.
    fn local(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.inverse() * (p - self.center)
    }

    /// The axes along which a local point lies beyond the box (a bit mask), 0 inside.
    fn region(&self, q: &Vector3<f64>) -> u8 {
        (0..3).fold(0, |m, k| {
            if q[k].abs() > self.half[k] {
                m | (1 << k)
            } else {
                m
            }
        })
    }
}

impl Obstacle for Cuboid {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        let q = self.local(p);
        let region = self.region(&q);
        if region == 0 {
            // Inside: the nearest face.
            let (k, depth) = (0..3)
                .map(|k| (k, q[k].abs() - self.half[k]))
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .expect("three axes");
            let mut n = Vector3::zeros();
            n[k] = if q[k] >= 0.0 { 1.0 } else { -1.0 };
            return SurfacePoint {
                distance: depth,
                normal: self.rotation * n,
                normal_derivative: Matrix3::zeros(),
            };
        }
        // Outside: from the closest point of the box.
        let closest = Vector3::from_fn(|k, _| q[k].clamp(-self.half[k], self.half[k]));
        let r = q - closest;
        let distance = r.norm();
        let n = r / distance;
        // The level set is flat over a face, a cylinder about an edge, a sphere about a
        // corner: ∂n/∂p = (I − n nᵀ − Σ over the free axes e eᵀ)/d, the free axes being those
        // along which the closest point slides.
        let mut curvature = Matrix3::identity() - n * n.transpose();
        for k in 0..3 {
            if region & (1 << k) == 0 {
                let mut e = Vector3::zeros();
                e[k] = 1.0;
                curvature -= e * e.transpose();
            }
        }
        let curvature = if region.count_ones() == 1 {
            Matrix3::zeros()
        } else {
            curvature / distance
        };
        let to_world = self.rotation.matrix();
        SurfacePoint {
            distance,
            normal: self.rotation * n,
            normal_derivative: to_world * curvature * to_world.transpose(),
        }
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        let (q0, q1) = (self.local(p), self.local(&(p + dp)));
        let (r0, r1) = (self.region(&q0), self.region(&q1));
        if r0 == r1 && r0.count_ones() == 1 {
            // Both ends beyond the same face: the distance is linear along the step.
            let k = r0.trailing_zeros() as usize;
            let (d0, d1) = (q0[k].abs() - self.half[k], q1[k].abs() - self.half[k]);
            if q0[k].signum() == q1[k].signum() {
                let room = d0 - clearance;
                return if d1 >= clearance {
                    1.0
                } else if room <= 0.0 {
                    0.0
                } else {
                    room / (d0 - d1)
                };
            }
        }
        // Elsewhere, conservative advancement.
        super::conservative_advancement(|x| self.surface(x).distance, p, dp, clearance)
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        let m = self.rotation.matrix().abs() * self.half;
        (self.center - m, self.center + m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn turned() -> Cuboid {
        Cuboid::new(
            Vector3::new(0.1, -0.2, 0.3),
            Vector3::new(0.4, 0.2, 0.6),
            Rotation3::new(Vector3::new(0.3, -0.5, 0.8)),
            0.2,
        )
        .unwrap()
    }

    #[test]
    fn distance_normal_and_curvature_match_differences_in_every_region() {
        let b = turned();
        let world = |q: Vector3<f64>| b.rotation * q + b.center;
        for q in [
            Vector3::new(0.35, 0.01, -0.05),  // face
            Vector3::new(0.31, 0.17, 0.02),   // edge
            Vector3::new(-0.28, 0.15, -0.41), // corner
            Vector3::new(0.05, -0.02, 0.1),   // inside
        ] {
            crate::contact::assert_surface_derivatives(&b, &world(q), 1e-8, 1e-6);
        }
        // A face point's distance is its height over the face.
        let s = b.surface(&world(Vector3::new(0.35, 0.01, -0.05)));
        assert!((s.distance - 0.15).abs() < 1e-14);
        assert!((b.surface(&world(Vector3::new(0.05, -0.02, 0.1))).distance + 0.08).abs() < 1e-14);
    }

    #[test]
    fn steps_stop_short_of_the_box() {
        let b = Cuboid::new(
            Vector3::zeros(),
            Vector3::new(2.0, 2.0, 2.0),
            Rotation3::identity(),
            0.0,
        )
        .unwrap();
        // Straight down on a face: exact.
        let p = Vector3::new(0.2, 0.3, 3.0);
        assert_eq!(
            b.time_of_impact(&p, &Vector3::new(0.0, 0.0, -4.0), 0.5),
            0.375
        );
        // Sliding along the face is free.
        assert_eq!(b.time_of_impact(&p, &Vector3::new(0.5, 0.0, 0.0), 0.5), 1.0);
        // Toward a corner: stops before the inflated corner, not far before it.
        let from = Vector3::new(3.0, 3.0, 3.0);
        let t = b.time_of_impact(&from, &Vector3::new(-2.0, -2.0, -2.0), 0.1);
        let end = b
            .surface(&(from + Vector3::new(-2.0, -2.0, -2.0) * t))
            .distance;
        assert!((0.1..0.101).contains(&end), "distance at the stop {end}");
    }
}
