//! Smooth rest (stress-free) centerlines, evaluated by arc length.
//!
//! Nodes of a rod are placed on the exact curve, so the rest polygon is inscribed in it and
//! its discrete curvature is the rest curvature of the model: an unloaded rod has zero energy
//! and zero gradient whatever the mesh.

use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

use crate::error::{require_positive, ModelError};
use crate::geometry::Vec3;

/// A smooth rest centerline parametrized by arc length s ∈ [0, length]. This is also the
/// `centerline` of a rod in a scene file (`kind = "straight" | "arc" | "helix" | "polyline"`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "schema", derive(schemars::JsonSchema))]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum RestCurve {
    /// Straight segment from `start` (m) along `direction` (normalized internally).
    Straight {
        /// First point (m).
        start: [f64; 3],
        /// Direction (any non-zero length).
        direction: [f64; 3],
        /// Length (m).
        length: f64,
    },
    /// Circular arc (possibly more than one turn) of radius `radius` (m), starting at `start`
    /// with unit tangent `tangent` and curving toward `normal`.
    #[serde(rename = "arc", alias = "circle")]
    Circle {
        /// First point (m).
        start: [f64; 3],
        /// Tangent at the start (normalized internally).
        tangent: [f64; 3],
        /// Direction toward the center at the start (made orthogonal to the tangent).
        normal: [f64; 3],
        /// Radius (m).
        radius: f64,
        /// Arc length (m); may exceed 2π·radius (coils).
        length: f64,
    },
    /// Circular helix about `axis` through the center, starting at `start` with the tangent
    /// made of `tangent`'s component ⊥ axis plus the pitch.
    Helix {
        /// First point (m).
        start: [f64; 3],
        /// Helix axis direction.
        axis: [f64; 3],
        /// Direction from the start point toward the axis.
        normal: [f64; 3],
        /// Radius of the helix (m).
        radius: f64,
        /// Rise along the axis per turn (m); negative for a left-handed helix.
        pitch: f64,
        /// Arc length (m).
        length: f64,
    },
    /// Polygonal line through `points` (m), parametrized by arc length along its segments.
    /// Its tangent is that of the segment at `s` (the first at s = 0, the last at the end).
    Polyline {
        /// At least two points, consecutive points distinct.
        points: Vec<[f64; 3]>,
    },
}

fn unit(field: &str, v: [f64; 3]) -> Result<Vec3, ModelError> {
    let v = Vector3::from(v);
    let n = v.norm();
    if !n.is_finite() || n <= 0.0 {
        return Err(ModelError::structure(
            field,
            "must be a finite, non-zero 3-vector",
        ));
    }
    Ok(v / n)
}

fn finite_point(field: &str, v: [f64; 3]) -> Result<Vec3, ModelError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vector3::from(v))
    } else {
        Err(ModelError::structure(field, "must be a finite 3-vector"))
    }
}

/// Orthonormal frame (tangent direction, normal, binormal) for circle-like curves.
fn plane_frame(tangent: Vec3, normal_hint: Vec3, field: &str) -> Result<(Vec3, Vec3), ModelError> {
    let n = normal_hint - tangent * tangent.dot(&normal_hint);
    let len = n.norm();
    if len < 1e-12 {
        return Err(ModelError::structure(
            field,
            "must not be parallel to the tangent/axis",
        ));
    }
    Ok((tangent, n / len))
}

impl RestCurve {
    /// Arc length (m).
    pub fn length(&self) -> f64 {
        match *self {
            Self::Straight { length, .. }
            | Self::Circle { length, .. }
            | Self::Helix { length, .. } => length,
            Self::Polyline { ref points } => points
                .windows(2)
                .map(|w| (Vector3::from(w[1]) - Vector3::from(w[0])).norm())
                .sum(),
        }
    }

    /// Checks the parameters; errors name the field.
    pub fn validate(&self) -> Result<(), ModelError> {
        if let Self::Polyline { points } = self {
            return validate_polyline(points);
        }
        require_positive("length", self.length())?;
        match *self {
            Self::Straight {
                start, direction, ..
            } => {
                finite_point("start", start)?;
                unit("direction", direction)?;
            }
            Self::Circle {
                start,
                tangent,
                normal,
                radius,
                ..
            } => {
                finite_point("start", start)?;
                require_positive("radius", radius)?;
                let t = unit("tangent", tangent)?;
                plane_frame(t, unit("normal", normal)?, "normal")?;
            }
            Self::Helix {
                start,
                axis,
                normal,
                radius,
                pitch,
                ..
            } => {
                finite_point("start", start)?;
                require_positive("radius", radius)?;
                crate::error::require_finite("pitch", pitch)?;
                let a = unit("axis", axis)?;
                plane_frame(a, unit("normal", normal)?, "normal")?;
            }
            Self::Polyline { .. } => {}
        }
        Ok(())
    }

    /// Position (m) and unit tangent at arc length `s` (m). Call [`Self::validate`] first.
    pub fn evaluate(&self, s: f64) -> (Vec3, Vec3) {
        match *self {
            Self::Straight {
                start, direction, ..
            } => {
                let d = Vector3::from(direction).normalize();
                (Vector3::from(start) + d * s, d)
            }
            Self::Circle {
                start,
                tangent,
                normal,
                radius,
                ..
            } => {
                let t0 = Vector3::from(tangent).normalize();
                let n0 = Vector3::from(normal);
                let n0 = (n0 - t0 * t0.dot(&n0)).normalize();
                let phi = s / radius;
                let (sin, cos) = phi.sin_cos();
                let p = Vector3::from(start) + t0 * (radius * sin) + n0 * (radius * (1.0 - cos));
                (p, t0 * cos + n0 * sin)
            }
            Self::Helix {
                start,
                axis,
                normal,
                radius,
                pitch,
                ..
            } => {
                let a = Vector3::from(axis).normalize();
                let n0 = Vector3::from(normal);
                let n0 = (n0 - a * a.dot(&n0)).normalize();
                let b0 = a.cross(&n0);
                let rise = pitch / (2.0 * std::f64::consts::PI);
                let speed = (radius * radius + rise * rise).sqrt();
                let phi = s / speed;
                let (sin, cos) = phi.sin_cos();
                let center = Vector3::from(start) + n0 * radius;
                // Start point is at −radius·n0 from the center; rotate about a.
                let p = center - n0 * (radius * cos) + b0 * (radius * sin) + a * (rise * phi);
                let t = (n0 * (radius * sin) + b0 * (radius * cos) + a * rise) / speed;
                (p, t)
            }
            Self::Polyline { ref points } => polyline_at(points, s),
        }
    }
}

/// Checks a polyline: ≥ 2 finite points, no two consecutive ones coincident (relative to the
/// total length), so that every segment has a tangent.
fn validate_polyline(points: &[[f64; 3]]) -> Result<(), ModelError> {
    if points.len() < 2 {
        return Err(ModelError::structure(
            "points",
            format!("got {} point(s); need at least 2", points.len()),
        ));
    }
    for (k, p) in points.iter().enumerate() {
        finite_point(&format!("points[{k}]"), *p)?;
    }
    let lengths: Vec<f64> = points
        .windows(2)
        .map(|w| (Vector3::from(w[1]) - Vector3::from(w[0])).norm())
        .collect();
    let total: f64 = lengths.iter().sum();
    if let Some(k) = lengths.iter().position(|&l| !(l > 1e-9 * total)) {
        return Err(ModelError::structure(
            format!("points[{}]", k + 1),
            format!(
                "coincides with points[{k}]; consecutive points must be distinct (segment length > 1e-9 × total length)"
            ),
        ));
    }
    Ok(())
}

/// Position and unit tangent at arc length `s` along a validated polyline.
fn polyline_at(points: &[[f64; 3]], s: f64) -> (Vec3, Vec3) {
    let n_seg = points.len() - 1;
    let mut start = 0.0;
    for k in 0..n_seg {
        let a = Vector3::from(points[k]);
        let b = Vector3::from(points[k + 1]);
        let len = (b - a).norm();
        let t = (b - a) / len;
        if s < start + len || k + 1 == n_seg {
            // The segment's exact end point when s reaches it, so that nodes placed at the
            // cumulative lengths reproduce the points bit for bit.
            let p = if s - start >= len {
                b
            } else {
                a + t * (s - start)
            };
            return (p, t);
        }
        start += len;
    }
    unreachable!("a validated polyline has at least one segment")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_unit_speed(c: &RestCurve) {
        c.validate().unwrap();
        let h = 1e-6;
        for k in 0..10 {
            let s = c.length() * (k as f64 + 0.5) / 10.0;
            let (p0, t) = c.evaluate(s - h);
            let (p1, _) = c.evaluate(s + h);
            let (_, tm) = c.evaluate(s);
            assert!(((p1 - p0) / (2.0 * h) - tm).norm() < 1e-8, "{c:?} at {s}");
            assert!((tm.norm() - 1.0).abs() < 1e-12);
            let _ = t;
        }
    }

    #[test]
    fn curves_have_unit_speed_tangents() {
        check_unit_speed(&RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 1.0, 0.0],
            length: 2.0,
        });
        check_unit_speed(&RestCurve::Circle {
            start: [0.0; 3],
            tangent: [0.0, 0.0, -1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 0.3,
            length: 5.0,
        });
        check_unit_speed(&RestCurve::Helix {
            start: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 0.2,
            pitch: 0.1,
            length: 3.0,
        });
    }

    #[test]
    fn seed_circle_starts_downward() {
        // Seed eq. (1) corrected (design.md §1.2): tangent −z at s = 0, curling toward +x.
        let c = RestCurve::Circle {
            start: [0.0; 3],
            tangent: [0.0, 0.0, -1.0],
            normal: [1.0, 0.0, 0.0],
            radius: 1.0,
            length: std::f64::consts::PI,
        };
        let (p, t) = c.evaluate(std::f64::consts::PI);
        assert!((p - Vector3::new(2.0, 0.0, 0.0)).norm() < 1e-14);
        assert!((t - Vector3::new(0.0, 0.0, 1.0)).norm() < 1e-14);
    }

    #[test]
    fn invalid_curves_name_the_field() {
        let c = RestCurve::Straight {
            start: [0.0; 3],
            direction: [0.0; 3],
            length: 1.0,
        };
        assert!(c.validate().unwrap_err().to_string().contains("direction"));
        let c = RestCurve::Straight {
            start: [0.0; 3],
            direction: [1.0, 0.0, 0.0],
            length: 0.0,
        };
        assert!(c.validate().unwrap_err().to_string().contains("length"));
    }
}
