//! A model in contact with rigid obstacles, as one [`EquilibriumProblem`] for the unchanged
//! solver: the model's energy plus a barrier energy of every site's gap to every obstacle.
//!
//! Each centerline vertex (a [`ContactSite`]) at distance d from an obstacle's surface has the
//! gap g = d − r (r its cable's radius: each member may have its own, see
//! [`ContactProblem::with_radii`]) and adds κ·w·b(g), with b the barrier of
//! [`barrier`](super::barrier), w the centerline length the vertex stands for and κ the
//! barrier stiffness (N/m²). Its exact gradient and Hessian follow from the obstacle's
//! distance derivatives (κw(b′ n, b″ n nᵀ + b′ ∂n/∂p)). The step cap stops every site short of
//! its obstacle (a tenth of its gap is kept), and the line search never accepts the infinite
//! energy of a penetration, so no gap ever closes: contacts rest within the activation
//! distance ĝ of the surface, which is the stated position tolerance of the contact.
//!
//! Dry Coulomb friction ([`friction`](super::friction)) adds, per contact, a tangential anchor
//! while it sticks or the kinetic force while it slides; [`ContactProblem::update_friction`]
//! is the active-set step between solves. Each contact's normal and friction force is
//! reported ([`ContactProblem::contact_forces`]).

use std::cell::RefCell;
use std::sync::Arc;

use nalgebra::{Matrix3, Vector3};

use crate::assembly::{Assembler, TermGroup};
use crate::error::{require_non_negative, require_positive};
use crate::linalg::{AdaptiveMatrix, SparseSymmetricMatrix};
use crate::solver::{EquilibriumProblem, MassMetric};
use crate::ModelError;

use super::barrier::barrier;
use super::broad_phase::{overlapping_pairs, Aabb, SweepBuffers};
use super::friction::{Friction, FrictionUpdate};
use super::obstacle::Obstacle;
use super::radii::{member_radius, site_radii, validate_member_radii};
use super::segment_distance::{
    closest_parameters, edge_edge_mollifier, point_segment_distance,
    point_segment_distance_squared, segment_distance, segment_distance_squared,
};
use super::sites::{ContactSite, ContactSites, SiteDof};
use crate::shell::dual::Dual2;

/// One active self-contact (see [`ContactProblem::self_contact_forces`]): the first site of
/// each side as (member, vertex), the gap (m) and the barrier's force magnitude (N).
pub type SelfContactForce = ((usize, usize), (usize, usize), f64, f64);
/// The term group of the contact energy (the top bit, which no model uses).
pub const CONTACT: TermGroup = TermGroup {
    bit: 31,
    name: "contact",
};

/// The term group of the friction terms (anchors of sticking contacts, forces of sliding ones).
pub const FRICTION: TermGroup = TermGroup {
    bit: 30,
    name: "friction",
};

/// Fraction of a site's gap that a step must leave open.
const KEEP_GAP: f64 = 0.1;

/// How contacts act.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactParams {
    /// Radius (m) of the cable's section: the centerline keeps this distance from surfaces.
    /// The radius of every member that [`ContactProblem::with_radii`] gives none.
    pub radius: f64,
    /// Activation distance ĝ (m, > 0): a site within this gap of a surface is in contact, and
    /// at equilibrium every contact rests within it (the position tolerance of contacts).
    pub activation: f64,
    /// Barrier stiffness κ (N/m², > 0): a line load q (N/m) pressing a cable on a surface
    /// rests it at the gap where −κ b′(g) = q (about ĝ/2 for κ = q/(1.19 ĝ); see
    /// [`Self::for_line_load`]). Larger loads only close the gap further, never through.
    pub stiffness: f64,
    /// Stiffness k_t (N/m², > 0) per unit length of the anchor that holds a sticking contact
    /// tangentially: at the friction limit μ q it deflects by μ q / k_t (a bounded elastic
    /// deflection, never a creep).
    pub stick_stiffness: f64,
    /// Contact of the structure's centerline edges with each other (self-contact of a coil,
    /// cable against cable): segment–segment distances against the sum of the two edges'
    /// radii, with the same barrier. Edges closer along the same member than π r (which no
    /// bend of a cable of radius r brings into contact) are not paired.
    pub self_contact: bool,
}

impl ContactParams {
    /// Parameters under which a line load `line_load` (N/m) rests a cable of radius `radius`
    /// (m) at half the activation distance `activation` (m).
    pub fn for_line_load(radius: f64, activation: f64, line_load: f64) -> Self {
        // −b′(ĝ/2) = ĝ (1/2 + ln 2).
        let slope = activation * (0.5 + std::f64::consts::LN_2);
        Self {
            radius,
            activation,
            stiffness: line_load / slope,
            // The tangential deflection at the friction limit, μ q / k_t, stays below
            // μ · 10⁻⁴ ĝ: far below the normal position tolerance.
            stick_stiffness: line_load / (1e-4 * activation),
            self_contact: false,
        }
    }

    /// Checks every field; errors name it and its valid range.
    pub fn validate(&self) -> Result<(), ModelError> {
        require_non_negative("radius", self.radius)?;
        require_positive("activation", self.activation)?;
        require_positive("stiffness", self.stiffness)?;
        require_positive("stick_stiffness", self.stick_stiffness)?;
        Ok(())
    }
}

/// The force one obstacle applies to one site.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactForce {
    /// Index of the site in [`ContactProblem::sites`].
    pub site: usize,
    /// Index of the obstacle.
    pub obstacle: usize,
    /// Gap g = distance − radius (m), in (0, ĝ).
    pub gap: f64,
    /// Outward unit normal of the surface at the contact.
    pub normal: Vector3<f64>,
    /// Normal force on the structure (N), along `normal`.
    pub force: Vector3<f64>,
    /// Friction force on the structure (N), tangential: the anchor's pull while sticking,
    /// the kinetic force while sliding, zero on a frictionless surface.
    pub friction: Vector3<f64>,
    /// True while the contact sticks.
    pub sticking: bool,
}

/// One side of a [`SegmentContact`]: an edge of the centerline, or a vertex of it.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentSide {
    /// Member (0 for a single rod).
    pub member: usize,
    /// The edge (the member's own numbering), for an edge side.
    pub edge: Option<usize>,
    /// The vertex (the member's own numbering), for a vertex side.
    pub vertex: Option<usize>,
    /// The closest point of this side to the other (m).
    pub point: Vector3<f64>,
    /// The contact's force (N) on each site of the side (index in
    /// [`ContactProblem::sites`]): two sites for an edge, one for a vertex.
    pub forces: Vec<(usize, Vector3<f64>)>,
}

impl SegmentSide {
    /// The resultant force (N) the other side applies to this one.
    pub fn force(&self) -> Vector3<f64> {
        self.forces.iter().map(|(_, f)| f).sum()
    }
}

/// One active self-contact or cable–cable contact: two edges of the structure's centerline
/// (or a vertex and an edge) closer than the activation distance, pushed apart by the
/// barrier. The forces are minus the gradient of the pair's energy (mollifier included), so
/// the two sides' resultants are equal and opposite and each site's share is the one the
/// solve balanced.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentContact {
    /// First side: an edge (edge–edge pair) or a vertex (vertex–edge pair).
    pub a: SegmentSide,
    /// Second side: always an edge.
    pub b: SegmentSide,
    /// Gap (m) between the surfaces: distance of the closest points minus the sum of the two
    /// sides' radii.
    pub gap: f64,
}

/// `model` in contact with `obstacles` (see the module docs).
#[derive(Debug)]
pub struct ContactProblem<'m, P: ContactSites> {
    model: &'m P,
    obstacles: Vec<Arc<dyn Obstacle>>,
    params: ContactParams,
    sites: Vec<ContactSite>,
    groups: Vec<TermGroup>,
    /// Per (site, obstacle) pair, at index site·n_obstacles + obstacle: what friction does
    /// there. Changed between solves only ([`Self::update_friction`]), through a shared
    /// reference so that a time stepper holding the problem can update it.
    friction: RefCell<Vec<Friction>>,
    /// Centerline edges for self-contact (empty without it).
    edges: Vec<EdgeSites>,
    /// Edge pairs that never interact (neighbours along a member, or sharing a site), sorted.
    excluded: Vec<(usize, usize)>,
    /// Per site: its chain and rest arc length (m) along it (see [`ContactProblem::with_chains`]).
    site_arcs: Vec<(usize, f64)>,
    /// Per site: its contact radius (m), the distance its centerline point keeps from surfaces.
    site_radius: Vec<f64>,
    scratch: RefCell<SelfScratch>,
}

/// An edge of the structure as two sites.
#[derive(Clone, Copy, Debug)]
struct EdgeSites {
    sites: [usize; 2],
    /// Rest length (m).
    length: f64,
    /// Member, and its index among the member's edges.
    member: usize,
    index: usize,
    /// Chain, and rest arc length (m) of its ends along the chain.
    chain: usize,
    arc: [f64; 2],
    /// Contact radius (m): its member's.
    radius: f64,
}

/// One self-contact primitive with its coordinates.
enum Primitive {
    /// Edges `a` and `b`: a₀, a₁, b₀, b₁.
    EdgeEdge { a: usize, b: usize, x: [f64; 12] },
    /// Site `v` against edge `e`: p, e₀, e₁.
    VertexEdge { v: usize, e: usize, x: [f64; 9] },
}

impl Primitive {
    /// Surface gap (m): distance minus `clearance` (the two sides' radii, [`Self::clearance`]).
    fn gap(&self, clearance: f64) -> f64 {
        let d2 = match self {
            Primitive::EdgeEdge { x, .. } => segment_distance_squared(x).v,
            Primitive::VertexEdge { x, .. } => point_segment_distance_squared(x).v,
        };
        d2.sqrt() - clearance
    }

    /// The distance (m) the two sides' centerlines keep: the sum of their radii.
    fn clearance<P: ContactSites>(&self, problem: &ContactProblem<'_, P>) -> f64 {
        match *self {
            Primitive::EdgeEdge { a, b, .. } => problem.edges[a].radius + problem.edges[b].radius,
            Primitive::VertexEdge { v, e, .. } => problem.site_radius[v] + problem.edges[e].radius,
        }
    }

    /// The first site of each side.
    fn first_sites<P: ContactSites>(&self, problem: &ContactProblem<'_, P>) -> (usize, usize) {
        match *self {
            Primitive::EdgeEdge { a, b, .. } => {
                (problem.edges[a].sites[0], problem.edges[b].sites[0])
            }
            Primitive::VertexEdge { v, e, .. } => (v, problem.edges[e].sites[0]),
        }
    }

    /// An edge of each side (for messages): the vertex's own first edge for a vertex.
    fn edges<P: ContactSites>(&self, problem: &ContactProblem<'_, P>) -> (usize, usize) {
        match *self {
            Primitive::EdgeEdge { a, b, .. } => (a, b),
            Primitive::VertexEdge { v, e, .. } => (
                problem
                    .edges
                    .iter()
                    .position(|edge| edge.sites.contains(&v))
                    .unwrap_or(e),
                e,
            ),
        }
    }
}

/// Buffers of the self-contact broad phase (no allocation per assembly once grown).
#[derive(Clone, Debug, Default)]
struct SelfScratch {
    boxes: Vec<Aabb>,
    sweep: SweepBuffers,
    pairs: Vec<(usize, usize)>,
    vertex_edges: Vec<(usize, usize)>,
}

impl<'m, P: ContactSites> ContactProblem<'m, P> {
    /// Per site, the fraction of its blended first-guess move (from `start` to `guessed`)
    /// that it keeps: 0 at a site in contact at `start` (within the activation distance of
    /// an obstacle) that the blend pushes into it (the cable rests there, held as at a
    /// support; a blend that lifts it off is kept), 1 at the supports, linear in rest station
    /// between them along each line ([`ContactSites::site_stations`]: a member, a strip's
    /// length) and constant past the outermost. All 1 when no contact is pushed.
    fn guess_fractions(&self, start: &P::State, guessed: &P::State) -> Vec<f64> {
        use crate::assembly::FIXED;
        let held: Vec<bool> = (self.sites.iter().zip(&self.site_radius))
            .map(|(site, &radius)| {
                let p = self.model.site_position(start, site);
                let dp = self.model.site_position(guessed, site) - p;
                site.dofs.iter().any(|d| d.dof != FIXED)
                    && self.obstacles.iter().any(|o| {
                        let s = o.surface(&p);
                        s.distance - radius <= self.params.activation && dp.dot(&s.normal) < 0.0
                    })
            })
            .collect();
        let mut fraction = vec![1.0; self.sites.len()];
        if !held.contains(&true) {
            return fraction;
        }
        // The sites ordered along their lines (members, or a strip's length).
        let mut along: Vec<(usize, f64, usize)> = (self.model.site_stations(&self.sites))
            .into_iter()
            .enumerate()
            .filter_map(|(k, at)| at.map(|(line, s)| (line, s, k)))
            .collect();
        along.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        // Anchors: held sites (0) and supported ones (every coordinate held: 1).
        let anchor = |k: usize| -> Option<f64> {
            if held[k] {
                Some(0.0)
            } else if self.sites[k].dofs.iter().all(|d| d.dof == FIXED) {
                Some(1.0)
            } else {
                None
            }
        };
        for line in along.chunk_by(|a, b| a.0 == b.0) {
            let anchors: Vec<(f64, f64)> = line
                .iter()
                .filter_map(|&(_, s, k)| anchor(k).map(|f| (s, f)))
                .collect();
            for &(_, s, k) in line {
                if let Some(f) = anchor(k) {
                    fraction[k] = f;
                    continue;
                }
                let next = anchors.partition_point(|a| a.0 < s);
                fraction[k] = match (next.checked_sub(1).map(|i| anchors[i]), anchors.get(next)) {
                    (Some((s0, f0)), Some(&(s1, f1))) => f0 + (f1 - f0) * (s - s0) / (s1 - s0),
                    (Some((_, f)), None) | (None, Some(&(_, f))) => f,
                    (None, None) => 1.0,
                };
            }
        }
        fraction
    }

    /// The largest fraction (≤ `alpha`, the model's own cap) of the step `dx` along which
    /// every site keeps its clearance from every obstacle and, with self-contact, every pair of
    /// segments theirs (a fraction [`KEEP_GAP`] of each gap stays open).
    fn contact_step_limit(&self, state: &P::State, dx: &[f64], mut alpha: f64) -> f64 {
        for (site, &radius) in self.sites.iter().zip(&self.site_radius) {
            let mut dp = Vector3::zeros();
            for (c, d) in site.dofs.iter().enumerate() {
                if d.dof != crate::assembly::FIXED {
                    dp[c] = d.coef * dx[d.dof];
                }
            }
            if dp == Vector3::zeros() {
                continue;
            }
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                let gap = obstacle.surface(&p).distance - radius;
                let clearance = radius + KEEP_GAP * gap.max(0.0);
                alpha = alpha.min(obstacle.time_of_impact(&p, &(dp * alpha), clearance) * alpha);
            }
        }
        if !self.edges.is_empty() {
            // Additive conservative advancement (Li et al. 2021): two segments whose end
            // points move by at most Δ_a and Δ_b come closer by at most Δ_a + Δ_b, so the
            // motion can be advanced by (1 − KEEP_GAP)·gap / (Δ_a + Δ_b) and the gap measured
            // again there. Repeating it lets a pressed contact slide along the other segment
            // (its gap stays, its motion is mostly tangential) where one such bound would cap
            // the step at gap / motion. The gap stays above a tenth of a tenth of its start
            // along the whole capped motion.
            let moved = |site: usize| -> Vector3<f64> {
                let mut dp = Vector3::zeros();
                for (c, d) in self.sites[site].dofs.iter().enumerate() {
                    if d.dof != crate::assembly::FIXED {
                        dp[c] = d.coef * dx[d.dof];
                    }
                }
                dp
            };
            let largest = (0..self.sites.len())
                .map(|k| moved(k).norm())
                .fold(0.0, f64::max);
            self.for_each_primitive(state, 2.0 * alpha * largest, |prim| {
                let clearance = prim.clearance(self);
                let t = match prim {
                    Primitive::EdgeEdge { a, b, x } => {
                        let sites = [self.edges[*a].sites, self.edges[*b].sites].concat();
                        let dp: [f64; 12] =
                            std::array::from_fn(|i| alpha * moved(sites[i / 3])[i % 3]);
                        additive_ccd(x, &dp, 2, |y| segment_distance(y) - clearance)
                    }
                    Primitive::VertexEdge { v, e, x } => {
                        let [e0, e1] = self.edges[*e].sites;
                        let sites = [*v, e0, e1];
                        let dp: [f64; 9] =
                            std::array::from_fn(|i| alpha * moved(sites[i / 3])[i % 3]);
                        additive_ccd(x, &dp, 1, |y| point_segment_distance(y) - clearance)
                    }
                };
                alpha *= t;
            });
        }
        alpha
    }

    /// `model` with `obstacles`, every member of radius `params.radius`. Errors: invalid
    /// parameters, a model that already uses the contact group's bit, or a site of `start`
    /// that is not outside every obstacle by more than its radius (the cable would start
    /// inside; the field names the obstacle).
    pub fn new(
        model: &'m P,
        obstacles: Vec<Arc<dyn Obstacle>>,
        params: ContactParams,
        start: &P::State,
    ) -> Result<Self, ModelError> {
        Self::with_chains(model, obstacles, params, start, &[])
    }

    /// As [`Self::new`], with the members laid along chains for self-contact: `chains[m]` =
    /// (chain, arc length (m) of member m's first vertex along it). Edges closer than π r + ĝ
    /// along one chain are not paired. A chain is a cable cut into several members (a scene's
    /// rod split at interior clamps: the two members meeting at the clamp hold one point
    /// twice, and must not be seen as touching there). Members missing from `chains` (all,
    /// for [`Self::new`]) are chains of their own.
    pub fn with_chains(
        model: &'m P,
        obstacles: Vec<Arc<dyn Obstacle>>,
        params: ContactParams,
        start: &P::State,
        chains: &[(usize, f64)],
    ) -> Result<Self, ModelError> {
        Self::with_radii(model, obstacles, params, start, chains, &[])
    }

    /// As [`Self::with_chains`], with a contact radius per member: `radii[m]` (m, finite and
    /// ≥ 0; `params.radius` for members missing from it). Against obstacles each site keeps
    /// its own member's radius (at a joint the largest of the members meeting there); two
    /// edges in self-contact keep the sum of theirs apart, and are not paired closer along
    /// one chain than π r + ĝ with r the larger. Errors as [`Self::new`], and `radii[m]`.
    pub fn with_radii(
        model: &'m P,
        obstacles: Vec<Arc<dyn Obstacle>>,
        params: ContactParams,
        start: &P::State,
        chains: &[(usize, f64)],
        radii: &[f64],
    ) -> Result<Self, ModelError> {
        params.validate()?;
        validate_member_radii(radii)?;
        if model.term_groups().iter().any(|g| g.bit == CONTACT.bit) {
            return Err(ModelError::structure(
                "obstacles",
                "the model already uses the contact term group's bit",
            ));
        }
        let sites = model.contact_sites();
        let site_radius = site_radii(model, &sites, radii, params.radius);
        for (o, obstacle) in obstacles.iter().enumerate() {
            for (site, &radius) in sites.iter().zip(&site_radius) {
                let gap = obstacle.surface(&model.site_position(start, site)).distance - radius;
                if !(gap > 0.0) {
                    return Err(ModelError::structure(
                        format!("obstacles[{o}]"),
                        format!(
                            "vertex {} of member {} starts inside the obstacle (gap {gap:.3e} m with radius {radius} m): move the obstacle or the cable",
                            site.vertex, site.member
                        ),
                    ));
                }
            }
        }
        if model.term_groups().iter().any(|g| g.bit == FRICTION.bit) {
            return Err(ModelError::structure(
                "obstacles",
                "the model already uses the friction term group's bit",
            ));
        }
        let mut groups = model.term_groups().to_vec();
        groups.push(CONTACT);
        groups.push(FRICTION);
        let pairs = sites.len() * obstacles.len();
        let (edges, excluded, site_arcs) = if params.self_contact {
            self_contact_edges(model, &sites, &params, chains, radii)
        } else {
            (Vec::new(), Vec::new(), Vec::new())
        };
        let me = Self {
            model,
            obstacles,
            params,
            sites,
            groups,
            friction: RefCell::new(vec![Friction::Free; pairs]),
            edges,
            excluded,
            site_arcs,
            site_radius,
            scratch: RefCell::new(SelfScratch::default()),
        };
        let mut worst: Option<(usize, usize, f64, f64)> = None;
        me.for_each_primitive(start, 0.0, |prim| {
            let clearance = prim.clearance(&me);
            let gap = prim.gap(clearance);
            let (a, b) = prim.edges(&me);
            if !(gap > 0.0) && worst.is_none_or(|w| gap < w.2) {
                worst = Some((a, b, gap, clearance));
            }
        });
        if let Some((a, b, gap, clearance)) = worst {
            let at = |e: usize| {
                let s = &me.sites[me.edges[e].sites[0]];
                format!("edge at vertex {} of member {}", s.vertex, s.member)
            };
            return Err(ModelError::structure(
                "self_contact",
                format!(
                    "the cable starts intersecting itself or another cable: {} and {} are {:.3e} m apart, less than the sum of their radii {clearance} m",
                    at(a),
                    at(b),
                    gap + clearance,
                ),
            ));
        }
        Ok(me)
    }

    /// The twelve endpoint coordinates of edges `a` and `b` in `state`.
    fn edge_pair_coordinates(&self, state: &P::State, a: usize, b: usize) -> [f64; 12] {
        let mut x = [0.0; 12];
        for (k, site) in [
            self.edges[a].sites[0],
            self.edges[a].sites[1],
            self.edges[b].sites[0],
            self.edges[b].sites[1],
        ]
        .into_iter()
        .enumerate()
        {
            let p = self.model.site_position(state, &self.sites[site]);
            x[3 * k..3 * k + 3].copy_from_slice(p.as_slice());
        }
        x
    }

    /// Calls `f` with every contact primitive — edge–edge and vertex–edge pairs — that may be
    /// within the activation distance in `state` (broad phase on edge boxes grown by `grow`
    /// m more), each once, in a deterministic order.
    fn for_each_primitive(&self, state: &P::State, grow: f64, mut f: impl FnMut(&Primitive)) {
        if self.edges.is_empty() {
            return;
        }
        let mut scratch = self.scratch.borrow_mut();
        let SelfScratch {
            boxes,
            sweep,
            pairs,
            vertex_edges,
        } = &mut *scratch;
        boxes.clear();
        for e in &self.edges {
            // Two boxes overlap when their edges may be closer than r_a + r_b + ĝ (+ 2 grow).
            let pad = Vector3::repeat(e.radius + 0.5 * self.params.activation + grow);
            let p = self.model.site_position(state, &self.sites[e.sites[0]]);
            let q = self.model.site_position(state, &self.sites[e.sites[1]]);
            boxes.push((p.inf(&q) - pad, p.sup(&q) + pad));
        }
        overlapping_pairs(boxes, sweep, pairs);
        vertex_edges.clear();
        for &(a, b) in pairs.iter() {
            for (edge, other) in [(a, b), (b, a)] {
                for v in self.edges[other].sites {
                    if self.vertex_edge_interacts(v, edge) {
                        vertex_edges.push((v, edge));
                    }
                }
            }
            if self.excluded.binary_search(&(a, b)).is_ok() {
                continue;
            }
            f(&Primitive::EdgeEdge {
                a,
                b,
                x: self.edge_pair_coordinates(state, a, b),
            });
        }
        vertex_edges.sort_unstable();
        vertex_edges.dedup();
        for &(v, e) in vertex_edges.iter() {
            let mut x = [0.0; 9];
            for (k, site) in [v, self.edges[e].sites[0], self.edges[e].sites[1]]
                .into_iter()
                .enumerate()
            {
                let p = self.model.site_position(state, &self.sites[site]);
                x[3 * k..3 * k + 3].copy_from_slice(p.as_slice());
            }
            f(&Primitive::VertexEdge { v, e, x });
        }
    }

    /// True if site `v` and edge `e` can touch: not an end of it, and not closer to it along
    /// their chain than π r + ĝ (r the larger of their radii).
    fn vertex_edge_interacts(&self, v: usize, e: usize) -> bool {
        let edge = &self.edges[e];
        if edge.sites.contains(&v) {
            return false;
        }
        let (chain, arc) = self.site_arcs[v];
        !(chain == edge.chain
            && (arc - arc.clamp(edge.arc[0], edge.arc[1])).abs()
                < std::f64::consts::PI * self.site_radius[v].max(edge.radius)
                    + self.params.activation)
    }

    /// The barrier weight of a primitive: half the shorter rest length involved (m).
    fn primitive_length(&self, prim: &Primitive) -> f64 {
        match *prim {
            Primitive::EdgeEdge { a, b, .. } => {
                0.5 * self.edges[a].length.min(self.edges[b].length)
            }
            Primitive::VertexEdge { v, e, .. } => {
                0.5 * self.sites[v].length.min(self.edges[e].length)
            }
        }
    }

    /// Energy (J) of a primitive with its derivatives in its own coordinates, if active;
    /// `clearance` (m) is the distance its sides keep ([`Primitive::clearance`]).
    fn primitive_energy<const N: usize>(
        &self,
        distance_squared: Dual2<N>,
        mollifier: Option<Dual2<N>>,
        length: f64,
        clearance: f64,
    ) -> Option<Dual2<N>> {
        let d = distance_squared.v.sqrt();
        let gap = d - clearance;
        if gap >= self.params.activation {
            return None;
        }
        let (b, db, ddb) = barrier(gap, self.params.activation);
        // d = √(d²): ∇d = ∇d²/(2d), ∇²d = ∇²d²/(2d) − ∇d² ∇d²ᵀ/(4d³).
        let grad_d = distance_squared.g / (2.0 * d);
        let hess_d = distance_squared.h / (2.0 * d)
            - distance_squared.g * distance_squared.g.transpose() / (4.0 * d * d * d);
        let energy = Dual2 {
            v: b,
            g: grad_d * db,
            h: grad_d * grad_d.transpose() * ddb + hess_d * db,
            affine: false,
            active: distance_squared.active,
            first_order: distance_squared.first_order,
        };
        let energy = match mollifier {
            Some(m) if m.v < 1.0 => m * energy,
            _ => energy,
        };
        Some(energy.scale(self.params.stiffness * length))
    }

    /// The remap of a primitive's coordinates (three per site, in order) to the free DOFs.
    fn primitive_remap<const N: usize>(&self, sites: &[usize]) -> [SiteDof; N] {
        let mut remap = [SiteDof {
            dof: crate::assembly::FIXED,
            coef: 0.0,
        }; N];
        for (k, &site) in sites.iter().enumerate() {
            remap[3 * k..3 * k + 3].copy_from_slice(&self.sites[site].dofs);
        }
        remap
    }

    /// The edge–edge mollifier's scale ε_x (m⁴) of edges `a`, `b`: 10⁻³ l_a² l_b² (at rest).
    fn mollifier_scale(&self, a: usize, b: usize) -> f64 {
        1e-3 * (self.edges[a].length * self.edges[b].length).powi(2)
    }

    /// Energy (J) of one primitive at its coordinates (0 when inactive).
    fn primitive_value(&self, prim: &Primitive) -> f64 {
        let length = self.primitive_length(prim);
        let clearance = prim.clearance(self);
        match prim {
            Primitive::EdgeEdge { a, b, x } => self
                .primitive_energy(
                    segment_distance_squared(x),
                    Some(edge_edge_mollifier(x, self.mollifier_scale(*a, *b))),
                    length,
                    clearance,
                )
                .map_or(0.0, |e| e.v),
            Primitive::VertexEdge { x, .. } => self
                .primitive_energy(point_segment_distance_squared(x), None, length, clearance)
                .map_or(0.0, |e| e.v),
        }
    }

    /// The friction state of the contact of site `site` with obstacle `obstacle`.
    pub fn friction(&self, site: usize, obstacle: usize) -> Friction {
        self.friction.borrow()[site * self.obstacles.len() + obstacle]
    }

    /// Normal gap (m), outward normal and normal force (N, ≥ 0) of site `k` at `p` against
    /// obstacle `o`, with `length` (m) the centerline the site stands for.
    fn normal_contact(
        &self,
        k: usize,
        p: &Vector3<f64>,
        o: usize,
        length: f64,
    ) -> (f64, Vector3<f64>, f64) {
        let s = self.obstacles[o].surface(p);
        let gap = s.distance - self.site_radius[k];
        let force = if gap < self.params.activation {
            -self.params.stiffness * length * barrier(gap, self.params.activation).1
        } else {
            0.0
        };
        (gap, s.normal, force)
    }

    /// The active-set step of Coulomb friction at `state`, an equilibrium (or time step)
    /// solved with the current friction set; `previous` is the state before that solve (the
    /// state to solve again from; the update itself needs only `state`). A contact on a rough
    /// surface starts to stick where it is; a sticking contact whose anchor pulls harder than
    /// μ f_n slides, its anchor becoming the slide's origin (its force the pull capped at
    /// μ f_n); a sliding contact whose slip from its origin falls back within the smoothing
    /// slip ε (it stopped or reversed) sticks again at its origin; a contact that opened is
    /// freed. Sliding magnitudes are refreshed to μ times the current normal force (origins
    /// kept). When the update says [`changed`](FrictionUpdate::changed), solve again from
    /// `previous`.
    pub fn update_friction(&self, state: &P::State, previous: Option<&P::State>) -> FrictionUpdate {
        self.update_friction_keeping(state, previous, &[])
    }

    /// As [`Self::update_friction`], except that a sliding contact flagged in `keep_sliding`
    /// (index as in [`Self::friction_state`]; missing entries are false) keeps sliding —
    /// against μ times its current normal force — even if its slip fell back within ε:
    /// within one time step, a contact that slipped stays sliding
    /// ([`step_with_friction`](super::step_with_friction)).
    pub fn update_friction_keeping(
        &self,
        state: &P::State,
        _previous: Option<&P::State>,
        keep_sliding: &[bool],
    ) -> FrictionUpdate {
        let mut update = FrictionUpdate::default();
        let mut friction = self.friction.borrow_mut();
        let n_obstacles = self.obstacles.len();
        for (k, site) in self.sites.iter().enumerate() {
            let x = self.model.site_position(state, site);
            for o in 0..n_obstacles {
                let slot = &mut friction[k * n_obstacles + o];
                let mu = self.obstacles[o].friction();
                let (_, normal, f_n) = self.normal_contact(k, &x, o, site.length);
                if f_n <= 0.0 || mu == 0.0 {
                    if *slot != Friction::Free {
                        update.released += 1;
                        *slot = Friction::Free;
                    }
                    continue;
                }
                let limit = mu * f_n;
                *slot = match *slot {
                    Friction::Free => {
                        update.stuck += 1;
                        Friction::Stick { anchor: x, normal }
                    }
                    stick @ Friction::Stick { anchor, normal } => {
                        let pull = stick.force(&x, site.length, self.params.stick_stiffness);
                        if pull.norm() > limit {
                            // The anchor's pull, capped to the cone: the force at x keeps
                            // its direction and is cut to μ f_n (no jump).
                            update.slipped += 1;
                            Friction::Slide {
                                origin: anchor,
                                normal,
                                magnitude: limit,
                            }
                        } else {
                            stick
                        }
                    }
                    Friction::Slide { origin, normal, .. } => {
                        let slide = Friction::Slide {
                            origin,
                            normal,
                            magnitude: limit,
                        };
                        let eps =
                            Friction::smoothing(limit, site.length, self.params.stick_stiffness);
                        let keep = keep_sliding.get(k * n_obstacles + o) == Some(&true);
                        if slide.slip(&x).norm() < eps && !keep {
                            // The slip from the origin fell back within the anchor's
                            // deflection at the limit: the contact stopped (or reversed), and
                            // sticks at the origin, where its force stays the same.
                            update.stuck += 1;
                            Friction::Stick {
                                anchor: origin,
                                normal,
                            }
                        } else {
                            slide
                        }
                    }
                };
            }
        }
        update
    }

    /// Where a piece of a load path or a time step starts at `state`: every sliding contact's
    /// origin is dragged to ε behind it along its slip ([`Friction::restarted`]), so that its
    /// force keeps its value at `state` and opposes the slip of the piece or step (as lagged
    /// friction lags to the step's start).
    pub fn restart_slides(&self, state: &P::State) {
        let mut friction = self.friction.borrow_mut();
        let n_obstacles = self.obstacles.len();
        for (k, site) in self.sites.iter().enumerate() {
            let x = self.model.site_position(state, site);
            for o in 0..n_obstacles {
                let slot = &mut friction[k * n_obstacles + o];
                if matches!(slot, Friction::Slide { .. }) {
                    let normal = self.obstacles[o].surface(&x).normal;
                    *slot = slot.restarted(&x, &normal, site.length, self.params.stick_stiffness);
                }
            }
        }
    }

    /// The friction state of every (site, obstacle) contact, at index site·n_obstacles +
    /// obstacle: to keep it across problems built for successive solves of one model.
    pub fn friction_state(&self) -> Vec<Friction> {
        self.friction.borrow().clone()
    }

    /// Replaces the friction state (see [`Self::friction_state`]). A state of another length
    /// (another model or obstacle set) is ignored and every contact is left free.
    pub fn set_friction_state(&self, state: &[Friction]) {
        let mut f = self.friction.borrow_mut();
        if state.len() == f.len() {
            f.copy_from_slice(state);
        }
    }

    /// The obstacles.
    pub fn obstacles(&self) -> &[Arc<dyn Obstacle>] {
        &self.obstacles
    }

    /// The model.
    pub fn model(&self) -> &P {
        self.model
    }

    /// The contact sites.
    pub fn sites(&self) -> &[ContactSite] {
        &self.sites
    }

    /// The parameters.
    pub fn params(&self) -> &ContactParams {
        &self.params
    }

    /// The contact radius (m) of site `site` (index in [`Self::sites`]): the distance its
    /// centerline point keeps from obstacles (see [`Self::with_radii`]).
    pub fn site_radius(&self, site: usize) -> f64 {
        self.site_radius[site]
    }

    /// Every active contact (gap below the activation distance) of `state` with its force.
    pub fn contact_forces(&self, state: &P::State) -> Vec<ContactForce> {
        let mut out = Vec::new();
        for (k, site) in self.sites.iter().enumerate() {
            let p = self.model.site_position(state, site);
            for (o, obstacle) in self.obstacles.iter().enumerate() {
                let s = obstacle.surface(&p);
                let gap = s.distance - self.site_radius[k];
                if gap < self.params.activation {
                    let (_, slope, _) = barrier(gap, self.params.activation);
                    let friction = self.friction(k, o);
                    out.push(ContactForce {
                        site: k,
                        obstacle: o,
                        gap,
                        normal: s.normal,
                        force: s.normal * (-self.params.stiffness * site.length * slope),
                        friction: friction.force(&p, site.length, self.params.stick_stiffness),
                        sticking: matches!(friction, Friction::Stick { .. }),
                    });
                }
            }
        }
        out
    }

    /// Smallest gap (m) of any site to any obstacle in `state` (negative: penetration).
    pub fn min_gap(&self, state: &P::State) -> f64 {
        let mut g = f64::INFINITY;
        for (site, &radius) in self.sites.iter().zip(&self.site_radius) {
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                g = g.min(obstacle.surface(&p).distance - radius);
            }
        }
        g
    }

    /// Smallest gap (m) between the surfaces of two non-neighbouring edges in `state` (∞
    /// without self-contact or when no pair is near).
    pub fn min_self_gap(&self, state: &P::State) -> f64 {
        let mut g = f64::INFINITY;
        self.for_each_primitive(state, 0.0, |prim| {
            g = g.min(prim.gap(prim.clearance(self)));
        });
        g
    }

    /// Every active self-contact of `state`: the first site of each side as (member,
    /// vertex), the gap (m) and the barrier's force magnitude (N) pushing them apart (for an
    /// edge–edge pair, before the parallel-edge mollifier).
    pub fn self_contact_forces(&self, state: &P::State) -> Vec<SelfContactForce> {
        let mut out = Vec::new();
        self.for_each_primitive(state, 0.0, |prim| {
            let gap = prim.gap(prim.clearance(self));
            if gap < self.params.activation {
                let slope = barrier(gap, self.params.activation).1;
                let force = -self.params.stiffness * self.primitive_length(prim) * slope;
                let (sa, sb) = prim.first_sites(self);
                let at = |k: usize| (self.sites[k].member, self.sites[k].vertex);
                out.push((at(sa), at(sb), gap, force));
            }
        });
        out
    }

    /// Every active self-contact and cable–cable contact of `state` with its forces (empty
    /// without self-contact; see [`SegmentContact`]).
    pub fn segment_contacts(&self, state: &P::State) -> Vec<SegmentContact> {
        let mut out = Vec::new();
        let point = |x: &[f64], k: usize| Vector3::new(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
        self.for_each_primitive(state, 0.0, |prim| {
            let clearance = prim.clearance(self);
            let gap = prim.gap(clearance);
            if gap >= self.params.activation {
                return;
            }
            let length = self.primitive_length(prim);
            let side = |member: usize,
                        edge: Option<usize>,
                        vertex: Option<usize>,
                        point: Vector3<f64>,
                        sites: &[usize],
                        grad: &[f64],
                        first: usize| SegmentSide {
                member,
                edge,
                vertex,
                point,
                forces: sites
                    .iter()
                    .enumerate()
                    .map(|(k, &s)| (s, -point3(grad, first + k)))
                    .collect(),
            };
            match prim {
                Primitive::EdgeEdge { a, b, x } => {
                    let m = edge_edge_mollifier(x, self.mollifier_scale(*a, *b));
                    let Some(e) = self.primitive_energy(
                        segment_distance_squared(x),
                        Some(m),
                        length,
                        clearance,
                    ) else {
                        return;
                    };
                    let (s, t) = closest_parameters(x);
                    let (ea, eb) = (&self.edges[*a], &self.edges[*b]);
                    let pa = point(x, 0) + (point(x, 1) - point(x, 0)) * s;
                    let pb = point(x, 2) + (point(x, 3) - point(x, 2)) * t;
                    out.push(SegmentContact {
                        a: side(
                            ea.member,
                            Some(ea.index),
                            None,
                            pa,
                            &ea.sites,
                            e.g.as_slice(),
                            0,
                        ),
                        b: side(
                            eb.member,
                            Some(eb.index),
                            None,
                            pb,
                            &eb.sites,
                            e.g.as_slice(),
                            2,
                        ),
                        gap,
                    });
                }
                Primitive::VertexEdge { v, e: edge, x } => {
                    let Some(e) = self.primitive_energy(
                        point_segment_distance_squared(x),
                        None,
                        length,
                        clearance,
                    ) else {
                        return;
                    };
                    let (p, q0, q1) = (point(x, 0), point(x, 1), point(x, 2));
                    let d = q1 - q0;
                    let t = ((p - q0).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                    let site = &self.sites[*v];
                    let eb = &self.edges[*edge];
                    out.push(SegmentContact {
                        a: side(
                            site.member,
                            None,
                            Some(site.vertex),
                            p,
                            &[*v],
                            e.g.as_slice(),
                            0,
                        ),
                        b: side(
                            eb.member,
                            Some(eb.index),
                            None,
                            q0 + d * t,
                            &eb.sites,
                            e.g.as_slice(),
                            1,
                        ),
                        gap,
                    });
                }
            }
        });
        out
    }

    /// The contact and friction energy (J) of `state`.
    fn contact_energy(&self, state: &P::State) -> f64 {
        let mut e = 0.0;
        let friction = self.friction.borrow();
        for (k, site) in self.sites.iter().enumerate() {
            let p = self.model.site_position(state, site);
            for (o, obstacle) in self.obstacles.iter().enumerate() {
                let gap = obstacle.surface(&p).distance - self.site_radius[k];
                if gap < self.params.activation {
                    e += self.params.stiffness
                        * site.length
                        * barrier(gap, self.params.activation).0;
                }
                let f = friction[k * self.obstacles.len() + o];
                if let Some((energy, _, _)) =
                    f.derivatives(&p, site.length, self.params.stick_stiffness)
                {
                    e += energy;
                }
            }
        }
        self.for_each_primitive(state, 0.0, |prim| e += self.primitive_value(prim));
        e
    }
}

impl<P: ContactSites> MassMetric for ContactProblem<'_, P> {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.model.inertia_metric(i)
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.model.eigenvalue_scale()
    }
}

impl<P: ContactSites> EquilibriumProblem for ContactProblem<'_, P> {
    type State = P::State;
    type Hessian = AdaptiveMatrix;

    fn n_free(&self) -> usize {
        self.model.n_free()
    }

    /// The model's storage; with self-contact, every pair of free DOFs (a contact may couple
    /// any two vertices, and the pattern must hold before the contacts are known). That dense
    /// pattern makes a factorization O(n³): fine for a few hundred vertices; a pattern grown
    /// as contacts appear is what larger scenes need.
    fn new_hessian(&self) -> AdaptiveMatrix {
        if self.edges.is_empty() {
            self.model.adaptive_hessian()
        } else {
            let n = self.model.n_free();
            AdaptiveMatrix::Sparse(SparseSymmetricMatrix::from_pattern(
                n,
                (0..n).flat_map(|i| (0..i).map(move |j| (i, j))),
            ))
        }
    }

    fn term_groups(&self) -> &[TermGroup] {
        &self.groups
    }

    fn assemble_selected<M: crate::linalg::SymmetricMatrix>(
        &self,
        state: &P::State,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        self.model.assemble_selected(state, load, asm);
        if asm.selects(FRICTION) {
            let friction = self.friction.borrow();
            for (k, site) in self.sites.iter().enumerate() {
                let p = self.model.site_position(state, site);
                for o in 0..self.obstacles.len() {
                    let f = friction[k * self.obstacles.len() + o];
                    if let Some((energy, grad, hess)) =
                        f.derivatives(&p, site.length, self.params.stick_stiffness)
                    {
                        let mut part = asm.part(&site.dofs);
                        part.local(&[0, 1, 2], energy, energy.abs(), &grad, &hess);
                        let info = part.finish();
                        asm.absorb(info);
                    }
                }
            }
        }
        if !asm.selects(CONTACT) {
            return;
        }
        let (kappa, activation) = (self.params.stiffness, self.params.activation);
        for (site, &radius) in self.sites.iter().zip(&self.site_radius) {
            let p = self.model.site_position(state, site);
            for obstacle in &self.obstacles {
                let s = obstacle.surface(&p);
                let gap = s.distance - radius;
                if gap >= activation {
                    continue;
                }
                let (b, db, ddb) = barrier(gap, activation);
                let weight = kappa * site.length;
                let energy = weight * b;
                let grad = s.normal * (weight * db);
                let hess: Matrix3<f64> =
                    (s.normal * s.normal.transpose() * ddb + s.normal_derivative * db) * weight;
                let mut part = asm.part(&site.dofs);
                part.local(&[0, 1, 2], energy, energy.abs(), &grad, &hess);
                let info = part.finish();
                asm.absorb(info);
            }
        }
        self.for_each_primitive(state, 0.0, |prim| {
            let length = self.primitive_length(prim);
            let clearance = prim.clearance(self);
            match prim {
                Primitive::EdgeEdge { a, b, x } => {
                    let m = edge_edge_mollifier(x, self.mollifier_scale(*a, *b));
                    let Some(e) = self.primitive_energy(
                        segment_distance_squared(x),
                        Some(m),
                        length,
                        clearance,
                    ) else {
                        return;
                    };
                    let remap: [SiteDof; 12] = self
                        .primitive_remap(&[self.edges[*a].sites, self.edges[*b].sites].concat());
                    let mut part = asm.part(&remap);
                    part.local(&std::array::from_fn(|k| k), e.v, e.v.abs(), &e.g, &e.h);
                    let info = part.finish();
                    asm.absorb(info);
                }
                Primitive::VertexEdge { v, e: edge, x } => {
                    let Some(e) = self.primitive_energy(
                        point_segment_distance_squared(x),
                        None,
                        length,
                        clearance,
                    ) else {
                        return;
                    };
                    let [e0, e1] = self.edges[*edge].sites;
                    let remap: [SiteDof; 9] = self.primitive_remap(&[*v, e0, e1]);
                    let mut part = asm.part(&remap);
                    part.local(&std::array::from_fn(|k| k), e.v, e.v.abs(), &e.g, &e.h);
                    let info = part.finish();
                    asm.absorb(info);
                }
            }
        });
    }

    fn merit(&self, trial: &P::State, load: f64) -> f64 {
        self.model.merit(trial, load) + self.contact_energy(trial)
    }

    fn difference(&self, a: &P::State, b: &P::State, out: &mut [f64]) {
        self.model.difference(a, b, out)
    }

    fn displace(&self, state: &P::State, dx: &[f64], alpha: f64, out: &mut P::State) {
        self.model.displace(state, dx, alpha, out)
    }

    fn chart(&self, state: &P::State, dx: &[f64], out: &mut P::State) {
        self.model.chart(state, dx, out)
    }

    fn impose_load(&self, state: &mut P::State, from: f64, to: f64, guess: bool) {
        if !guess || self.obstacles.is_empty() {
            return self.model.impose_load(state, from, to, guess);
        }
        // The model's first guess moves the free vertices by a blend of the supports' motion,
        // in one jump. A cable resting on an obstacle is held there as at a support, so the
        // blend is faded out toward its contacts (see [`Self::guess_fractions`]): carried
        // rigidly, a cable lying on a floor would be pushed into it by a downward drag of its
        // clamp, its vertices stopped at the floor and the others not, and Newton would start
        // from kinks of thousands of newtons. Each vertex's jump is then capped like a Newton
        // step (its time of impact with every obstacle, keeping a fraction of its gap), so
        // that the guess cannot carry a vertex through a thin obstacle (a ring's tube, a
        // panel) to a feasible state on its far side.
        let before = state.clone();
        self.model.impose_load(state, from, to, true);
        let mut fraction = self.guess_fractions(&before, state);
        let mut capped = fraction.iter().any(|&f| f < 1.0);
        for (k, (site, &radius)) in self.sites.iter().zip(&self.site_radius).enumerate() {
            let p0 = self.model.site_position(&before, site);
            let dp = (self.model.site_position(state, site) - p0) * fraction[k];
            if dp == Vector3::zeros() || site.dofs.iter().all(|d| d.dof == crate::assembly::FIXED) {
                continue;
            }
            for o in &self.obstacles {
                let gap = o.surface(&p0).distance - radius;
                let clearance = radius + KEEP_GAP * gap.max(0.0);
                let t = o.time_of_impact(&p0, &dp, clearance);
                if t < 1.0 {
                    fraction[k] *= t;
                    capped = true;
                }
            }
        }
        if !capped {
            return;
        }
        // The guess as a step from the supports-only state, each site's coordinates scaled by
        // its fraction.
        let guessed = std::mem::replace(state, before);
        self.model.impose_load(state, from, to, false);
        let mut dx = vec![0.0; self.model.n_free()];
        self.model.difference(&guessed, state, &mut dx);
        for (site, &f) in self.sites.iter().zip(&fraction) {
            for d in &site.dofs {
                if d.dof != crate::assembly::FIXED {
                    dx[d.dof] *= f;
                }
            }
        }
        let moved = state.clone();
        self.model.chart(&moved, &dx, state);
    }

    fn refresh_loads(&self, state: &mut P::State) -> f64 {
        self.model.refresh_loads(state)
    }

    fn has_lagged_loads(&self) -> bool {
        self.model.has_lagged_loads()
    }

    fn lagged_loads(&self, state: &P::State, out: &mut Vec<f64>) {
        self.model.lagged_loads(state, out);
    }

    fn set_lagged_loads(&self, state: &mut P::State, values: &[f64]) {
        self.model.set_lagged_loads(state, values);
    }

    fn max_step(&self, state: &P::State, dx: &[f64]) -> f64 {
        self.contact_step_limit(state, dx, self.model.max_step(state, dx))
    }

    fn kick_limit(&self, state: &P::State, dx: &[f64]) -> f64 {
        self.contact_step_limit(state, dx, 1.0)
    }

    fn caps_predictor(&self) -> bool {
        true
    }

    fn force_length(&self, i: usize) -> f64 {
        self.model.force_length(i)
    }

    fn dof_magnitude(&self, state: &P::State, i: usize) -> f64 {
        self.model.dof_magnitude(state, i)
    }
}

/// The wrapped model's DOFs, unchanged: the contact terms act on site positions only
/// (coordinates of every model), so the frames whose rotations are DOFs, their rotary inertia
/// and their orientations are the model's. Forwarding them is what lets the time stepper give
/// a Cosserat rod's or an SE(3) beam's frames their inertia (and the log chart's dexp⁻¹) in
/// contact; without them the rotation DOFs would have no mass at all.
impl<P: ContactSites + crate::dynamics::FlatDofs> crate::dynamics::FlatDofs
    for ContactProblem<'_, P>
{
    fn has_flat_dofs(&self) -> bool {
        self.model.has_flat_dofs()
    }

    fn frames(&self) -> Vec<crate::dynamics::FrameInertia> {
        self.model.frames()
    }

    fn frame_orientations(&self, state: &P::State, out: &mut Vec<nalgebra::UnitQuaternion<f64>>) {
        self.model.frame_orientations(state, out);
    }
}

/// Sub-steps of one additive conservative advancement before it settles for the motion
/// reached (still a safe step).
const MAX_CCD_STEPS: usize = 1000;

/// The largest fraction t ∈ [0, 1] of the motion `dp` of the points `x` (coordinate triples;
/// the first `first_side` points are one side, the others the other) that additive
/// conservative advancement certifies: `gap` (m) of the positions stays positive along
/// x + [0, t]·dp, above a tenth of a tenth of its start. 0 if the start's gap is not positive.
fn additive_ccd<const N: usize>(
    x: &[f64; N],
    dp: &[f64; N],
    first_side: usize,
    gap: impl Fn(&[f64; N]) -> f64,
) -> f64 {
    let g0 = gap(x);
    if !(g0 > 0.0) {
        return 0.0;
    }
    let side_motion =
        |points: std::ops::Range<usize>| points.map(|k| point3(dp, k).norm()).fold(0.0, f64::max);
    let bound = side_motion(0..first_side) + side_motion(first_side..N / 3);
    if bound == 0.0 {
        return 1.0;
    }
    let (mut t, mut g) = (0.0, g0);
    for _ in 0..MAX_CCD_STEPS {
        let next = t + (1.0 - KEEP_GAP) * g / bound;
        if next >= 1.0 {
            return 1.0;
        }
        t = next;
        g = gap(&std::array::from_fn(|i| x[i] + t * dp[i]));
        if g < KEEP_GAP * g0 {
            break;
        }
    }
    t
}

/// The three coordinates of point `k` of a gradient over point triples.
fn point3(g: &[f64], k: usize) -> Vector3<f64> {
    Vector3::new(g[3 * k], g[3 * k + 1], g[3 * k + 2])
}

/// What [`self_contact_edges`] finds: the edges as site pairs, the edge pairs that never
/// interact, and each site's chain and arc length (m).
type SelfContactEdges = (Vec<EdgeSites>, Vec<(usize, usize)>, Vec<(usize, f64)>);

/// The edges of `model` as site pairs, and the edge pairs that never interact: those sharing a
/// site, and those of one chain closer along it than π r + ĝ, r the larger of their radii
/// (see [`ContactProblem::with_chains`], [`ContactProblem::with_radii`]: member m has
/// `radii[m]`, or `params.radius`); with each site's chain and arc length.
fn self_contact_edges<P: ContactSites>(
    model: &P,
    sites: &[ContactSite],
    params: &ContactParams,
    chains: &[(usize, f64)],
    radii: &[f64],
) -> SelfContactEdges {
    // A member not in `chains` is its own chain, numbered past every given one.
    let first_own = chains.iter().map(|c| c.0 + 1).max().unwrap_or(0);
    let chain_of = |m: usize| chains.get(m).copied().unwrap_or((first_own + m, 0.0));
    let index: std::collections::HashMap<(usize, usize), usize> = sites
        .iter()
        .enumerate()
        .map(|(k, s)| ((s.member, s.vertex), k))
        .collect();
    let raw = model.contact_edges();
    let site_of = |m: usize, v: usize| index[&model.canonical_vertex(m, v)];
    let edges: Vec<EdgeSites> = raw
        .iter()
        .map(|e| EdgeSites {
            sites: [
                site_of(e.member, e.vertices[0]),
                site_of(e.member, e.vertices[1]),
            ],
            length: e.arc[1] - e.arc[0],
            member: e.member,
            index: e.vertices[0],
            chain: chain_of(e.member).0,
            arc: e.arc.map(|s| s + chain_of(e.member).1),
            radius: member_radius(radii, e.member, params.radius),
        })
        .collect();
    // Each site's arc length along its chain, from the edges that start or end there.
    let mut site_arcs: Vec<(usize, f64)> =
        sites.iter().map(|s| (chain_of(s.member).0, 0.0)).collect();
    for (e, edge) in raw.iter().zip(&edges) {
        for (k, &v) in e.vertices.iter().enumerate() {
            if let Some(&i) = index.get(&(e.member, v)) {
                site_arcs[i] = (edge.chain, edge.arc[k]);
            }
        }
    }
    let mut excluded = Vec::new();
    for a in 0..raw.len() {
        for b in a + 1..raw.len() {
            let shares = edges[a].sites.iter().any(|s| edges[b].sites.contains(s));
            let (ea, eb) = (&edges[a], &edges[b]);
            let reach = std::f64::consts::PI * ea.radius.max(eb.radius) + params.activation;
            let near =
                ea.chain == eb.chain && ea.arc[0].max(eb.arc[0]) - ea.arc[1].min(eb.arc[1]) < reach;
            if shares || near {
                excluded.push((a, b));
            }
        }
    }
    (edges, excluded, site_arcs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two crossing segments 1 mm apart (radius 0): edge a along x at z = 1 mm, edge b along
    /// y at z = 0.
    fn crossing() -> [f64; 12] {
        [
            -0.1, 0.0, 1e-3, 0.1, 0.0, 1e-3, 0.0, -0.1, 0.0, 0.0, 0.1, 0.0,
        ]
    }

    #[test]
    fn additive_ccd_lets_a_pressed_contact_slide_and_stops_an_approach_short() {
        let x = crossing();
        let gap = |y: &[f64; 12]| segment_distance(y);
        // Sliding 5 cm along its own axis at 1 mm: the gap stays, the whole motion is safe
        // (one bound of the motion against the gap would allow 2 % of it).
        let slide: [f64; 12] =
            std::array::from_fn(|i| if i % 3 == 0 && i < 6 { 0.05 } else { 0.0 });
        assert_eq!(additive_ccd(&x, &slide, 2, gap), 1.0);
        // Moving 3 mm down through the other: stopped with the gap still open.
        let through: [f64; 12] =
            std::array::from_fn(|i| if i % 3 == 2 && i < 6 { -3e-3 } else { 0.0 });
        let t = additive_ccd(&x, &through, 2, gap);
        let end: [f64; 12] = std::array::from_fn(|i| x[i] + t * through[i]);
        assert!(t > 0.0 && t < 1.0 / 3.0, "{t}");
        assert!(gap(&end) > 0.01 * 1e-3, "{}", gap(&end));
        // Nothing moves: no cap; a closed start: no motion at all.
        assert_eq!(additive_ccd(&x, &[0.0; 12], 2, gap), 1.0);
        assert_eq!(additive_ccd(&x, &through, 2, |y| gap(y) - 2e-3), 0.0);
    }
}
