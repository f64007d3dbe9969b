//! A discrete elastic rod: rest state, supports, loads, and assembly of energy, gradient and
//! banded Hessian over the free DOFs.

use nalgebra::{SMatrix, SVector};

use crate::error::{require_finite, ModelError};
use crate::geometry::{any_orthogonal, parallel_transport, Vec3};
use crate::linalg::SymmetricBandMatrix;
use crate::solver::problem::{AssemblyInfo, EquilibriumProblem};

use super::bending::{material_curvature, BendingHinge};
use super::dofs::{DofMap, FIXED, ROD_HALF_BANDWIDTH};
use super::frames::{updated_ref_twist, EdgeFrame, EdgeId, GhostEdge, ReferenceFrames};
use super::gravity::lumped_vertex_masses;
use super::hinge::{EdgeHessian, HingeFrame, HingeMatrix, HingeState, HingeVector, HINGE_DOFS};
use super::mesh::Grading;
use super::moment::MomentLoad;
use super::rest_curve::RestCurve;
use super::section::RodProperties;
use super::stretching::stretching_energy;
use super::twisting::TwistingHinge;

/// Which energy terms an assembly includes (all by default; tests select single terms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Terms {
    /// Stretching.
    pub stretching: bool,
    /// Bending.
    pub bending: bool,
    /// Twisting.
    pub twisting: bool,
    /// Gravity and point loads.
    pub external: bool,
}

impl Terms {
    /// Every term.
    pub const ALL: Self = Self {
        stretching: true,
        bending: true,
        twisting: true,
        external: true,
    };
    /// No term (combine with struct update syntax).
    pub const NONE: Self = Self {
        stretching: false,
        bending: false,
        twisting: false,
        external: false,
    };
}

/// A hinge of the rod: topology, DOF map and its bending and twisting data.
#[derive(Clone, Debug)]
struct Hinge {
    vertex: usize,
    edges: (EdgeId, EdgeId),
    dofs: [usize; HINGE_DOFS],
    bending: BendingHinge,
    twisting: TwistingHinge,
}

/// Positions, edge angles and adapted reference frames of a rod.
#[derive(Clone, Debug, PartialEq)]
pub struct RodState {
    positions: Vec<Vec3>,
    thetas: Vec<f64>,
    frames: ReferenceFrames,
    /// Unwrapped angle (rad) of each moment load's edge about its axis (see `moment.rs`).
    load_angles: Vec<f64>,
}

impl RodState {
    /// Vertex positions (m), from the start to the end of the rod.
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Edge material angles θ (rad) relative to the reference frames.
    pub fn thetas(&self) -> &[f64] {
        &self.thetas
    }

    /// Reference frames adapted to [`Self::positions`].
    pub fn frames(&self) -> &ReferenceFrames {
        &self.frames
    }

    /// This state moved rigidly: x ↦ R x + c for every vertex, frames (and clamp frames)
    /// rotated by R. Angles and reference twists are unchanged, so internal energy is too.
    pub fn rigidly_transformed(&self, rotation: &nalgebra::Rotation3<f64>, offset: &Vec3) -> Self {
        let rot = |f: &EdgeFrame| EdgeFrame {
            tangent: rotation * f.tangent,
            a1: rotation * f.a1,
        };
        let ghost = |g: &Option<GhostEdge>| {
            g.map(|g| GhostEdge {
                frame: rot(&g.frame),
                ..g
            })
        };
        Self {
            positions: self
                .positions
                .iter()
                .map(|x| rotation * x + offset)
                .collect(),
            thetas: self.thetas.clone(),
            frames: ReferenceFrames {
                edges: self.frames.edges.iter().map(rot).collect(),
                ghost_start: ghost(&self.frames.ghost_start),
                ghost_end: ghost(&self.frames.ghost_end),
                ref_twist: self.frames.ref_twist.clone(),
            },
            load_angles: self.load_angles.clone(),
        }
    }

    /// Material frame (m₁, m₂, t) of edge `j`.
    pub fn material_frame(&self, j: usize) -> [Vec3; 3] {
        let f = self.frames.edges[j];
        let a2 = f.tangent.cross(&f.a1);
        let (s, c) = self.thetas[j].sin_cos();
        [f.a1 * c + a2 * s, a2 * c - f.a1 * s, f.tangent]
    }
}

/// Where a rod is held.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Supports {
    /// Clamp at vertex 0: position and material frame fixed (ghost edge, half Voronoi cell).
    pub clamp_start: bool,
    /// Clamp at the last vertex.
    pub clamp_end: bool,
    /// Pinned vertices: position fixed, rotation free.
    pub pins: Vec<usize>,
    /// If `Some(k)`: motion restricted to the plane ⊥ e_k through the rest shape (coordinate k
    /// of every vertex and every twist angle fixed). For following symmetric equilibria of
    /// planar problems; the rest curve must lie in that plane.
    pub planar_axis: Option<usize>,
}

/// A dead force (N) on a vertex, scaled by the load factor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointForce {
    /// Vertex index.
    pub vertex: usize,
    /// Force (N).
    pub force: Vec3,
}

/// A moment (N m) on a vertex, scaled by the load factor. It acts on the edge that starts at
/// the vertex (the last edge for the last vertex); see `moment.rs` for its conservative form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointMoment {
    /// Vertex index.
    pub vertex: usize,
    /// Moment (N m).
    pub moment: Vec3,
}

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
        }
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
        let arclengths = self
            .grading
            .node_arclengths(self.n_elements, self.curve.length())?;
        let n = self.n_elements;
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
        for v in &self.supports.pins {
            if *v > n {
                return Err(ModelError::structure(
                    "pins",
                    format!("vertex {v} does not exist; valid vertices are 0..={n}"),
                ));
            }
        }
        for pf in &self.point_forces {
            if pf.vertex > n {
                return Err(ModelError::structure(
                    "point_forces.vertex",
                    format!(
                        "vertex {} does not exist; valid vertices are 0..={n}",
                        pf.vertex
                    ),
                ));
            }
            if pf.force.iter().any(|c| !c.is_finite()) {
                return Err(ModelError::structure(
                    "point_forces.force",
                    "must be finite",
                ));
            }
        }
        for pm in &self.point_moments {
            if pm.vertex > n {
                return Err(ModelError::structure(
                    "point_moments.vertex",
                    format!(
                        "vertex {} does not exist; valid vertices are 0..={n}",
                        pm.vertex
                    ),
                ));
            }
            if pm.moment.iter().any(|c| !c.is_finite()) {
                return Err(ModelError::structure(
                    "point_moments.moment",
                    "must be finite",
                ));
            }
        }
        require_finite("natural_twist", self.natural_twist)?;
        let mut pins = self.supports.pins.clone();
        pins.sort_unstable();
        pins.dedup();
        let n_clamps =
            usize::from(self.supports.clamp_start) + usize::from(self.supports.clamp_end);
        if n_clamps == 0 && pins.len() < 3 {
            return Err(ModelError::structure(
                "supports",
                "the rod can move as a rigid body; add a clamp, or pin at least three non-collinear vertices",
            ));
        }

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
                let m = m - t0 * t0.dot(&m);
                if !(m.norm() > 1e-12) || m.iter().any(|c| !c.is_finite()) {
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
        let ghost = |end_tangent: Vec3, edge: EdgeFrame, length: f64, theta: f64| GhostEdge {
            frame: EdgeFrame {
                tangent: end_tangent,
                a1: parallel_transport(&edge.a1, &edge.tangent, &end_tangent).normalize(),
            },
            theta,
            length,
        };
        let ghost_start = self
            .supports
            .clamp_start
            .then(|| ghost(points[0].1, edges[0], rest_lengths[0], 0.0));
        let ghost_end = self.supports.clamp_end.then(|| {
            ghost(
                points[n].1,
                edges[n - 1],
                rest_lengths[n - 1],
                self.natural_twist * arclengths[n],
            )
        });

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
        let dofs = DofMap::new(n, &fixed_vertices, self.supports.planar_axis);

        // Hinges: interior vertices, plus the clamped ends (half Voronoi cell, design.md §2.5).
        let mut topology: Vec<(usize, EdgeId, EdgeId, f64)> = Vec::new();
        if ghost_start.is_some() {
            topology.push((
                0,
                EdgeId::GhostStart,
                EdgeId::Real(0),
                0.5 * rest_lengths[0],
            ));
        }
        for i in 1..n {
            topology.push((
                i,
                EdgeId::Real(i - 1),
                EdgeId::Real(i),
                0.5 * (rest_lengths[i - 1] + rest_lengths[i]),
            ));
        }
        if ghost_end.is_some() {
            topology.push((
                n,
                EdgeId::Real(n - 1),
                EdgeId::GhostEnd,
                0.5 * rest_lengths[n - 1],
            ));
        }
        let hinge_edges: Vec<(EdgeId, EdgeId)> = topology.iter().map(|h| (h.1, h.2)).collect();
        let mut frames = ReferenceFrames {
            edges,
            ghost_start,
            ghost_end,
            ref_twist: Vec::with_capacity(topology.len()),
        };
        for &(l, r) in &hinge_edges {
            let t = updated_ref_twist(&frames.edge(l), &frames.edge(r), 0.0);
            frames.ref_twist.push(t);
        }
        let moments: Vec<MomentLoad> = self
            .point_moments
            .iter()
            .map(|pm| {
                let edge = pm.vertex.min(n - 1);
                MomentLoad::new(edge, pm.moment, &tangents[edge])
            })
            .collect();
        let rest = RodState {
            positions: positions.clone(),
            thetas: rest_thetas,
            frames,
            load_angles: vec![0.0; moments.len()],
        };

        let stiffness = self.properties.stiffness;
        let mut rod = Rod {
            properties: self.properties,
            rest_lengths,
            length: total,
            hinges: Vec::with_capacity(topology.len()),
            hinge_edges,
            vertex_masses: Vec::new(),
            nodal_forces: Vec::new(),
            preload_forces: Vec::new(),
            dofs,
            moments,
            fixed_vertices,
            supports: Supports {
                pins,
                ..self.supports
            },
            gravity: self.gravity,
            rest: rest.clone(),
        };
        rod.vertex_masses = lumped_vertex_masses(&rod.rest_lengths, self.properties.linear_density);
        rod.nodal_forces = rod
            .vertex_masses
            .iter()
            .map(|&m| self.gravity * m)
            .collect();
        for pf in &self.point_forces {
            rod.nodal_forces[pf.vertex] += pf.force;
        }
        rod.preload_forces = rod
            .vertex_masses
            .iter()
            .map(|&m| self.preload_gravity * m)
            .collect();
        for (k, &(vertex, l, r, voronoi)) in topology.iter().enumerate() {
            let mut hinge = Hinge {
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
            let hs = rod.hinge_state(&rest, &hinge, k);
            hinge.bending.rest_kappa = material_curvature(&HingeFrame::new(&hs));
            hinge.twisting.rest_twist = twist_strain(&hs);
            rod.hinges.push(hinge);
        }
        Ok(rod)
    }
}

/// Twist strain m = θᶠ − θᵉ + m_ref of a hinge (rad).
fn twist_strain(s: &HingeState) -> f64 {
    s.theta[1] - s.theta[0] + s.ref_twist
}

/// A discrete elastic rod ready to be solved (see the crate docs and design.md §2).
#[derive(Clone, Debug)]
pub struct Rod {
    properties: RodProperties,
    rest_lengths: Vec<f64>,
    length: f64,
    hinges: Vec<Hinge>,
    hinge_edges: Vec<(EdgeId, EdgeId)>,
    vertex_masses: Vec<f64>,
    /// Dead nodal forces (N) at load factor 1: gravity plus point forces.
    nodal_forces: Vec<Vec3>,
    /// Dead nodal forces (N) on at every load factor (preload gravity).
    preload_forces: Vec<Vec3>,
    dofs: DofMap,
    /// Point moments, split into bending and axial parts.
    moments: Vec<MomentLoad>,
    /// Vertices with fixed positions (clamps and pins), sorted.
    fixed_vertices: Vec<usize>,
    supports: Supports,
    gravity: Vec3,
    rest: RodState,
}

impl Rod {
    /// Number of edges.
    pub fn n_edges(&self) -> usize {
        self.rest_lengths.len()
    }

    /// Rest length of the centerline (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Section properties.
    pub fn properties(&self) -> &RodProperties {
        &self.properties
    }

    /// Rest edge lengths (m).
    pub fn rest_lengths(&self) -> &[f64] {
        &self.rest_lengths
    }

    /// Supports.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// Gravitational acceleration (m/s²) at load factor 1.
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The stress-free state (also the default initial state).
    pub fn rest_state(&self) -> &RodState {
        &self.rest
    }

    /// Lumped vertex masses (kg).
    pub fn vertex_masses(&self) -> &[f64] {
        &self.vertex_masses
    }

    /// Free-DOF vector of a state (coordinates in m, angles in rad).
    pub fn dof_vector(&self, s: &RodState) -> Vec<f64> {
        let mut v = vec![0.0; self.dofs.n_free()];
        self.dof_values(s, &mut v);
        v
    }

    fn hinge_dofs(&self, vertex: usize, l: EdgeId, r: EdgeId) -> [usize; HINGE_DOFS] {
        let mut d = [FIXED; HINGE_DOFS];
        let put_vertex = |slot: usize, v: usize, d: &mut [usize; HINGE_DOFS]| {
            for k in 0..3 {
                d[slot + k] = self.dofs.vertex(v, k);
            }
        };
        if let EdgeId::Real(j) = l {
            put_vertex(0, j, &mut d);
            d[3] = self.dofs.theta(j);
        }
        put_vertex(4, vertex, &mut d);
        if let EdgeId::Real(j) = r {
            d[7] = self.dofs.theta(j);
            put_vertex(8, j + 1, &mut d);
        }
        d
    }

    fn hinge_state(&self, s: &RodState, hinge: &Hinge, k: usize) -> HingeState {
        let v = hinge.vertex;
        let (l, r) = hinge.edges;
        let (x0, theta_l) = match l {
            EdgeId::Real(j) => (s.positions[j], s.thetas[j]),
            _ => {
                let g = s.frames.ghost_start.expect("start clamp");
                (s.positions[v] - g.frame.tangent * g.length, g.theta)
            }
        };
        let (x2, theta_r) = match r {
            EdgeId::Real(j) => (s.positions[j + 1], s.thetas[j]),
            _ => {
                let g = s.frames.ghost_end.expect("end clamp");
                (s.positions[v] + g.frame.tangent * g.length, g.theta)
            }
        };
        HingeState {
            x: [x0, s.positions[v], x2],
            a1: [s.frames.edge(l).a1, s.frames.edge(r).a1],
            theta: [theta_l, theta_r],
            ref_twist: s.frames.ref_twist[k],
        }
    }

    /// Energy (J) of the selected terms at load factor `load`.
    pub fn energy_terms(&self, s: &RodState, load: f64, terms: Terms) -> f64 {
        self.assemble_terms(s, load, terms, None, None, None).energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected terms. `grad` and `abs_grad`
    /// are overwritten; `hess` is zeroed first.
    pub fn assemble_terms(
        &self,
        s: &RodState,
        load: f64,
        terms: Terms,
        mut grad: Option<&mut [f64]>,
        mut hess: Option<&mut SymmetricBandMatrix>,
        mut abs_grad: Option<&mut [f64]>,
    ) -> AssemblyInfo {
        if let Some(g) = grad.as_deref_mut() {
            g.fill(0.0);
        }
        if let Some(a) = abs_grad.as_deref_mut() {
            a.fill(0.0);
        }
        if let Some(h) = hess.as_deref_mut() {
            h.set_zero();
        }
        let want_grad = grad.is_some() || abs_grad.is_some();
        let want_hess = hess.is_some();
        let mut info = AssemblyInfo::default();

        if terms.stretching {
            let ea = self.properties.stiffness.ea;
            let mut g6 = SVector::<f64, 6>::zeros();
            let mut h6 = SMatrix::<f64, 6, 6>::zeros();
            for (j, &rest_length) in self.rest_lengths.iter().enumerate() {
                g6.fill(0.0);
                h6.fill(0.0);
                let e = stretching_energy(
                    &s.positions[j],
                    &s.positions[j + 1],
                    rest_length,
                    ea,
                    want_grad.then_some(&mut g6),
                    want_hess.then_some(&mut h6),
                );
                info.energy += e;
                info.energy_magnitude += e.abs();
                let mut map = [FIXED; 6];
                for k in 0..3 {
                    map[k] = self.dofs.vertex(j, k);
                    map[3 + k] = self.dofs.vertex(j + 1, k);
                }
                scatter(
                    &map,
                    g6.as_slice(),
                    &h6,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
            }
        }

        if terms.bending || terms.twisting {
            let mut g = HingeVector::zeros();
            let mut h = HingeMatrix::zeros();
            let mut edge = EdgeHessian::default();
            for (k, hinge) in self.hinges.iter().enumerate() {
                let hs = self.hinge_state(s, hinge, k);
                let frame = HingeFrame::new(&hs);
                g.fill(0.0);
                if want_hess {
                    h.fill(0.0);
                    edge = EdgeHessian::default();
                }
                if terms.bending {
                    let e = hinge.bending.energy(
                        &frame,
                        want_grad.then_some(&mut g),
                        want_hess.then_some((&mut h, &mut edge)),
                    );
                    info.energy += e;
                    info.energy_magnitude += e.abs();
                }
                if terms.twisting {
                    let e = hinge.twisting.energy(
                        &frame,
                        twist_strain(&hs),
                        want_grad.then_some(&mut g),
                        want_hess.then_some((&mut h, &mut edge)),
                    );
                    info.energy += e;
                    info.energy_magnitude += e.abs();
                }
                if want_hess {
                    edge.scatter_into(&mut h);
                }
                scatter(
                    &hinge.dofs,
                    g.as_slice(),
                    &h,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
            }
        }

        if terms.external {
            // Dead loads: V = −λ Σ f_v·x_v, measured from the rest positions so that the
            // energy scale is the work done, not an arbitrary datum.
            for (v, (f, f0)) in self
                .nodal_forces
                .iter()
                .zip(&self.preload_forces)
                .enumerate()
            {
                let f = f * load + f0;
                let du = s.positions[v] - self.rest.positions[v];
                let w = f.dot(&du);
                info.energy -= w;
                info.energy_magnitude += w.abs();
                info.external_work += w;
                info.external_force = info.external_force.max(f.amax());
                for k in 0..3 {
                    let i = self.dofs.vertex(v, k);
                    if i == FIXED {
                        continue;
                    }
                    if let Some(gr) = grad.as_deref_mut() {
                        gr[i] -= f[k];
                    }
                    if let Some(a) = abs_grad.as_deref_mut() {
                        a[i] += f[k].abs();
                    }
                }
            }
            let mut g6 = SVector::<f64, 6>::zeros();
            let mut h6 = SMatrix::<f64, 6, 6>::zeros();
            for (m, &alpha) in self.moments.iter().zip(&s.load_angles) {
                let j = m.edge;
                let e = s.positions[j + 1] - s.positions[j];
                let v = m.bending_potential(&e, alpha, load, &mut g6, &mut h6);
                let dtheta = s.thetas[j] - self.rest.thetas[j];
                let w = -v + load * m.axial * dtheta;
                info.energy -= w;
                info.energy_magnitude += w.abs();
                info.external_work += w;
                info.external_force = info
                    .external_force
                    .max(load * (m.bending + m.axial.abs()) / self.length);
                let mut map = [FIXED; 6];
                for k in 0..3 {
                    map[k] = self.dofs.vertex(j, k);
                    map[3 + k] = self.dofs.vertex(j + 1, k);
                }
                scatter(
                    &map,
                    g6.as_slice(),
                    &h6,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
                let i = self.dofs.theta(j);
                if i != FIXED {
                    if let Some(gr) = grad.as_deref_mut() {
                        gr[i] -= load * m.axial;
                    }
                    if let Some(a) = abs_grad.as_deref_mut() {
                        a[i] += (load * m.axial).abs();
                    }
                }
            }
        }
        info
    }

    /// Continues the moment loads' unwrapped angles from `old` to the positions of `out`.
    fn update_load_angles(&self, old: &RodState, out: &mut RodState) {
        out.load_angles.clear();
        for (m, &alpha) in self.moments.iter().zip(&old.load_angles) {
            let j = m.edge;
            let e_old = old.positions[j + 1] - old.positions[j];
            let e_new = out.positions[j + 1] - out.positions[j];
            out.load_angles.push(m.updated_angle(&e_old, &e_new, alpha));
        }
    }

    /// `out` = `state` + `alpha·dx` in the plain linear sense (x ← x + α dx, θ ← θ + α dθ),
    /// with frames transported. The solver uses [`Rod::retract`]; this is the map whose
    /// derivatives the energy's gradient and Hessian are (finite-difference tests use it).
    pub fn displace_linear(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        out.positions.clone_from(&state.positions);
        out.thetas.clone_from(&state.thetas);
        for (i, &d) in dx.iter().enumerate() {
            let f = self.dofs.full_index(i);
            if f % 4 == 3 {
                out.thetas[f / 4] += alpha * d;
            } else {
                out.positions[f / 4][f % 4] += alpha * d;
            }
        }
        state
            .frames
            .transport_into(&out.positions, &self.hinge_edges, &mut out.frames);
        self.update_load_angles(state, out);
    }

    /// `out` = `state` moved along `alpha·dx` by a rotation-preserving retraction: each edge's
    /// step is applied as a rotation (by its transverse part) and an axial change (by its
    /// tangential part), and positions are rebuilt by walking the edges away from the
    /// supports. It agrees with x + α dx to first order, so Newton's convergence is unchanged,
    /// but a rotation no longer stretches edges at second order — with EA L²/EI ≈ 10⁷ that
    /// second-order stretch would otherwise force line searches to crawl.
    ///
    /// Between two fixed vertices the walks from both ends are blended linearly in arc length,
    /// so supports stay exact and only the O(|dx|²) closure gap is spread along the segment.
    pub fn retract(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        out.thetas.clone_from(&state.thetas);
        for j in 0..self.n_edges() {
            let i = self.dofs.theta(j);
            if i != FIXED {
                out.thetas[j] += alpha * dx[i];
            }
        }
        let x = &state.positions;
        let disp = |v: usize| -> Vec3 {
            let mut d = Vec3::zeros();
            for k in 0..3 {
                let i = self.dofs.vertex(v, k);
                if i != FIXED {
                    d[k] = alpha * dx[i];
                }
            }
            d
        };
        let new_edge = |j: usize| -> Vec3 {
            let e = x[j + 1] - x[j];
            let de = disp(j + 1) - disp(j);
            let len = e.norm();
            let t = e / len;
            let along = t.dot(&de);
            let across = de - t * along;
            let turn = across.norm() / len;
            let dir = if turn > 0.0 {
                let axis = t.cross(&across) / (turn * len);
                crate::geometry::rotate_about_axis(&t, &axis, turn)
            } else {
                t
            };
            dir * (len + along)
        };
        let n = self.n_edges();
        let p = &mut out.positions;
        p.clone_from(x);
        let fixed = &self.fixed_vertices;
        if fixed.is_empty() {
            for v in 0..=n {
                p[v] += disp(v);
            }
        } else {
            let first = fixed[0];
            let last = fixed[fixed.len() - 1];
            // Free tail before the first support: walk backward.
            for j in (0..first).rev() {
                p[j] = p[j + 1] - new_edge(j);
            }
            // Free tail after the last support: walk forward.
            for j in last..n {
                p[j + 1] = p[j] + new_edge(j);
            }
            // Segments between supports: blend the two walks.
            for w in fixed.windows(2) {
                let (a, b) = (w[0], w[1]);
                if b <= a + 1 {
                    continue;
                }
                let mut forward = x[a];
                let mut fwd = Vec::with_capacity(b - a + 1);
                fwd.push(forward);
                for j in a..b {
                    forward += new_edge(j);
                    fwd.push(forward);
                }
                let mut backward = x[b];
                let s_total: f64 = self.rest_lengths[a..b].iter().sum();
                let mut s_from_b = 0.0;
                for j in (a..b).rev() {
                    backward -= new_edge(j);
                    s_from_b += self.rest_lengths[j];
                    if j > a {
                        let wb = 1.0 - s_from_b / s_total;
                        p[j] = fwd[j - a] * (1.0 - wb) + backward * wb;
                    }
                }
            }
        }
        state
            .frames
            .transport_into(&out.positions, &self.hinge_edges, &mut out.frames);
        self.update_load_angles(state, out);
    }

    /// The largest edge-angle rotation (rad) that `alpha·dx` would cause, for the step cap.
    fn max_edge_rotation(&self, s: &RodState, dx: &[f64]) -> (f64, f64) {
        let n = self.n_edges();
        let disp = |v: usize| -> Vec3 {
            let mut d = Vec3::zeros();
            for k in 0..3 {
                let i = self.dofs.vertex(v, k);
                if i != FIXED {
                    d[k] = dx[i];
                }
            }
            d
        };
        let mut max_turn: f64 = 0.0;
        let mut max_stretch: f64 = 0.0;
        for j in 0..n {
            let e = s.positions[j + 1] - s.positions[j];
            let de = disp(j + 1) - disp(j);
            let len = e.norm();
            // Rotation of the edge direction ≈ |de⊥|/|e|, exact angle for the full step.
            let new = e + de;
            let turn = e.cross(&new).norm().atan2(e.dot(&new));
            max_turn = max_turn.max(turn);
            max_stretch = max_stretch.max(de.norm() / len);
        }
        (max_turn, max_stretch)
    }
}

/// Adds a stencil's gradient and Hessian into the global (free-DOF) arrays.
fn scatter<const D: usize>(
    map: &[usize; D],
    g: &[f64],
    h: &SMatrix<f64, D, D>,
    grad: &mut Option<&mut [f64]>,
    hess: &mut Option<&mut SymmetricBandMatrix>,
    abs_grad: &mut Option<&mut [f64]>,
) {
    for (a, &i) in map.iter().enumerate() {
        if i == FIXED {
            continue;
        }
        if let Some(gr) = grad.as_deref_mut() {
            gr[i] += g[a];
        }
        if let Some(ab) = abs_grad.as_deref_mut() {
            ab[i] += g[a].abs();
        }
        if let Some(hm) = hess.as_deref_mut() {
            for (b, &j) in map.iter().enumerate() {
                // Lower triangle only: the band matrix stores each pair once.
                if j != FIXED && j <= i {
                    hm.add(i, j, h[(a, b)]);
                }
            }
        }
    }
}

/// Largest rotation (rad) of an edge direction allowed in one Newton step.
const MAX_EDGE_TURN: f64 = std::f64::consts::FRAC_PI_4;
/// Largest change of an edge angle θ (rad) allowed in one Newton step.
const MAX_THETA_STEP: f64 = std::f64::consts::FRAC_PI_2;
/// Largest relative change of an edge vector allowed in one Newton step.
const MAX_EDGE_CHANGE: f64 = 0.5;

impl EquilibriumProblem for Rod {
    type State = RodState;

    fn n_free(&self) -> usize {
        self.dofs.n_free()
    }

    fn half_bandwidth(&self) -> usize {
        ROD_HALF_BANDWIDTH
    }

    fn energy(&self, state: &RodState, load: f64) -> f64 {
        self.energy_terms(state, load, Terms::ALL)
    }

    fn assemble(
        &self,
        state: &RodState,
        load: f64,
        grad: &mut [f64],
        hess: &mut SymmetricBandMatrix,
        abs_grad: &mut [f64],
    ) -> AssemblyInfo {
        self.assemble_terms(
            state,
            load,
            Terms::ALL,
            Some(grad),
            Some(hess),
            Some(abs_grad),
        )
    }

    fn dof_values(&self, state: &RodState, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            let f = self.dofs.full_index(i);
            *o = if f % 4 == 3 {
                state.thetas[f / 4]
            } else {
                state.positions[f / 4][f % 4]
            };
        }
    }

    fn displace(&self, state: &RodState, dx: &[f64], alpha: f64, out: &mut RodState) {
        self.retract(state, dx, alpha, out);
    }

    fn max_step(&self, state: &RodState, dx: &[f64]) -> f64 {
        let (turn, change) = self.max_edge_rotation(state, dx);
        let theta = (0..dx.len())
            .filter(|&i| self.dofs.is_angle(i))
            .map(|i| dx[i].abs())
            .fold(0.0, f64::max);
        let mut alpha: f64 = 1.0;
        if turn > MAX_EDGE_TURN {
            alpha = alpha.min(MAX_EDGE_TURN / turn);
        }
        if change > MAX_EDGE_CHANGE {
            alpha = alpha.min(MAX_EDGE_CHANGE / change);
        }
        if theta > MAX_THETA_STEP {
            alpha = alpha.min(MAX_THETA_STEP / theta);
        }
        alpha
    }

    fn force_length(&self, i: usize) -> f64 {
        if self.dofs.is_angle(i) {
            self.length
        } else {
            1.0
        }
    }

    fn dof_magnitude(&self, state: &RodState, i: usize) -> f64 {
        let f = self.dofs.full_index(i);
        if f % 4 == 3 {
            state.thetas[f / 4].abs().max(std::f64::consts::PI)
        } else {
            state.positions[f / 4].amax().max(self.length)
        }
    }

    fn inertia_metric(&self, i: usize) -> f64 {
        let f = self.dofs.full_index(i);
        if f % 4 == 3 {
            let j = f / 4;
            self.properties.linear_density
                * self.properties.stiffness.gyration_radius_sq()
                * self.rest_lengths[j]
        } else {
            self.vertex_masses[f / 4]
        }
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.properties.stiffness.ei_min() / (self.properties.linear_density * self.length.powi(4))
    }
}
