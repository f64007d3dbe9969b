//! Building a rod with material frames: the input both models share (rest curve, section,
//! shear, mesh, supports, loads), its validation, and the rest frames.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion};

use crate::error::{require_finite, ModelError};
use crate::geometry::{any_orthogonal, parallel_transport, rotate_about_axis, Vec3};
use crate::rod::{Grading, PointForce, PointMoment, RestCurve, RodProperties, Supports};

use super::section::ShearStiffness;

/// Input of a discrete Cosserat rod or an SE(3) beam; `K` carries the model's own options and
/// selects its `build` (see `cosserat::CosseratBuilder` and `se3::Se3Builder`).
///
/// Semantics follow [`RodBuilder`](crate::rod::RodBuilder): nodes on the exact rest curve,
/// clamps hold the exact pose of the curve at their end, moments act on the frame at (or just
/// after) their vertex, gravity is lumped on the vertices.
#[derive(Clone, Debug)]
pub struct FramedRodBuilder<K> {
    pub(crate) curve: RestCurve,
    pub(crate) properties: RodProperties,
    pub(crate) shear: ShearStiffness,
    pub(crate) n_elements: usize,
    pub(crate) grading: Grading,
    pub(crate) supports: Supports,
    pub(crate) gravity: Vec3,
    pub(crate) preload_gravity: Vec3,
    pub(crate) point_forces: Vec<PointForce>,
    pub(crate) point_moments: Vec<PointMoment>,
    pub(crate) first_director: Option<Vec3>,
    pub(crate) natural_twist: f64,
    pub(crate) node_arclengths: Option<Vec<f64>>,
    pub(crate) allow_rigid_motion: bool,
    pub(crate) options: K,
}

impl<K: Default> FramedRodBuilder<K> {
    /// A rod along `curve` with `properties` and shear stiffnesses `shear`, 10 uniform
    /// elements, no supports and no loads.
    pub fn new(curve: RestCurve, properties: RodProperties, shear: ShearStiffness) -> Self {
        Self {
            curve,
            properties,
            shear,
            n_elements: 10,
            grading: Grading::Uniform,
            supports: Supports::default(),
            gravity: Vec3::zeros(),
            preload_gravity: Vec3::zeros(),
            point_forces: Vec::new(),
            point_moments: Vec::new(),
            first_director: None,
            natural_twist: 0.0,
            node_arclengths: None,
            allow_rigid_motion: false,
            options: K::default(),
        }
    }
}

impl<K> FramedRodBuilder<K> {
    /// Places the nodes at these arc lengths (m) along the rest curve (strictly increasing,
    /// from 0 to the curve's length) instead of [`Self::elements`] and [`Self::grading`].
    pub fn nodes_at(mut self, arclengths: Vec<f64>) -> Self {
        self.node_arclengths = Some(arclengths);
        self
    }

    /// Number of elements, ≥ 1.
    pub fn elements(mut self, n: usize) -> Self {
        self.n_elements = n;
        self
    }

    /// Node distribution (graded toward vertex 0).
    pub fn grading(mut self, grading: Grading) -> Self {
        self.grading = grading;
        self
    }

    /// Clamps vertex 0 in the exact rest pose of the curve's start.
    pub fn clamp_start(mut self) -> Self {
        self.supports.clamp_start = true;
        self
    }

    /// Clamps the last vertex in the exact rest pose of the curve's end.
    pub fn clamp_end(mut self) -> Self {
        self.supports.clamp_end = true;
        self
    }

    /// Restricts the motion to the plane ⊥ coordinate axis `axis` (0, 1, 2): that coordinate
    /// of every vertex is held, and frames turn about that axis only.
    pub fn planar_motion(mut self, axis: usize) -> Self {
        self.supports.planar_axis = Some(axis);
        self
    }

    /// Pins vertex `v` (position held, frames free).
    pub fn pin(mut self, v: usize) -> Self {
        self.supports.pins.push(v);
        self
    }

    /// Gravitational acceleration (m/s²) at load factor 1.
    pub fn gravity(mut self, g: Vec3) -> Self {
        self.gravity = g;
        self
    }

    /// Gravitational acceleration (m/s²) that is on at every load factor (see
    /// [`RodBuilder::preload_gravity`](crate::rod::RodBuilder::preload_gravity)).
    pub fn preload_gravity(mut self, g: Vec3) -> Self {
        self.preload_gravity = g;
        self
    }

    /// Adds a dead point force (N) on vertex `v`.
    pub fn point_force(mut self, v: usize, force: Vec3) -> Self {
        self.point_forces.push(PointForce { vertex: v, force });
        self
    }

    /// Adds a point moment (N m) at vertex `v` (see `framed/moment.rs` for its form).
    pub fn point_moment(mut self, v: usize, moment: Vec3) -> Self {
        self.point_moments.push(PointMoment { vertex: v, moment });
        self
    }

    /// Natural twist rate (rad/m) of the material frame about the centerline. Default 0.
    pub fn natural_twist(mut self, rate: f64) -> Self {
        self.natural_twist = rate;
        self
    }

    /// Direction of the first director d₁ at the start of the rest curve (made orthogonal to
    /// the tangent). Default: any deterministic orthogonal direction.
    pub fn first_director(mut self, d1: Vec3) -> Self {
        self.first_director = Some(d1);
        self
    }

    /// Builds the rod even if its own supports leave it free to move rigidly: for a member
    /// of a structure that checks the whole for free motion, or is allowed it (a rod in free
    /// fall, or resting on obstacles, in a time run; see
    /// [`StructureBuilder::allow_free_motion`](crate::structure::StructureBuilder::allow_free_motion)).
    pub fn allow_rigid_motion(mut self) -> Self {
        self.allow_rigid_motion = true;
        self
    }

    /// The nodes, validated input and supports (everything but the frames).
    pub(crate) fn geometry(&self) -> Result<RestGeometry, ModelError> {
        self.properties.validate()?;
        self.shear.validate()?;
        self.curve.validate()?;
        for (k, c) in ["gravity.x", "gravity.y", "gravity.z"]
            .iter()
            .zip(self.gravity.iter())
        {
            require_finite(k, *c)?;
        }
        for (k, c) in [
            "preload_gravity.x",
            "preload_gravity.y",
            "preload_gravity.z",
        ]
        .iter()
        .zip(self.preload_gravity.iter())
        {
            require_finite(k, *c)?;
        }
        require_finite("natural_twist", self.natural_twist)?;
        let arclengths = match &self.node_arclengths {
            None => self
                .grading
                .node_arclengths(self.n_elements, self.curve.length())?,
            Some(s) => {
                let total = self.curve.length();
                let ok = s.len() >= 2
                    && s[0] == 0.0
                    && (s[s.len() - 1] - total).abs() <= 1e-12 * total
                    && s.windows(2).all(|w| w[1] > w[0]);
                if !ok {
                    return Err(ModelError::structure(
                        "node_arclengths",
                        format!(
                            "need at least 2 strictly increasing values from 0 to the curve length {total}"
                        ),
                    ));
                }
                s.clone()
            }
        };
        let n = arclengths.len() - 1;
        let points: Vec<(Vec3, Vec3)> =
            arclengths.iter().map(|&s| self.curve.evaluate(s)).collect();
        let positions: Vec<Vec3> = points.iter().map(|p| p.0).collect();
        let tangents: Vec<Vec3> = points.iter().map(|p| p.1).collect();
        let rest_lengths: Vec<f64> = positions.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
        let total: f64 = rest_lengths.iter().sum();
        if let Some(j) = rest_lengths
            .iter()
            .position(|&l| !(l > 1e-9 * total) || !l.is_finite())
        {
            return Err(ModelError::structure(
                "rest_positions",
                format!("element {j} has (near) zero length; nodes must be distinct"),
            ));
        }
        let check_vertex = |field: &str, v: usize| {
            if v > n {
                Err(ModelError::structure(
                    field,
                    format!("vertex {v} does not exist; valid vertices are 0..={n}"),
                ))
            } else {
                Ok(())
            }
        };
        for &v in &self.supports.pins {
            check_vertex("pins", v)?;
        }
        for pf in &self.point_forces {
            check_vertex("point_forces.vertex", pf.vertex)?;
            if pf.force.iter().any(|c| !c.is_finite()) {
                return Err(ModelError::structure(
                    "point_forces.force",
                    "must be finite",
                ));
            }
        }
        for pm in &self.point_moments {
            check_vertex("point_moments.vertex", pm.vertex)?;
            if pm.moment.iter().any(|c| !c.is_finite()) {
                return Err(ModelError::structure(
                    "point_moments.moment",
                    "must be finite",
                ));
            }
        }
        let mut pins = self.supports.pins.clone();
        pins.sort_unstable();
        pins.dedup();
        if !self.supports.clamp_start
            && !self.supports.clamp_end
            && pins.len() < 3
            && !self.allow_rigid_motion
        {
            return Err(ModelError::structure(
                "supports",
                "the rod can move as a rigid body; add a clamp, or pin at least three non-collinear vertices",
            ));
        }
        let mut fixed_vertices = pins.clone();
        if self.supports.clamp_start {
            fixed_vertices.push(0);
        }
        if self.supports.clamp_end {
            fixed_vertices.push(n);
        }
        fixed_vertices.sort_unstable();
        fixed_vertices.dedup();
        if let Some(k) = self.supports.planar_axis {
            if k > 2 {
                return Err(ModelError::structure(
                    "planar_axis",
                    format!("got {k}; valid axes are 0 (x), 1 (y), 2 (z)"),
                ));
            }
            let c0 = positions[0][k];
            if positions.iter().any(|p| (p[k] - c0).abs() > 1e-12 * total) {
                return Err(ModelError::structure(
                    "planar_axis",
                    "the rest curve does not lie in the plane of motion",
                ));
            }
        }
        let t0 = tangents[0];
        let director = match self.first_director {
            Some(m) => {
                let big = m.amax();
                let m = if big.is_finite() && big > 0.0 {
                    m / big
                } else {
                    m
                };
                let scale = m.norm();
                let m = m - t0 * t0.dot(&m);
                if !(m.norm() > 1e-12 * scale.min(1.0))
                    || !scale.is_finite()
                    || m.iter().any(|c| !c.is_finite())
                {
                    return Err(ModelError::structure(
                        "first_director",
                        "must be finite and not parallel to the rod's first tangent",
                    ));
                }
                m.normalize()
            }
            None => any_orthogonal(&t0),
        };
        let polygon_arclengths: Vec<f64> = std::iter::once(0.0)
            .chain(rest_lengths.iter().scan(0.0, |s, l| {
                *s += l;
                Some(*s)
            }))
            .collect();
        Ok(RestGeometry {
            curve_arclengths: arclengths,
            arclengths: polygon_arclengths,
            positions,
            tangents,
            rest_lengths,
            length: total,
            director,
            pins,
            fixed_vertices,
        })
    }
}

/// The validated nodes of a rod and its supports.
#[derive(Clone, Debug)]
pub(crate) struct RestGeometry {
    /// Arc length (m) of every node along the rest curve.
    pub curve_arclengths: Vec<f64>,
    /// Arc length (m) of every node along the rest polygon.
    pub arclengths: Vec<f64>,
    /// Node positions (m).
    pub positions: Vec<Vec3>,
    /// Unit tangents of the curve at the nodes.
    pub tangents: Vec<Vec3>,
    /// Rest element lengths (m).
    pub rest_lengths: Vec<f64>,
    /// Length of the rest polygon (m).
    pub length: f64,
    /// d₁ at s = 0 (unit, ⊥ the curve's tangent there).
    pub director: Vec3,
    /// Pinned vertices, sorted.
    pub pins: Vec<usize>,
    /// Vertices whose positions supports hold, sorted.
    pub fixed_vertices: Vec<usize>,
}

/// The frame with directors d₁ (⊥ d₃), d₂ = d₃ × d₁, d₃.
pub(crate) fn frame_from(d1: &Vec3, d3: &Vec3) -> UnitQuaternion<f64> {
    let d2 = d3.cross(d1);
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(Matrix3::from_columns(
        &[*d1, d2, *d3],
    )))
}

/// Carries the unit vector `d` (⊥ `from`) to the unit tangent `to`, re-orthonormalized.
fn transported(d: &Vec3, from: &Vec3, to: &Vec3) -> Vec3 {
    let d = parallel_transport(d, from, to);
    (d - to * to.dot(&d)).normalize()
}

impl RestGeometry {
    /// Rest frames on the edges (d₃ along the chord; d₁ transported from the start director
    /// chord to chord, then turned by the natural twist at the edge's mid-arc-length), and the
    /// frames at s = 0 and s = L (d₃ the curve's tangent; the end's d₁ transported from the last
    /// chord and turned by the twist at L). The same frames as the discrete elastic rod's rest
    /// material frames.
    pub fn edge_frames(
        &self,
        natural_twist: f64,
    ) -> (Vec<UnitQuaternion<f64>>, [UnitQuaternion<f64>; 2]) {
        let n = self.rest_lengths.len();
        let chords: Vec<Vec3> = self
            .positions
            .windows(2)
            .map(|w| (w[1] - w[0]).normalize())
            .collect();
        let mut reference = Vec::with_capacity(n);
        reference.push(transported(&self.director, &self.tangents[0], &chords[0]));
        for j in 1..n {
            let d = transported(&reference[j - 1], &chords[j - 1], &chords[j]);
            reference.push(d);
        }
        let s = &self.curve_arclengths;
        let frames = (0..n)
            .map(|j| {
                let angle = natural_twist * 0.5 * (s[j] + s[j + 1]);
                let d1 = rotate_about_axis(&reference[j], &chords[j], angle);
                frame_from(&d1, &chords[j])
            })
            .collect();
        let start = frame_from(&self.director, &self.tangents[0]);
        let end_t = self.tangents[n];
        let d_end = transported(&reference[n - 1], &chords[n - 1], &end_t);
        let end = frame_from(
            &rotate_about_axis(&d_end, &end_t, natural_twist * s[n]),
            &end_t,
        );
        (frames, [start, end])
    }

    /// Rest frames at the nodes: d₃ the curve's tangent; d₁ transported from the start
    /// director node to node, then turned by the natural twist at the node's arc length.
    pub fn node_frames(&self, natural_twist: f64) -> Vec<UnitQuaternion<f64>> {
        let n = self.rest_lengths.len();
        let mut d = self.director;
        let mut out = Vec::with_capacity(n + 1);
        for i in 0..=n {
            if i > 0 {
                d = transported(&d, &self.tangents[i - 1], &self.tangents[i]);
            }
            let t = self.tangents[i];
            let d1 = rotate_about_axis(&d, &t, natural_twist * self.curve_arclengths[i]);
            out.push(frame_from(&d1, &t));
        }
        out
    }
}
