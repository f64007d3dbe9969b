//! Building a rod: rest curve, mesh, section, supports and loads, validated.

use crate::error::{require_finite, ModelError};
use crate::geometry::{any_orthogonal, Vec3};

use super::bending::{material_curvature, BendingHinge};
use super::clamp::{clamp_hinges, GhostEdge};
use super::dofs::DofMap;
use super::frames::{updated_ref_twist, EdgeFrame, EdgeId, ReferenceFrames};
use super::gravity::lumped_vertex_masses;
use super::hinge::Hinge;
use super::hinge::HingeFrame;
use super::mesh::Grading;
use super::model::Rod;
use super::point_loads::{
    moment_loads, nodal_forces, validate_point_loads, PointForce, PointMoment,
};
use super::rest_curve::RestCurve;
use super::section::RodProperties;
use super::state::RodState;
use super::stretching::StretchTerm;
use super::supports::Supports;
use super::twisting::TwistingHinge;

/// Builds a [`Rod`] from a rest curve, section properties, mesh and supports.
#[derive(Clone, Debug)]
pub struct RodBuilder {
    curve: RestCurve,
    properties: RodProperties,
    n_elements: usize,
    grading: Grading,
    supports: Supports,
    gravity: Vec3,
    point_forces: Vec<PointForce>,
    point_moments: Vec<PointMoment>,
    first_director: Option<Vec3>,
    natural_twist: f64,
    preload_gravity: Vec3,
    node_arclengths: Option<Vec<f64>>,
    allow_rigid_motion: bool,
    followers: Vec<(usize, Vec3, Vec3)>,
}

impl RodBuilder {
    /// A rod along `curve` with `properties`, 10 uniform elements, no supports and no loads.
    pub fn new(curve: RestCurve, properties: RodProperties) -> Self {
        Self {
            curve,
            properties,
            n_elements: 10,
            grading: Grading::Uniform,
            supports: Supports::default(),
            gravity: Vec3::zeros(),
            point_forces: Vec::new(),
            point_moments: Vec::new(),
            first_director: None,
            natural_twist: 0.0,
            preload_gravity: Vec3::zeros(),
            node_arclengths: None,
            allow_rigid_motion: false,
            followers: Vec::new(),
        }
    }

    /// Places the nodes at these arc lengths (m) along the rest curve instead of using
    /// [`Self::elements`] and [`Self::grading`]: strictly increasing, from 0 to the curve's
    /// length (e.g. the vertices of a polyline, so that the mesh is the polyline itself).
    pub fn nodes_at(mut self, arclengths: Vec<f64>) -> Self {
        self.node_arclengths = Some(arclengths);
        self
    }

    /// Number of elements (edges), ≥ 1.
    pub fn elements(mut self, n: usize) -> Self {
        self.n_elements = n;
        self
    }

    /// Node distribution (graded toward vertex 0).
    pub fn grading(mut self, grading: Grading) -> Self {
        self.grading = grading;
        self
    }

    /// Clamps vertex 0 in its rest position and orientation.
    pub fn clamp_start(mut self) -> Self {
        self.supports.clamp_start = true;
        self
    }

    /// Clamps the last vertex in its rest position and orientation.
    pub fn clamp_end(mut self) -> Self {
        self.supports.clamp_end = true;
        self
    }

    /// Restricts the motion to the plane ⊥ coordinate axis `axis` (0, 1, 2 for x, y, z): see
    /// [`Supports::planar_axis`].
    pub fn planar_motion(mut self, axis: usize) -> Self {
        self.supports.planar_axis = Some(axis);
        self
    }

    /// Pins vertex `v` (position fixed).
    pub fn pin(mut self, v: usize) -> Self {
        self.supports.pins.push(v);
        self
    }

    /// Gravitational acceleration (m/s²), e.g. (0, −9.81, 0).
    pub fn gravity(mut self, g: Vec3) -> Self {
        self.gravity = g;
        self
    }

    /// Gravitational acceleration (m/s²) that is always fully on, whatever the load factor:
    /// with it, ramping the load factor from 0 to 1 moves the gravity from `preload` to
    /// `preload + gravity` (e.g. the stages of the seed's bend–twist protocol).
    pub fn preload_gravity(mut self, g: Vec3) -> Self {
        self.preload_gravity = g;
        self
    }

    /// Adds a dead point force (N) on vertex `v`.
    pub fn point_force(mut self, v: usize, force: Vec3) -> Self {
        self.point_forces.push(PointForce { vertex: v, force });
        self
    }

    /// Adds a point moment (N m) on vertex `v`.
    pub fn point_moment(mut self, v: usize, moment: Vec3) -> Self {
        self.point_moments.push(PointMoment { vertex: v, moment });
        self
    }

    /// Adds a follower load on vertex `v`: a force (N) and a moment (N m), given in world axes
    /// at rest, that turn with the rod's material frame there (see `follower.rs`).
    pub fn follower_load(mut self, v: usize, force: Vec3, moment: Vec3) -> Self {
        self.followers.push((v, force, moment));
        self
    }

    /// Natural (stress-free) twist rate of the material frame about the centerline (rad/m),
    /// e.g. a pre-twisted strip. Default 0.
    pub fn natural_twist(mut self, rate: f64) -> Self {
        self.natural_twist = rate;
        self
    }

    /// Direction of the first material director m₁ at the start of the rest curve (made
    /// orthogonal to the tangent). Default: any deterministic orthogonal direction.
    pub fn first_director(mut self, m1: Vec3) -> Self {
        self.first_director = Some(m1);
        self
    }

    /// Builds the rod even if its own supports leave it free to move rigidly: for a member
    /// of a structure held through joints or structure-level supports (the structure checks
    /// the whole for free motion).
    pub fn allow_rigid_motion(mut self) -> Self {
        self.allow_rigid_motion = true;
        self
    }

    /// Validates the input and builds the rod.
    pub fn build(self) -> Result<Rod, ModelError> {
        self.properties.validate()?;
        self.curve.validate()?;
        for (k, c) in ["gravity.x", "gravity.y", "gravity.z"]
            .iter()
            .zip(self.gravity.iter())
        {
            require_finite(k, *c)?;
        }
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
        let rest_lengths: Vec<f64> = positions.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
        let total: f64 = rest_lengths.iter().sum();
        if let Some(j) = rest_lengths
            .iter()
            .position(|&l| !(l > 1e-9 * total) || !l.is_finite())
        {
            return Err(ModelError::structure(
                "rest_positions",
                format!("edge {j} has (near) zero length; points must be distinct"),
            ));
        }
        self.supports.validate(n)?;
        validate_point_loads(&self.point_forces, &self.point_moments, n)?;
        require_finite("natural_twist", self.natural_twist)?;
        let supports = self.supports.normalized(self.allow_rigid_motion)?;
        // Rest reference frames: space-parallel (Bishop) transport along the rest polygon, so
        // the rest reference twist is zero and the rest material frame twists only if the
        // curve does.
        let tangents: Vec<Vec3> = positions
            .windows(2)
            .map(|w| (w[1] - w[0]).normalize())
            .collect();
        let t0 = tangents[0];
        let d = match self.first_director {
            Some(m) => {
                // Rescale a finite director whose norm would overflow or underflow (only then,
                // so that ordinary inputs keep their exact bits).
                let big = m.amax();
                let m = if big.is_finite() && big > 0.0 && !(m.norm() > 1e-150 && m.norm() < 1e150)
                {
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
        // The director is given at the curve's start tangent; carry it to the first chord.
        let d = EdgeFrame {
            tangent: points[0].1,
            a1: (d - points[0].1 * points[0].1.dot(&d)).normalize(),
        }
        .transported_to(&t0)
        .a1;
        let mut edges = Vec::with_capacity(n);
        edges.push(EdgeFrame { tangent: t0, a1: d });
        for j in 1..n {
            let prev = edges[j - 1];
            edges.push(prev.transported_to(&tangents[j]));
        }
        // Natural twist: the rest material angle grows with arc length (edge midpoints), and
        // each clamp holds the material frame of its end of the rod (s = 0 and s = L).
        let rest_thetas: Vec<f64> = (0..n)
            .map(|j| self.natural_twist * 0.5 * (arclengths[j] + arclengths[j + 1]))
            .collect();
        let ghost_start = self
            .supports
            .clamp_start
            .then(|| GhostEdge::new(points[0].1, edges[0], rest_lengths[0], 0.0));
        let ghost_end = self.supports.clamp_end.then(|| {
            GhostEdge::new(
                points[n].1,
                edges[n - 1],
                rest_lengths[n - 1],
                self.natural_twist * arclengths[n],
            )
        });

        let fixed_vertices = supports.fixed_vertices(n);
        supports.check_plane(&positions, total)?;
        let dofs = DofMap::new(n, &fixed_vertices, supports.planar_axis);

        // Hinges: interior vertices, plus the clamped ends (half Voronoi cell, design.md §2.5).
        let (start_hinge, end_hinge) =
            clamp_hinges(&rest_lengths, ghost_start.is_some(), ghost_end.is_some());
        let mut topology: Vec<(usize, EdgeId, EdgeId, f64)> = Vec::new();
        topology.extend(start_hinge);
        for i in 1..n {
            topology.push((
                i,
                EdgeId::Real(i - 1),
                EdgeId::Real(i),
                0.5 * (rest_lengths[i - 1] + rest_lengths[i]),
            ));
        }
        topology.extend(end_hinge);
        let hinge_edges: Vec<(EdgeId, EdgeId)> = topology.iter().map(|h| (h.1, h.2)).collect();
        let mut frames = ReferenceFrames {
            edges,
            ghost_start,
            ghost_end,
            ref_twist: Vec::with_capacity(topology.len()),
            lengths: super::frames::EdgeLength::of_polyline(&positions),
        };
        for &(l, r) in &hinge_edges {
            let t = updated_ref_twist(&frames.edge(l), &frames.edge(r), 0.0);
            frames.ref_twist.push(t);
        }
        let mut rest = RodState {
            positions: positions.clone(),
            thetas: rest_thetas,
            frames,
            load_angles: Vec::new(),
            followers: Vec::new(),
        };
        let moments = moment_loads(&self.point_moments, &rest);
        rest.load_angles = vec![[0.0; 2]; moments.len()];

        let polygon_arclengths: Vec<f64> = std::iter::once(0.0)
            .chain(rest_lengths.iter().scan(0.0, |s, l| {
                *s += l;
                Some(*s)
            }))
            .collect();
        let stiffness = self.properties.stiffness;
        let mut rod = Rod {
            properties: self.properties,
            rest_lengths,
            length: total,
            stretch_terms: Vec::new(),
            hinges: Vec::with_capacity(topology.len()),
            hinge_edges,
            vertex_masses: Vec::new(),
            nodal_forces: Vec::new(),
            preload_forces: Vec::new(),
            dofs,
            moments,
            anchors: fixed_vertices.clone(),
            fixed_vertices,
            supports,
            gravity: self.gravity,
            rest: rest.clone(),
            arclengths: polygon_arclengths,
            load_path: Default::default(),
            followers: Vec::new(),
            saved_loads: Default::default(),
        };
        rod.stretch_terms = (0..n)
            .map(|j| StretchTerm {
                edge: j,
                dofs: rod.edge_dofs(j),
                rest_length: rod.rest_lengths[j],
                ea: stiffness.ea,
            })
            .collect();
        rod.vertex_masses = lumped_vertex_masses(&rod.rest_lengths, self.properties.linear_density);
        rod.nodal_forces = nodal_forces(&rod.vertex_masses, self.gravity, &self.point_forces);
        rod.preload_forces = rod
            .vertex_masses
            .iter()
            .map(|&m| self.preload_gravity * m)
            .collect();
        for &(v, force, moment) in &self.followers {
            if v > n {
                return Err(ModelError::structure(
                    "follower_loads.vertex",
                    format!("vertex {v} does not exist; valid vertices are 0..={n}"),
                ));
            }
            if force.iter().chain(moment.iter()).any(|c| !c.is_finite()) {
                return Err(ModelError::structure(
                    "follower_loads",
                    "force and moment must be finite",
                ));
            }
            if rod.fixed_vertices.contains(&v) {
                return Err(ModelError::structure(
                    "follower_loads.vertex",
                    format!("vertex {v} is held by a support: a follower load there does nothing"),
                ));
            }
            rod.followers.push(super::follower::FollowerLoad {
                vertex: v,
                edge: v.min(n - 1),
                force,
                moment,
            });
        }
        for (k, &(vertex, l, r, voronoi)) in topology.iter().enumerate() {
            let mut hinge = Hinge {
                index: k,
                vertex,
                edges: (l, r),
                dofs: rod.hinge_dofs(vertex, l, r),
                bending: BendingHinge {
                    stiffness: [stiffness.ei1, stiffness.ei2],
                    rest_kappa: [0.0; 2],
                    voronoi_length: voronoi,
                },
                twisting: TwistingHinge {
                    stiffness: stiffness.gj,
                    rest_twist: 0.0,
                    voronoi_length: voronoi,
                },
            };
            // Rest strains are evaluated by the same code as deformed ones, so the rest state
            // has exactly zero bending and twisting energy and gradient.
            let hs = rod.hinge_state(&rest, &hinge);
            hinge.bending.rest_kappa = material_curvature(&HingeFrame::new(&hs));
            hinge.twisting.rest_twist = hs.twist();
            rod.hinges.push(hinge);
        }
        let fresh: Vec<_> = rod.follower_loads(&rod.rest).collect();
        rod.rest.followers = fresh;
        Ok(rod)
    }
}
