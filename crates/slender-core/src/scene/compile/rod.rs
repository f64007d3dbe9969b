//! A rod of the scene file made ready for structures: its nodes (with vertices inserted where a
//! support is given by arc length), its supports and loads in vertex numbers, and its parts —
//! the rod split at interior clamps, each part a discrete elastic rod.
//!
//! A clamp fixes the position and the material frame of its vertex, so the parts on either
//! side of an interior clamp only meet there: each is clamped at the shared vertex (a ghost
//! edge and half Voronoi cell, exactly like an end clamp). A clip is a pin on its vertex and
//! on the next one (twist left free). Sliders and twist holds act across a part's own DOFs
//! and belong to the structure the part is a member of.

use crate::cosserat::CosseratBuilder;
use crate::framed::{FramedRodBuilder, ShearStiffness};
use crate::geometry::Vec3;
use crate::lie::DarbouxMeasure;
use crate::rod::{Grading, RestCurve, RodBuilder, RodProperties};
use crate::se3::Se3Builder;
use crate::solver::SolverParams;
use crate::structure::Member;

use super::super::error::SceneError;
use super::super::magnitudes::check_magnitudes;
use super::super::spec::{Centerline, RodModelSpec, RodSpec, SupportKind};
use super::precision::check_bending_resolved;
use super::section::{check_name, section, shear};

/// Default number of elements of a rod whose centerline is not a polyline.
pub const DEFAULT_ELEMENTS: usize = 20;

/// A support after validation, in the whole rod's vertex numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct CompiledSupport {
    /// Its kind.
    pub kind: SupportKind,
    /// The support's vertex (its point: moments are reported about it).
    pub vertex: usize,
    /// Every vertex whose position it holds (two for a clip, none for a twist hold).
    pub held: Vec<usize>,
    /// Slider axis (unit), for a slider.
    pub axis: Option<Vec3>,
    /// The held edge, for a twist hold.
    pub edge: Option<usize>,
}

/// A part of a rod between interior clamps (the whole rod if there are none).
#[derive(Clone, Debug)]
pub struct RodPart {
    /// Whole-rod index of its vertex 0.
    pub first_vertex: usize,
    /// Its number of vertices.
    pub n_vertices: usize,
    /// The structure it is a member of, and its member index there.
    pub structure: usize,
    /// Member index in the structure.
    pub member: usize,
}

impl RodPart {
    /// True if whole-rod vertex `v` lies on this part.
    pub fn contains(&self, v: usize) -> bool {
        v >= self.first_vertex && v < self.first_vertex + self.n_vertices
    }

    /// True if this part carries the loads on whole-rod vertex `v` of a rod of `n_edges`
    /// edges: a vertex shared by two parts (an interior clamp) loads the first.
    pub fn carries_loads_of(&self, v: usize, n_edges: usize) -> bool {
        let (a, b) = (self.first_vertex, self.first_vertex + self.n_vertices - 1);
        v >= a && (v < b || b == n_edges)
    }
}

/// A rod of the scene, ready to solve.
#[derive(Clone, Debug)]
pub struct CompiledRod {
    /// Output name.
    pub name: String,
    /// Number of edges of the whole rod.
    pub n_edges: usize,
    /// Rest arc length (m) of every vertex from vertex 0.
    pub node_arclengths: Vec<f64>,
    /// Parts between interior clamps, in order along the rod.
    pub parts: Vec<RodPart>,
    /// Supports in the order of the file.
    pub supports: Vec<CompiledSupport>,
    /// Radius (m) drawn in shape files.
    pub display_radius: f64,
    /// Section stiffnesses and mass per length.
    pub properties: RodProperties,
    /// Closed loop (its ends are joined).
    pub closed: bool,
    /// Smallest allowed bend radius (m), if given.
    pub min_bend_radius: Option<f64>,
    /// The whole-rod vertex of each of the file's point forces (`forces`, in order).
    pub force_vertices: Vec<usize>,
    /// The whole-rod vertex of each of the file's point moments (`moments`, in order).
    pub moment_vertices: Vec<usize>,
    /// The line loads' load per length (N/m) at each whole-rod vertex, summed over the file's
    /// `line_loads` (empty without line loads): what `slender view` draws.
    pub line_load_per_length: Vec<[f64; 3]>,
    /// The whole-rod vertex of every vertex of the file's mesh (what a `vertex` index in the
    /// file names); supports given by arc length (`at`) may insert vertices between them.
    pub base_vertices: Vec<usize>,
}

impl CompiledRod {
    /// The part that carries the loads on whole-rod vertex `v` (see
    /// [`RodPart::carries_loads_of`]).
    pub fn load_part(&self, v: usize) -> Option<&RodPart> {
        self.parts
            .iter()
            .find(|p| p.carries_loads_of(v, self.n_edges))
    }
}

/// A rod being compiled: its parts' rods, before they are grouped into structures.
pub(super) struct RodDraft {
    pub(super) rod: CompiledRod,
    /// The parts' members (same order as `rod.parts`).
    pub(super) members: Vec<Member>,
}

fn finite3(path: &str, v: [f64; 3]) -> Result<Vec3, SceneError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vec3::from(v))
    } else {
        Err(SceneError::new(
            path,
            format!("{v:?}: every component must be a finite number"),
        ))
    }
}

/// The rest arc lengths of the nodes before supports given by `at` insert theirs.
fn base_nodes(path: &str, spec: &RodSpec, length: f64) -> Result<Vec<f64>, SceneError> {
    match (&spec.centerline, spec.elements, spec.grading) {
        (Centerline::Polyline { points }, None, None) => {
            let mut s = vec![0.0];
            for w in points.windows(2) {
                let l = (Vec3::from(w[1]) - Vec3::from(w[0])).norm();
                s.push(s[s.len() - 1] + l);
            }
            Ok(s)
        }
        (_, elements, grading) => {
            let n = elements.unwrap_or(DEFAULT_ELEMENTS);
            if n == 0 || n > 100_000 {
                return Err(SceneError::new(
                    format!("{path}.elements"),
                    format!("{n}: must be in 1..=100000"),
                ));
            }
            grading
                .unwrap_or(Grading::Uniform)
                .node_arclengths(n, length)
                .map_err(|e| SceneError::model(format!("{path}.grading"), e))
        }
    }
}

/// Where the vertex given by a support, force or moment is, after the inserted nodes: maps
/// vertex numbers of the base mesh to the final one.
struct Renumber {
    /// Final index of every base vertex.
    map: Vec<usize>,
}

/// Compiles rod `index` of the scene (its supports, loads and parts), with the scene's
/// gravity.
pub(super) fn compile_rod(
    path: &str,
    index: usize,
    spec: &RodSpec,
    gravity: Vec3,
    _params: &SolverParams,
) -> Result<RodDraft, SceneError> {
    let name = spec.name.clone().unwrap_or_else(|| format!("rod{index}"));
    check_name(&format!("{path}.name"), &name)?;
    check_magnitudes(path, spec)?;
    let curve: RestCurve = spec.centerline.clone();
    curve
        .validate()
        .map_err(|e| SceneError::model(format!("{path}.centerline"), e))?;
    let length = curve.length();
    let (properties, display_radius) = section(path, spec, length)?;
    let shear = shear(path, spec)?;
    if let Some(r) = spec.min_bend_radius {
        if !(r.is_finite() && r > 0.0) {
            return Err(SceneError::new(
                format!("{path}.min_bend_radius"),
                format!("{r}: must be finite and > 0 (m)"),
            ));
        }
    }

    // Nodes: the base mesh, plus a vertex wherever a support is given by arc length.
    let base = base_nodes(path, spec, length)?;
    let mut nodes = base.clone();
    let tol = 1e-6 * length;
    for (k, s) in spec.supports.iter().enumerate() {
        let p = format!("{path}.supports[{k}]");
        match (s.vertex, s.at) {
            (Some(_), Some(_)) | (None, None) => {
                return Err(SceneError::new(
                    p,
                    "give exactly one of `vertex` (an index, \"start\" or \"end\") or `at` (arc length in m)",
                ));
            }
            (None, Some(at)) => {
                if !(at.is_finite() && (0.0..=length).contains(&at)) {
                    return Err(SceneError::new(
                        format!("{p}.at"),
                        format!("{at}: must be within 0..={length} (the rod's rest length, m)"),
                    ));
                }
                if !nodes.iter().any(|&x| (x - at).abs() <= tol) {
                    nodes.push(at);
                }
            }
            _ => {}
        }
    }
    nodes.sort_by(f64::total_cmp);
    let renumber = Renumber {
        map: base
            .iter()
            .map(|b| nodes.iter().position(|x| x == b).expect("base node kept"))
            .collect(),
    };
    let n_edges = nodes.len() - 1;
    let n_base = base.len() - 1;
    let base_vertex = |p: String, v: usize| -> Result<usize, SceneError> {
        if v > n_base {
            Err(SceneError::new(
                p,
                format!("{v}: must be <= {n_base} (rod {index} has vertices 0..={n_base})"),
            ))
        } else {
            Ok(renumber.map[v])
        }
    };
    let nearest = |at: f64| -> usize {
        (0..nodes.len())
            .min_by(|&a, &b| (nodes[a] - at).abs().total_cmp(&(nodes[b] - at).abs()))
            .expect("nodes")
    };
    let positions: Vec<Vec3> = nodes.iter().map(|&s| curve.evaluate(s).0).collect();
    check_bending_resolved(path, spec, &properties, shear, &positions, length)?;

    if spec.closed {
        let gap = (positions[n_edges] - positions[0]).norm();
        if !(gap <= 1e-9 * length) {
            return Err(SceneError::new(
                format!("{path}.closed"),
                format!(
                    "the centerline's end is {gap:.3e} m from its start: a closed rod's ends must meet (e.g. an arc of length 2π·radius)"
                ),
            ));
        }
    }

    // Supports.
    let mut supports: Vec<CompiledSupport> = Vec::with_capacity(spec.supports.len());
    let mut held_by: Vec<Option<usize>> = vec![None; n_edges + 1];
    for (k, s) in spec.supports.iter().enumerate() {
        let p = format!("{path}.supports[{k}]");
        let v = match (s.vertex, s.at) {
            (Some(vr), None) => base_vertex(format!("{p}.vertex"), vr.index(n_base))?,
            (None, Some(at)) => nearest(at),
            _ => unreachable!("checked above"),
        };
        if s.axis.is_some() && s.kind != SupportKind::Slider {
            return Err(SceneError::new(
                format!("{p}.axis"),
                "only a slider has an axis",
            ));
        }
        let mut axis = None;
        let mut edge = None;
        let held = match s.kind {
            SupportKind::Clip if v == n_edges => vec![v - 1, v],
            SupportKind::Clip => vec![v, v + 1],
            // A closed rod clamped where its ends meet holds both ends there.
            SupportKind::Clamp if spec.closed && (v == 0 || v == n_edges) => vec![0, n_edges],
            SupportKind::Clamp | SupportKind::Pin => vec![v],
            SupportKind::Slider => {
                let a = match s.axis {
                    Some(a) => {
                        let a = finite3(&format!("{p}.axis"), a)?;
                        let n = a.norm();
                        if !(n > 0.0 && n.is_finite()) {
                            return Err(SceneError::new(
                                format!("{p}.axis"),
                                "must be a non-zero direction: a slider slides along one straight axis (curved guides are not supported)",
                            ));
                        }
                        a / n
                    }
                    None => curve.evaluate(nodes[v]).1,
                };
                axis = Some(a);
                vec![v]
            }
            SupportKind::TwistHold => {
                edge = Some(v.min(n_edges - 1));
                Vec::new()
            }
        };
        for &h in &held {
            if let Some(other) = held_by[h] {
                return Err(SceneError::new(
                    if s.vertex.is_some() {
                        format!("{p}.vertex")
                    } else {
                        format!("{p}.at")
                    },
                    format!(
                        "vertex {h} is already held by supports[{other}]; one support per vertex"
                    ),
                ));
            }
            held_by[h] = Some(k);
        }
        supports.push(CompiledSupport {
            kind: s.kind,
            vertex: v,
            held,
            axis,
            edge,
        });
    }
    for (k, s) in supports.iter().enumerate() {
        if let Some(e) = s.edge {
            if supports
                .iter()
                .enumerate()
                .any(|(o, t)| o != k && t.edge == Some(e))
            {
                return Err(SceneError::new(
                    format!("{path}.supports[{k}]"),
                    format!("edge {e}'s twist is held twice"),
                ));
            }
        }
    }
    // A rod with no support may still be held through a joint: its structure decides.

    // Loads, in the final numbering.
    let mut forces: Vec<(usize, Vec3)> = Vec::new();
    let mut followers: Vec<(usize, Vec3, Vec3)> = Vec::new();
    let mut force_vertices = Vec::with_capacity(spec.forces.len());
    for (k, f) in spec.forces.iter().enumerate() {
        let v = base_vertex(format!("{path}.forces[{k}].vertex"), f.vertex.index(n_base))?;
        force_vertices.push(v);
        let force = finite3(&format!("{path}.forces[{k}].force"), f.force)?;
        if f.follower {
            if held_by[v].is_some() {
                return Err(SceneError::new(
                    format!("{path}.forces[{k}].follower"),
                    format!("vertex {v} is held by a support: a follower load there does nothing"),
                ));
            }
            followers.push((v, force, Vec3::zeros()));
        } else {
            forces.push((v, force));
        }
    }
    let mut moments = Vec::new();
    let mut moment_vertices = Vec::with_capacity(spec.moments.len());
    for (k, m) in spec.moments.iter().enumerate() {
        let v = base_vertex(
            format!("{path}.moments[{k}].vertex"),
            m.vertex.index(n_base),
        )?;
        moment_vertices.push(v);
        let moment = finite3(&format!("{path}.moments[{k}].moment"), m.moment)?;
        if m.follower {
            if held_by[v].is_some() {
                return Err(SceneError::new(
                    format!("{path}.moments[{k}].follower"),
                    format!("vertex {v} is held by a support: a follower load there does nothing"),
                ));
            }
            followers.push((v, Vec3::zeros(), moment));
        } else {
            moments.push((v, moment));
        }
    }
    let mut line_load_per_length = Vec::new();
    for (k, l) in spec.line_loads.iter().enumerate() {
        let q = super::line_loads::sample(&format!("{path}.line_loads[{k}]"), l, &nodes)?;
        line_load_per_length.resize(nodes.len(), [0.0; 3]);
        for (total, q) in line_load_per_length.iter_mut().zip(q) {
            for c in 0..3 {
                total[c] += q[c];
            }
        }
        for (v, f) in super::line_loads::lump(&format!("{path}.line_loads[{k}]"), l, &nodes)? {
            forces.push((v, f));
        }
    }
    if spec.model != RodModelSpec::Der {
        framed_restrictions(path, spec)?;
    }
    let first_director = match spec.first_director {
        Some(d) => Some(finite3(&format!("{path}.first_director"), d)?),
        None => None,
    };

    // Split at interior clamps (and, for a closed rod, nowhere else: its ends are joined by
    // the structure).
    let mut cuts: Vec<usize> = supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp && s.vertex > 0 && s.vertex < n_edges)
        .map(|s| s.vertex)
        .collect();
    cuts.sort_unstable();
    let mut bounds = vec![0];
    bounds.extend(cuts.iter().copied());
    bounds.push(n_edges);

    // Material frames of the whole rod's rest state orient each part like the whole rod.
    let whole_curve = RestCurve::Polyline {
        points: positions.iter().map(|p| [p.x, p.y, p.z]).collect(),
    };
    let chord_nodes = |pts: &[Vec3]| -> Vec<f64> {
        std::iter::once(0.0)
            .chain(pts.windows(2).scan(0.0, |s, w| {
                *s += (w[1] - w[0]).norm();
                Some(*s)
            }))
            .collect()
    };
    let part_director = |a: usize| -> Result<Option<Vec3>, SceneError> {
        if bounds.len() == 2 {
            return Ok(first_director);
        }
        let mut b = RodBuilder::new(whole_curve.clone(), properties)
            .nodes_at(chord_nodes(&positions))
            .allow_rigid_motion();
        if let Some(d) = first_director {
            b = b.first_director(d);
        }
        let probe = b
            .build()
            .map_err(|e| SceneError::model(format!("{path}.first_director"), e))?;
        Ok(Some(probe.rest_state().material_frame(a)[0]))
    };

    // A closed rod clamped where its ends meet is clamped at both ends by that clamp.
    let clamped: Vec<usize> = supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .flat_map(|s| {
            if spec.closed && (s.vertex == 0 || s.vertex == n_edges) {
                vec![0, n_edges]
            } else {
                vec![s.vertex]
            }
        })
        .collect();
    let mut parts = Vec::with_capacity(bounds.len() - 1);
    let mut members = Vec::with_capacity(bounds.len() - 1);
    for w in bounds.windows(2) {
        let (a, b) = (w[0], w[1]);
        let single = bounds.len() == 2;
        let part_curve = if single {
            curve.clone()
        } else {
            let pts: Vec<[f64; 3]> = positions[a..=b].iter().map(|p| [p.x, p.y, p.z]).collect();
            RestCurve::Polyline { points: pts }
        };
        let part_nodes = if single {
            nodes.clone()
        } else {
            chord_nodes(&positions[a..=b])
        };
        // A load on a vertex shared by two parts (an interior clamp) goes to the first (the
        // rule of `RodPart::carries_loads_of`).
        let owns = |v: usize| v >= a && (v < b || b == n_edges);
        let pins: Vec<usize> = supports
            .iter()
            .filter(|s| matches!(s.kind, SupportKind::Pin | SupportKind::Clip))
            .flat_map(|s| s.held.iter().copied())
            .filter(|&h| h >= a && h <= b)
            .map(|h| h - a)
            .collect();
        let part_forces: Vec<(usize, Vec3)> = forces
            .iter()
            .filter(|(v, _)| owns(*v))
            .map(|&(v, f)| (v - a, f))
            .collect();
        let part_moments: Vec<(usize, Vec3)> = moments
            .iter()
            .filter(|(v, _)| owns(*v))
            .map(|&(v, m)| (v - a, m))
            .collect();
        let part_path = if single {
            path.to_string()
        } else {
            format!("{path} (part between vertices {a} and {b})")
        };
        let director = part_director(a)?;
        let member = match shear {
            None => {
                let mut builder = RodBuilder::new(part_curve, properties)
                    .nodes_at(part_nodes)
                    .allow_rigid_motion()
                    .gravity(gravity);
                if let Some(d) = director {
                    builder = builder.first_director(d);
                }
                if clamped.contains(&a) {
                    builder = builder.clamp_start();
                }
                if clamped.contains(&b) {
                    builder = builder.clamp_end();
                }
                for &p in &pins {
                    builder = builder.pin(p);
                }
                for &(v, f) in &part_forces {
                    builder = builder.point_force(v, f);
                }
                for &(v, m) in &part_moments {
                    builder = builder.point_moment(v, m);
                }
                for &(v, f, m) in &followers {
                    if owns(v) {
                        builder = builder.follower_load(v - a, f, m);
                    }
                }
                Member::Der(
                    builder
                        .build()
                        .map_err(|e| SceneError::model(part_path.clone(), e))?,
                )
            }
            Some(shear) => {
                let setup = FramedSetup {
                    curve: part_curve,
                    nodes: part_nodes,
                    properties,
                    shear,
                    director,
                    gravity,
                    clamps: [clamped.contains(&a), clamped.contains(&b)],
                    pins: &pins,
                    forces: &part_forces,
                    moments: &part_moments,
                };
                framed_member(spec.model, &setup)
                    .map_err(|e| SceneError::model(part_path.clone(), e))?
            }
        };
        let rest = member.rest_state();
        let rest_lengths_ok = rest.positions().windows(2).all(|w| {
            let l = (w[1] - w[0]).norm();
            l.is_finite() && l > 0.0
        });
        if rest.positions().iter().flatten().any(|c| !c.is_finite()) || !rest_lengths_ok {
            return Err(SceneError::new(
                path,
                format!("{part_path}: the mesh has non-finite coordinates; check lengths, radii and points for overflow"),
            ));
        }
        parts.push(RodPart {
            first_vertex: a,
            n_vertices: b - a + 1,
            structure: usize::MAX,
            member: usize::MAX,
        });
        members.push(member);
    }
    Ok(RodDraft {
        rod: CompiledRod {
            name,
            n_edges,
            node_arclengths: nodes,
            parts,
            supports,
            display_radius,
            properties,
            closed: spec.closed,
            min_bend_radius: spec.min_bend_radius,
            force_vertices,
            moment_vertices,
            line_load_per_length,
            base_vertices: renumber.map,
        },
        members,
    })
}

/// What the Cosserat and SE(3) rods cannot take in a scene (each names its field).
fn framed_restrictions(path: &str, spec: &RodSpec) -> Result<(), SceneError> {
    let model = spec.model.name();
    if spec.closed {
        return Err(SceneError::new(
            format!("{path}.closed"),
            format!("closed loops are discrete elastic rods only (model = \"der\"), not model = \"{model}\""),
        ));
    }
    for (k, s) in spec.supports.iter().enumerate() {
        if matches!(s.kind, SupportKind::Slider | SupportKind::TwistHold) {
            return Err(SceneError::new(
                format!("{path}.supports[{k}].kind"),
                format!("{:?} is not available with model = \"{model}\"; valid: clamp, pin, clip (sliders and twist holds need model = \"der\")", s.kind),
            ));
        }
    }
    for (k, f) in spec.forces.iter().enumerate() {
        if f.follower {
            return Err(SceneError::new(
                format!("{path}.forces[{k}].follower"),
                format!(
                    "follower loads need model = \"der\"; with model = \"{model}\" loads are dead"
                ),
            ));
        }
    }
    for (k, m) in spec.moments.iter().enumerate() {
        if m.follower {
            return Err(SceneError::new(
                format!("{path}.moments[{k}].follower"),
                format!(
                    "follower loads need model = \"der\"; with model = \"{model}\" loads are dead"
                ),
            ));
        }
    }
    Ok(())
}

/// A part of a framed rod, as the scene gives it.
struct FramedSetup<'a> {
    curve: RestCurve,
    nodes: Vec<f64>,
    properties: RodProperties,
    shear: ShearStiffness,
    director: Option<Vec3>,
    gravity: Vec3,
    /// Clamped at its start and end.
    clamps: [bool; 2],
    pins: &'a [usize],
    forces: &'a [(usize, Vec3)],
    moments: &'a [(usize, Vec3)],
}

impl FramedSetup<'_> {
    /// The builder input both framed models share.
    fn apply<K>(&self, mut b: FramedRodBuilder<K>) -> FramedRodBuilder<K> {
        // As for a discrete elastic rod, the structure checks the whole for free motion (or
        // allows it: a rod in free fall or resting on obstacles).
        b = b
            .nodes_at(self.nodes.clone())
            .gravity(self.gravity)
            .allow_rigid_motion();
        if let Some(d) = self.director {
            b = b.first_director(d);
        }
        if self.clamps[0] {
            b = b.clamp_start();
        }
        if self.clamps[1] {
            b = b.clamp_end();
        }
        for &p in self.pins {
            b = b.pin(p);
        }
        for &(v, f) in self.forces {
            b = b.point_force(v, f);
        }
        for &(v, m) in self.moments {
            b = b.point_moment(v, m);
        }
        b
    }
}

/// Builds a Cosserat rod or an SE(3) beam part.
fn framed_member(
    model: RodModelSpec,
    s: &FramedSetup<'_>,
) -> Result<Member, crate::error::ModelError> {
    let (c, p, g) = (s.curve.clone(), s.properties, s.shear);
    Ok(match model {
        RodModelSpec::Cosserat | RodModelSpec::CosseratTan => {
            let measure = if model == RodModelSpec::CosseratTan {
                DarbouxMeasure::Tangent
            } else {
                DarbouxMeasure::Sine
            };
            Member::Cosserat(
                s.apply(CosseratBuilder::new(c, p, g))
                    .darboux(measure)
                    .build()?,
            )
        }
        RodModelSpec::Se3 => Member::Se3(s.apply(Se3Builder::new(c, p, g)).build()?),
        RodModelSpec::Der => unreachable!("the discrete elastic rod is built by RodBuilder"),
    })
}
