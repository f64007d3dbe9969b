//! Turning a parsed scene into rods ready to solve, checking everything a file can get wrong
//! and naming the place when it does.
//!
//! A clamp fixes the position and the material frame of its vertex, so the parts of a rod on
//! either side of an interior clamp do not interact: such a rod is split there into
//! *segments*, each clamped at the shared vertex (a ghost edge and half Voronoi cell, exactly
//! like an end clamp). A clip is a pin on its vertex and on the next one (twist left free).

use crate::error::ModelError;
use crate::geometry::Vec3;
use crate::rod::SectionStiffness;
use crate::rod::{CrossSection, Grading, Material, RestCurve, Rod, RodBuilder, RodProperties};
use crate::solver::SolverParams;

use super::error::SceneError;
use super::free_motion::check_no_free_motion;
use super::magnitudes::{check_magnitudes, MAGNITUDE_LIMIT};
use super::spec::{
    Centerline, MaterialSpec, MotionStage, RodSpec, Scene, SectionSpec, SupportKind,
};

/// Default number of elements of a rod whose centerline is not a polyline.
pub const DEFAULT_ELEMENTS: usize = 20;

/// Largest number of solved pieces one motion step may need (see `solve.rs`).
const MAX_PIECES_PER_STEP: f64 = 1000.0;

/// A support after validation, with its vertices in the whole rod's numbering.
#[derive(Clone, Debug, PartialEq)]
pub struct CompiledSupport {
    /// Clamp, pin or clip.
    pub kind: SupportKind,
    /// The support's vertex (its point: moments are reported about it).
    pub vertex: usize,
    /// Every vertex it holds (two for a clip).
    pub held: Vec<usize>,
}

/// A part of a rod between interior clamps (the whole rod if there are none).
#[derive(Clone, Debug)]
pub struct Segment {
    /// The rod model of this part.
    pub rod: Rod,
    /// Whole-rod index of its vertex 0.
    pub first_vertex: usize,
}

impl Segment {
    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.rod.n_edges() + 1
    }

    /// True if whole-rod vertex `v` lies on this segment.
    pub fn contains(&self, v: usize) -> bool {
        v >= self.first_vertex && v < self.first_vertex + self.n_vertices()
    }
}

/// A rod of the scene, ready to solve.
#[derive(Clone, Debug)]
pub struct CompiledRod {
    /// Output name.
    pub name: String,
    /// Number of edges of the whole rod.
    pub n_edges: usize,
    /// Parts between interior clamps, in order along the rod.
    pub segments: Vec<Segment>,
    /// Supports in the order of the file.
    pub supports: Vec<CompiledSupport>,
    /// Radius (m) drawn in shape files.
    pub display_radius: f64,
    /// Section stiffnesses and mass per length.
    pub properties: RodProperties,
}

/// A scene ready to solve.
#[derive(Clone, Debug)]
pub struct CompiledScene {
    /// The rods.
    pub rods: Vec<CompiledRod>,
    /// The shell strips (solved independently of the rods).
    pub shells: Vec<super::shells::CompiledShell>,
    /// Prescribed motion stages (validated).
    pub motion: Vec<MotionStage>,
    /// Solver parameters (validated).
    pub solver: SolverParams,
    /// Gravitational acceleration (m/s²).
    pub gravity: [f64; 3],
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

fn rest_curve(c: &Centerline) -> RestCurve {
    match c.clone() {
        Centerline::Straight {
            start,
            direction,
            length,
        } => RestCurve::Straight {
            start,
            direction,
            length,
        },
        Centerline::Arc {
            start,
            tangent,
            normal,
            radius,
            length,
        } => RestCurve::Circle {
            start,
            tangent,
            normal,
            radius,
            length,
        },
        Centerline::Helix {
            start,
            axis,
            normal,
            radius,
            pitch,
            length,
        } => RestCurve::Helix {
            start,
            axis,
            normal,
            radius,
            pitch,
            length,
        },
        Centerline::Polyline { points } => RestCurve::Polyline { points },
    }
}

fn material(path: &str, m: &MaterialSpec) -> Result<Material, SceneError> {
    let poisson = match (m.poisson, m.shear_modulus) {
        (Some(nu), None) => nu,
        (None, Some(g)) => {
            if !(g.is_finite() && g > 0.0) {
                return Err(SceneError::new(
                    format!("{path}.shear_modulus"),
                    format!("{g}: must be finite and > 0"),
                ));
            }
            let nu = m.young / (2.0 * g) - 1.0;
            if !(nu > -1.0 && nu <= 0.5) {
                return Err(SceneError::new(
                    format!("{path}.shear_modulus"),
                    format!(
                        "{g}: with young = {} the implied Poisson ratio {nu} is outside (-1, 0.5]; valid: shear_modulus >= young/3",
                        m.young
                    ),
                ));
            }
            nu
        }
        _ => {
            return Err(SceneError::new(
                path,
                "give exactly one of `poisson` or `shear_modulus`",
            ))
        }
    };
    Ok(Material {
        young: m.young,
        poisson,
        density: m.density,
    })
}

/// Stiffnesses, mass per length and drawn radius of a rod's section.
fn section(path: &str, spec: &RodSpec, length: f64) -> Result<(RodProperties, f64), SceneError> {
    let geometric = |shape: CrossSection, radius: f64| {
        let m = spec.material.as_ref().ok_or_else(|| {
            SceneError::new(
                format!("{path}.material"),
                "missing: a circle or rectangle section needs `material` (young, poisson or shear_modulus, density)",
            )
        })?;
        let mat = material(&format!("{path}.material"), m)?;
        let props = shape.properties(&mat).map_err(|e| {
            // Name the table the offending field is in.
            let field = match &e {
                ModelError::InvalidParameter { field, .. }
                | ModelError::InvalidStructure { field, .. } => field.as_str(),
            };
            let table = if ["young", "poisson", "density"].contains(&field) {
                "material"
            } else {
                "section"
            };
            SceneError::model(format!("{path}.{table}"), e)
        })?;
        Ok((props, radius))
    };
    match spec.section {
        SectionSpec::Circle { diameter } => {
            geometric(CrossSection::Circle { diameter }, 0.5 * diameter)
        }
        SectionSpec::Rectangle { width, height } => geometric(
            CrossSection::Rectangle { width, height },
            (width * height / std::f64::consts::PI).sqrt(),
        ),
        SectionSpec::Stiffness {
            ea,
            ei1,
            ei2,
            gj,
            linear_density,
            display_radius,
        } => {
            if spec.material.is_some() {
                return Err(SceneError::new(
                    format!("{path}.material"),
                    "not allowed with section shape = \"stiffness\" (the stiffnesses and linear_density say it all)",
                ));
            }
            let props = RodProperties {
                stiffness: SectionStiffness { ea, ei1, ei2, gj },
                linear_density,
            };
            props
                .validate()
                .map_err(|e| SceneError::model(format!("{path}.section"), e))?;
            let radius = display_radius.unwrap_or(0.01 * length);
            if !(radius.is_finite() && radius > 0.0) {
                return Err(SceneError::new(
                    format!("{path}.section.display_radius"),
                    format!("{radius}: must be finite and > 0"),
                ));
            }
            Ok((props, radius))
        }
    }
}

/// Name check: safe as a file-name stem.
pub(super) fn check_name(path: &str, name: &str) -> Result<(), SceneError> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(SceneError::new(
            path,
            format!("{name:?}: must be 1 to 64 characters among letters, digits, '-' and '_'"),
        ))
    }
}

impl Scene {
    /// Validates the scene and builds its rods. Errors name the path in the file.
    pub fn compile(&self) -> Result<CompiledScene, SceneError> {
        if self.rods.is_empty() && self.shells.is_empty() {
            return Err(SceneError::new(
                "rods",
                "the scene has no rod and no shell; add at least one [[rods]] or [[shells]] table",
            ));
        }
        let gravity = finite3("gravity", self.gravity)?;
        if gravity.amax() > MAGNITUDE_LIMIT {
            return Err(SceneError::new(
                "gravity",
                format!(
                    "{:?}: components must have magnitude <= {MAGNITUDE_LIMIT:e}",
                    self.gravity
                ),
            ));
        }
        self.solver
            .validate()
            .map_err(|e| SceneError::model("solver", e))?;
        let mut rods = Vec::with_capacity(self.rods.len());
        let mut names = Vec::new();
        for (i, spec) in self.rods.iter().enumerate() {
            let rod = compile_rod(&format!("rods[{i}]"), i, spec, gravity, &self.solver)?;
            if names.contains(&rod.name) {
                return Err(SceneError::new(
                    format!("rods[{i}].name"),
                    format!(
                        "{:?} is used by another rod; names must be unique",
                        rod.name
                    ),
                ));
            }
            names.push(rod.name.clone());
            rods.push(rod);
        }
        for (k, stage) in self.motion.iter().enumerate() {
            let path = format!("motion[{k}]");
            let Some(rod) = rods.get(stage.rod) else {
                return Err(SceneError::new(
                    format!("{path}.rod"),
                    format!("{}: must be < {} (number of rods)", stage.rod, rods.len()),
                ));
            };
            let Some(support) = rod.supports.get(stage.support) else {
                return Err(SceneError::new(
                    format!("{path}.support"),
                    format!(
                        "{}: must be < {} (supports of rod {})",
                        stage.support,
                        rod.supports.len(),
                        stage.rod
                    ),
                ));
            };
            finite3(&format!("{path}.translate"), stage.translate)?;
            let rot = finite3(&format!("{path}.rotate"), stage.rotate)?;
            if support.kind == SupportKind::Pin && rot.norm() > 0.0 {
                return Err(SceneError::new(
                    format!("{path}.rotate"),
                    "a pin has no orientation to rotate; rotate clamps or clips, translate pins",
                ));
            }
            if stage.steps == 0 || stage.steps > 10_000 {
                return Err(SceneError::new(
                    format!("{path}.steps"),
                    format!("{}: must be in 1..=10000", stage.steps),
                ));
            }
            // Each step is solved in pieces small enough for Newton (see solve.rs); bound
            // their number so that an absurd motion is an error, not an endless run.
            let shortest = rod
                .segments
                .iter()
                .map(|s| s.rod.length())
                .fold(f64::INFINITY, f64::min);
            let per_step = |v: [f64; 3]| Vec3::from(v).norm() / stage.steps as f64;
            let pieces = (per_step(stage.rotate) / super::solve::MAX_PIECE_ROTATION)
                .max(per_step(stage.translate) / (super::solve::MAX_PIECE_TRANSLATION * shortest));
            if !(pieces <= MAX_PIECES_PER_STEP) {
                return Err(SceneError::new(
                    path,
                    format!(
                        "the motion per step is too large ({:.3e} rad, {:.3e} m per step would need {pieces:.3e} solves); at most {} rad and {} m per step here: use more steps",
                        per_step(stage.rotate),
                        per_step(stage.translate),
                        MAX_PIECES_PER_STEP * super::solve::MAX_PIECE_ROTATION,
                        MAX_PIECES_PER_STEP * super::solve::MAX_PIECE_TRANSLATION * shortest
                    ),
                ));
            }
        }
        let mut shells = Vec::with_capacity(self.shells.len());
        for (i, spec) in self.shells.iter().enumerate() {
            let path = format!("shells[{i}]");
            let shell = super::shells::compile_shell(&path, i, spec, gravity)?;
            if names.contains(&shell.name) {
                return Err(SceneError::new(
                    format!("{path}.name"),
                    format!(
                        "{:?} is used by another rod or shell; names must be unique",
                        shell.name
                    ),
                ));
            }
            names.push(shell.name.clone());
            shells.push(shell);
        }
        let mut solver = self.solver;
        solver
            .polish_iterations
            .get_or_insert(super::solve::SCENE_POLISH_ITERATIONS);
        Ok(CompiledScene {
            rods,
            shells,
            motion: self.motion.clone(),
            solver,
            gravity: self.gravity,
        })
    }
}

fn compile_rod(
    path: &str,
    index: usize,
    spec: &RodSpec,
    gravity: Vec3,
    params: &SolverParams,
) -> Result<CompiledRod, SceneError> {
    let name = spec.name.clone().unwrap_or_else(|| format!("rod{index}"));
    check_name(&format!("{path}.name"), &name)?;
    check_magnitudes(path, spec)?;
    let curve = rest_curve(&spec.centerline);
    curve
        .validate()
        .map_err(|e| SceneError::model(format!("{path}.centerline"), e))?;
    let length = curve.length();
    let (properties, display_radius) = section(path, spec, length)?;

    // Node arc lengths of the whole rod.
    let nodes: Vec<f64> = match (&spec.centerline, spec.elements, spec.grading) {
        (Centerline::Polyline { points }, None, None) => {
            let mut s = vec![0.0];
            for w in points.windows(2) {
                let l = (Vec3::from(w[1]) - Vec3::from(w[0])).norm();
                s.push(s[s.len() - 1] + l);
            }
            s
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
                .map_err(|e| SceneError::model(format!("{path}.grading"), e))?
        }
    };
    let n_edges = nodes.len() - 1;
    let positions: Vec<Vec3> = nodes.iter().map(|&s| curve.evaluate(s).0).collect();

    // Supports.
    let mut supports = Vec::with_capacity(spec.supports.len());
    let mut held_by: Vec<Option<usize>> = vec![None; n_edges + 1];
    for (k, s) in spec.supports.iter().enumerate() {
        let p = format!("{path}.supports[{k}].vertex");
        let v = s.vertex.index(n_edges);
        if v > n_edges {
            return Err(SceneError::new(
                p,
                format!("{v}: must be <= {n_edges} (rod {index} has vertices 0..={n_edges})"),
            ));
        }
        let held = match s.kind {
            SupportKind::Clip if v == n_edges => vec![v - 1, v],
            SupportKind::Clip => vec![v, v + 1],
            _ => vec![v],
        };
        for &h in &held {
            if let Some(other) = held_by[h] {
                return Err(SceneError::new(
                    p,
                    format!(
                        "{v}: vertex {h} is already held by supports[{other}]; one support per vertex"
                    ),
                ));
            }
            held_by[h] = Some(k);
        }
        supports.push(CompiledSupport {
            kind: s.kind,
            vertex: v,
            held,
        });
    }
    if supports.is_empty() {
        return Err(SceneError::new(
            format!("{path}.supports"),
            "the rod has no support and can move as a rigid body; add a clamp, or pins/clips on at least three non-collinear vertices",
        ));
    }

    // Loads, checked in the whole rod's numbering.
    let mut forces = Vec::new();
    for (k, f) in spec.forces.iter().enumerate() {
        let v = f.vertex.index(n_edges);
        if v > n_edges {
            return Err(SceneError::new(
                format!("{path}.forces[{k}].vertex"),
                format!("{v}: must be <= {n_edges} (rod {index} has vertices 0..={n_edges})"),
            ));
        }
        forces.push((v, finite3(&format!("{path}.forces[{k}].force"), f.force)?));
    }
    let mut moments = Vec::new();
    for (k, m) in spec.moments.iter().enumerate() {
        let v = m.vertex.index(n_edges);
        if v > n_edges {
            return Err(SceneError::new(
                format!("{path}.moments[{k}].vertex"),
                format!("{v}: must be <= {n_edges} (rod {index} has vertices 0..={n_edges})"),
            ));
        }
        moments.push((
            v,
            finite3(&format!("{path}.moments[{k}].moment"), m.moment)?,
        ));
    }
    let first_director = match spec.first_director {
        Some(d) => Some(finite3(&format!("{path}.first_director"), d)?),
        None => None,
    };

    // Split at interior clamps.
    let mut cuts: Vec<usize> = supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp && s.vertex > 0 && s.vertex < n_edges)
        .map(|s| s.vertex)
        .collect();
    cuts.sort_unstable();
    let mut bounds = vec![0];
    bounds.extend(cuts.iter().copied());
    bounds.push(n_edges);

    // Material frames of the whole rod's rest state, to orient each segment like the whole rod.
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
    let segment_director = |a: usize| -> Result<Option<Vec3>, SceneError> {
        if bounds.len() == 2 {
            return Ok(first_director);
        }
        let mut b = RodBuilder::new(whole_curve.clone(), properties)
            .nodes_at(chord_nodes(&positions))
            .clamp_start();
        if let Some(d) = first_director {
            b = b.first_director(d);
        }
        let probe = b
            .build()
            .map_err(|e| SceneError::model(format!("{path}.first_director"), e))?;
        Ok(Some(probe.rest_state().material_frame(a)[0]))
    };

    let mut segments = Vec::with_capacity(bounds.len() - 1);
    for w in bounds.windows(2) {
        let (a, b) = (w[0], w[1]);
        let single = bounds.len() == 2;
        let mut builder = if single {
            match (&spec.centerline, spec.elements, spec.grading) {
                (Centerline::Polyline { .. }, None, None) => {
                    RodBuilder::new(curve.clone(), properties).nodes_at(nodes.clone())
                }
                _ => RodBuilder::new(curve.clone(), properties)
                    .elements(n_edges)
                    .grading(spec.grading.unwrap_or(Grading::Uniform)),
            }
        } else {
            let pts: Vec<[f64; 3]> = positions[a..=b].iter().map(|p| [p.x, p.y, p.z]).collect();
            let local = chord_nodes(&positions[a..=b]);
            RodBuilder::new(RestCurve::Polyline { points: pts }, properties).nodes_at(local)
        };
        if let Some(d) = segment_director(a)? {
            builder = builder.first_director(d);
        }
        builder = builder.gravity(gravity);
        for s in &supports {
            match s.kind {
                SupportKind::Clamp if s.vertex == a => builder = builder.clamp_start(),
                SupportKind::Clamp if s.vertex == b => builder = builder.clamp_end(),
                SupportKind::Clamp => {}
                SupportKind::Pin | SupportKind::Clip => {
                    for &h in s.held.iter().filter(|&&h| h >= a && h <= b) {
                        builder = builder.pin(h - a);
                    }
                }
            }
        }
        // A load on a vertex shared by two segments (an interior clamp) goes to the first.
        let owns = |v: usize| v >= a && (v < b || b == n_edges);
        for &(v, f) in &forces {
            if owns(v) {
                builder = builder.point_force(v - a, f);
            }
        }
        for &(v, m) in &moments {
            if owns(v) {
                builder = builder.point_moment(v - a, m);
            }
        }
        let seg_path = if single {
            path.to_string()
        } else {
            format!("{path} (part between vertices {a} and {b})")
        };
        let rod = builder.build().map_err(|e| {
            let msg = e.to_string();
            if msg.contains("rigid body") {
                SceneError::new(
                    format!("{path}.supports"),
                    format!(
                        "{seg_path} can move as a rigid body: add a clamp, or pins/clips on at least three non-collinear vertices"
                    ),
                )
            } else {
                SceneError::model(seg_path.clone(), e)
            }
        })?;
        check_no_free_motion(path, &seg_path, &rod, params)?;
        segments.push(Segment {
            rod,
            first_vertex: a,
        });
    }
    Ok(CompiledRod {
        name,
        n_edges,
        segments,
        supports,
        display_radius,
        properties,
    })
}
