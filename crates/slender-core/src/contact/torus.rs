//! A rigid ring: a solid torus (a ring clip, a grommet, an eyelet) that a cable runs through and
//! slides in — the sliding clip of a harness, as a contact rather than a held vertex.
//!
//! Only the cable's vertices touch obstacles, so a ring holds a cable whose elements near it
//! are shorter than the ring's tube diameter plus twice the cable's contact radius: a longer
//! edge could straddle the tube with a vertex on each side.

use nalgebra::{Matrix3, Vector3};

use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// The solid torus around the circle of radius `radius` about `center` in the plane normal to
/// `axis`; its tube has radius `tube_radius`.
#[derive(Clone, Debug, PartialEq)]
pub struct Torus {
    center: Vector3<f64>,
    axis: Vector3<f64>,
    radius: f64,
    tube_radius: f64,
    friction: f64,
}

impl Torus {
    /// Ring of centre `center` (m), axis `axis` (any length > 0: the direction a cable runs
    /// through it), radius `radius` (m, > 0: centre to the tube's centre circle), tube radius
    /// `tube_radius` (m, 0 < tube_radius < radius, so that it has a hole), Coulomb
    /// coefficient `friction` (≥ 0).
    pub fn new(
        center: Vector3<f64>,
        axis: Vector3<f64>,
        radius: f64,
        tube_radius: f64,
        friction: f64,
    ) -> Result<Self, ModelError> {
        let center = super::finite_point("center", center)?;
        let axis = super::unit_direction("axis", axis)?;
        crate::error::require_positive("radius", radius)?;
        crate::error::require_positive("tube_radius", tube_radius)?;
        if !(tube_radius < radius) {
            return Err(ModelError::structure(
                "tube_radius",
                format!("{tube_radius} m: must be < radius ({radius} m), or the ring has no hole"),
            ));
        }
        crate::error::require_non_negative("friction", friction)?;
        Ok(Self {
            center,
            axis,
            radius,
            tube_radius,
            friction,
        })
    }

    /// A unit vector across the axis (any one: the direction from the axis where it has none).
    fn any_across(&self) -> Vector3<f64> {
        let a = self.axis;
        let helper = if a.x.abs() < 0.9 {
            Vector3::x()
        } else {
            Vector3::y()
        };
        (helper - a * a.dot(&helper)).normalize()
    }
}

impl Obstacle for Torus {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        // q = p − c splits into z along the axis and ρ across it; the closest point of the
        // tube's centre circle is c + R ρ̂, and r = q − R ρ̂ points from it to p.
        let a = self.axis;
        let q = p - self.center;
        let z = a.dot(&q);
        let across = q - a * z;
        let rho = across.norm();
        let radial = if rho > 0.0 {
            across / rho
        } else {
            // On the axis every point of the circle is closest (the medial axis).
            self.any_across()
        };
        let r = radial * (rho - self.radius) + a * z;
        let len = r.norm();
        let (normal, curvature) = if len > 0.0 && rho > 0.0 {
            let n = r / len;
            // ∂n/∂p = (I − n nᵀ)/|r| · ∂r/∂p with ∂r/∂p = I − (R/ρ) t tᵀ, t = a × ρ̂ the circle's
            // tangent (⊥ n): (I − n nᵀ)/|r| − R/(ρ|r|) t tᵀ. Along t that is (ρ − R)/(ρ|r|),
            // the curvature of the surface of revolution there.
            let t = a.cross(&radial);
            (
                n,
                (Matrix3::identity() - n * n.transpose()) / len
                    - t * t.transpose() * (self.radius / (rho * len)),
            )
        } else if len > 0.0 {
            (r / len, Matrix3::zeros())
        } else {
            // On the tube's centre circle: deep inside, any outward direction.
            (radial, Matrix3::zeros())
        };
        SurfacePoint {
            distance: len - self.tube_radius,
            normal,
            normal_derivative: curvature,
        }
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        // The distance is exact (1-Lipschitz): conservative advancement.
        super::conservative_advancement(|x| self.surface(x).distance, p, dp, clearance)
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        // The circle reaches R·√(1 − a_k²) along axis k; the tube adds its radius.
        let reach = self
            .axis
            .map(|a| self.radius * (1.0 - a * a).max(0.0).sqrt() + self.tube_radius);
        (self.center - reach, self.center + reach)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tilted() -> Torus {
        Torus::new(
            Vector3::new(0.1, -0.2, 0.3),
            Vector3::new(0.3, -0.5, 0.8),
            0.05,
            0.01,
            0.3,
        )
        .unwrap()
    }

    #[test]
    fn distance_normal_and_curvature_match_differences() {
        let t = tilted();
        let a = t.axis;
        let u = t.any_across();
        let v = a.cross(&u);
        // Outside the ring, inside its hole, inside its tube, above its plane.
        for (x, y, z) in [
            (0.08, 0.01, 0.02),
            (0.012, -0.007, 0.004),
            (0.046, 0.011, -0.003),
            (-0.03, 0.02, 0.09),
        ] {
            let p = t.center + u * x + v * y + a * z;
            let s = t.surface(&p);
            crate::contact::assert_surface_derivatives(&t, &p, 1e-8, 1e-5);
            // The distance against the closed form: the hypot of the offsets from the circle.
            let rho = (x * x + y * y).sqrt();
            let exact = ((rho - 0.05).powi(2) + z * z).sqrt() - 0.01;
            assert!(
                (s.distance - exact).abs() < 1e-15,
                "{} vs {exact}",
                s.distance
            );
        }
        // On the axis, at the centre: the hole's radius less the tube's.
        assert!((t.surface(&t.center).distance - 0.04).abs() < 1e-15);
    }

    #[test]
    fn steps_stop_short_of_the_ring_and_pass_through_its_hole() {
        let t = Torus::new(Vector3::zeros(), Vector3::z(), 1.0, 0.2, 0.0).unwrap();
        // Through the hole along the axis: free.
        let from = Vector3::new(0.1, 0.0, -2.0);
        assert_eq!(
            t.time_of_impact(&from, &Vector3::new(0.0, 0.0, 4.0), 0.1),
            1.0
        );
        // Straight at the tube from above (x = 1): stops at the clearance, to the advancement's
        // 1e-3 of the room.
        let from = Vector3::new(1.0, 0.0, 2.0);
        let alpha = t.time_of_impact(&from, &Vector3::new(0.0, 0.0, -4.0), 0.1);
        let stop = from.z - 4.0 * alpha;
        assert!(
            (0.3 - 1e-12..0.3 + 1.7e-3).contains(&stop),
            "stopped at z = {stop}"
        );
        // Across the hole toward the tube's inside: stops where the gap is the clearance.
        let from = Vector3::new(0.0, 0.0, 0.0);
        let alpha = t.time_of_impact(&from, &Vector3::new(1.0, 0.0, 0.0), 0.1);
        let gap = t.surface(&Vector3::new(alpha, 0.0, 0.0)).distance;
        assert!((0.1 - 1e-12..0.1 + 0.6e-3).contains(&gap), "gap {gap}");
        // Along a chord of the hole that would cross the tube: stopped before it, not through.
        let from = Vector3::new(0.0, 0.0, 0.0);
        let alpha = t.time_of_impact(&from, &Vector3::new(3.0, 0.0, 0.0), 0.1);
        assert!(
            3.0 * alpha < 0.7 + 1e-12,
            "went through the tube: x = {}",
            3.0 * alpha
        );
    }

    #[test]
    fn bounds_hold_the_ring() {
        let t = tilted();
        let (lo, hi) = t.bounds();
        let u = t.any_across();
        let v = t.axis.cross(&u);
        for k in 0..360 {
            let phi = (k as f64).to_radians();
            let c = t.center + (u * phi.cos() + v * phi.sin()) * t.radius;
            for m in 0..36 {
                let psi = (m as f64 * 10.0).to_radians();
                let radial = (c - t.center).normalize();
                let p = c + (radial * psi.cos() + t.axis * psi.sin()) * t.tube_radius;
                for i in 0..3 {
                    assert!(p[i] >= lo[i] - 1e-15 && p[i] <= hi[i] + 1e-15);
                }
            }
        }
    }

    #[test]
    fn a_ring_without_a_hole_is_refused_by_name() {
        let e = Torus::new(Vector3::zeros(), Vector3::z(), 0.01, 0.01, 0.0).unwrap_err();
        assert!(e.to_string().contains("tube_radius"), "{e}");
        let e = Torus::new(Vector3::zeros(), Vector3::zeros(), 0.02, 0.01, 0.0).unwrap_err();
        assert!(e.to_string().contains("axis"), "{e}");
    }
}
