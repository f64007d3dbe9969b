//! The scene's obstacles and `[contact]` table: obstacles built from their shapes, and the
//! contact parameters of every structure (its radius, the activation distance and the barrier
//! stiffness), checked against the structures' rest states (no cable may start inside an
//! obstacle, or, with self-contact, intersecting itself).

use std::sync::Arc;

use nalgebra::{Rotation3, Vector3};

use crate::contact::{
    ContactParams, ContactProblem, ContactSites, Cuboid, Cylinder, Obstacle, Plane, Sphere, Torus,
    TriangleMesh,
};
use crate::error::ModelError;
use crate::structure::Structure;

use super::super::error::SceneError;
use super::super::shells::CompiledShell;
use super::super::spec::{ObstacleShapeSpec, ObstacleSpec, Scene, SectionSpec};
use super::rod::CompiledRod;

/// Default activation distance, as a fraction of the longest rod's or strip's length.
pub const DEFAULT_ACTIVATION: f64 = 1e-6;

/// The compiled obstacles and contact parameters of a scene.
#[derive(Clone, Debug)]
pub struct CompiledContact {
    /// The obstacles, in the order of the file (shared by every solve).
    pub obstacles: Vec<Arc<dyn Obstacle>>,
    /// Their names (`obstacle<i>` by default).
    pub names: Vec<String>,
    /// Contact parameters per structure (its `radius` is the largest of its rods'; each
    /// member keeps its own rod's, see `radii`).
    pub params: Vec<ContactParams>,
    /// Per structure, per member: its rod's contact radius (m), for
    /// [`ContactProblem::with_radii`] — a thin and a thick cable in one structure (with
    /// self-contact every rod is in one) rest on obstacles at their own radii and touch each
    /// other at the sum of theirs.
    pub radii: Vec<Vec<f64>>,
    /// Per rod: its contact radius (m).
    pub rod_radii: Vec<f64>,
    /// Contact parameters per shell strip, in the order of `shells` (radius h/2, stiffness
    /// per unit area: see [`shell_contact`](super::shell_contact)).
    pub shell_params: Vec<ContactParams>,
    /// Per structure, per member: its rod (index) and the arc length (m) of its first vertex
    /// along the rod — the chains of [`ContactProblem::with_chains`], so that self-contact
    /// measures "near along the cable" by rod (across interior clamps).
    pub chains: Vec<Vec<(usize, f64)>>,
}

fn finite3(path: String, v: [f64; 3]) -> Result<Vector3<f64>, SceneError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vector3::from(v))
    } else {
        Err(SceneError::new(
            path,
            format!("{v:?}: every component must be a finite number"),
        ))
    }
}

/// The error of a model error raised while building `obstacles[i]`: the field it names, under
/// the shape's path.
fn shape_error(path: &str, e: ModelError) -> SceneError {
    match e {
        ModelError::InvalidParameter { ref field, .. } if field == "friction" => {
            SceneError::new(format!("{path}.friction"), e.to_string())
        }
        ModelError::InvalidParameter { ref field, .. }
        | ModelError::InvalidStructure { ref field, .. } => {
            let field = field.clone();
            let msg = match &e {
                ModelError::InvalidStructure { reason, .. } => reason.clone(),
                _ => e.to_string(),
            };
            let field = if field == "rotation" {
                "rotate".to_string()
            } else {
                field
            };
            SceneError::new(format!("{path}.shape.{field}"), msg)
        }
    }
}

/// Builds one obstacle.
pub(crate) fn obstacle(path: &str, spec: &ObstacleSpec) -> Result<Arc<dyn Obstacle>, SceneError> {
    let mu = spec.friction;
    if !(mu.is_finite() && mu >= 0.0) {
        return Err(SceneError::new(
            format!("{path}.friction"),
            format!("{mu}: must be finite and >= 0 (Coulomb coefficient μ)"),
        ));
    }
    let sp = format!("{path}.shape");
    let positive = |field: &str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(SceneError::new(
                format!("{sp}.{field}"),
                format!("{v}: must be finite and > 0 (m)"),
            ))
        }
    };
    let nonzero = |field: &str, v: [f64; 3]| -> Result<Vector3<f64>, SceneError> {
        let x = finite3(format!("{sp}.{field}"), v)?;
        if x.norm() > 0.0 {
            Ok(x)
        } else {
            Err(SceneError::new(
                format!("{sp}.{field}"),
                format!("{v:?}: must be non-zero (a direction)"),
            ))
        }
    };
    let out: Arc<dyn Obstacle> = match &spec.shape {
        ObstacleShapeSpec::Plane { point, normal } => {
            let p = finite3(format!("{sp}.point"), *point)?;
            let n = nonzero("normal", *normal)?;
            Arc::new(Plane::new(p, n, mu).map_err(|e| shape_error(path, e))?)
        }
        ObstacleShapeSpec::Sphere { center, radius } => {
            let c = finite3(format!("{sp}.center"), *center)?;
            positive("radius", *radius)?;
            Arc::new(Sphere::new(c, *radius, mu).map_err(|e| shape_error(path, e))?)
        }
        ObstacleShapeSpec::Cylinder {
            point,
            axis,
            radius,
        } => {
            let p = finite3(format!("{sp}.point"), *point)?;
            let a = nonzero("axis", *axis)?;
            positive("radius", *radius)?;
            Arc::new(Cylinder::new(p, a, *radius, mu).map_err(|e| shape_error(path, e))?)
        }
        ObstacleShapeSpec::Torus {
            center,
            axis,
            radius,
            tube_radius,
        } => {
            let c = finite3(format!("{sp}.center"), *center)?;
            let a = nonzero("axis", *axis)?;
            positive("radius", *radius)?;
            positive("tube_radius", *tube_radius)?;
            Arc::new(Torus::new(c, a, *radius, *tube_radius, mu).map_err(|e| shape_error(path, e))?)
        }
        ObstacleShapeSpec::Box {
            center,
            size,
            rotate,
        } => {
            let c = finite3(format!("{sp}.center"), *center)?;
            for (k, s) in size.iter().enumerate() {
                positive(&format!("size[{k}]"), *s)?;
            }
            let r = finite3(format!("{sp}.rotate"), *rotate)?;
            Arc::new(
                Cuboid::new(c, Vector3::from(*size), Rotation3::new(r), mu)
                    .map_err(|e| shape_error(path, e))?,
            )
        }
        ObstacleShapeSpec::Mesh {
            file,
            vertices,
            triangles,
        } => {
            if let (Some(file), true) = (file, vertices.is_empty()) {
                return Err(SceneError::new(
                    format!("{sp}.file"),
                    format!(
                        "the mesh file {file:?} was not read: the slender binary (solve, view) loads mesh files; elsewhere give `vertices` and `triangles` inline"
                    ),
                ));
            }
            let mut vs = Vec::with_capacity(vertices.len());
            for (k, v) in vertices.iter().enumerate() {
                vs.push(finite3(format!("{sp}.vertices[{k}]"), *v)?);
            }
            Arc::new(
                TriangleMesh::new(vs, triangles.clone(), mu).map_err(|e| shape_error(path, e))?,
            )
        }
    };
    Ok(out)
}

/// The contact radius (m) of rod `i`: `contact_radius`, or the section's.
fn rod_radius(scene: &Scene, i: usize) -> Result<f64, SceneError> {
    let spec = &scene.rods[i];
    let path = format!("rods[{i}].contact_radius");
    let r = match (spec.contact_radius, &spec.section) {
        (Some(r), _) => r,
        (None, SectionSpec::Circle { diameter }) => 0.5 * diameter,
        (None, SectionSpec::Rectangle { width, height }) => 0.5 * width.max(*height),
        (None, SectionSpec::Stiffness { .. }) => {
            return Err(SceneError::new(
                path,
                "missing: a rod with section shape = \"stiffness\" needs `contact_radius` (m, > 0) when the scene has obstacles or self-contact",
            ))
        }
    };
    if !(r.is_finite() && r > 0.0) {
        return Err(SceneError::new(
            path,
            format!("{r}: must be finite and > 0 (m)"),
        ));
    }
    Ok(r)
}

/// Validates the obstacles and `[contact]` of `scene` and the contact parameters of every
/// structure and shell strip; `None` when the scene has neither obstacles nor self-contact.
/// Checks the structures' and strips' rest states: a cable or strip starting inside an
/// obstacle is an error naming it.
pub(crate) fn compile_contact(
    scene: &Scene,
    rods: &[CompiledRod],
    structures: &[Structure],
    shells: &[CompiledShell],
) -> Result<Option<CompiledContact>, SceneError> {
    let spec = scene.contact.clone().unwrap_or_default();
    if scene.obstacles.is_empty() && !spec.self_contact {
        return Ok(None);
    }
    let mut obstacles = Vec::with_capacity(scene.obstacles.len());
    let mut names: Vec<String> = Vec::with_capacity(scene.obstacles.len());
    for (i, o) in scene.obstacles.iter().enumerate() {
        let path = format!("obstacles[{i}]");
        let name = o.name.clone().unwrap_or_else(|| format!("obstacle{i}"));
        super::check_name(&format!("{path}.name"), &name)?;
        if names.contains(&name) {
            return Err(SceneError::new(
                format!("{path}.name"),
                format!("{name:?} is used by another obstacle; names must be unique"),
            ));
        }
        names.push(name);
        obstacles.push(obstacle(&path, o)?);
    }
    let longest = structures
        .iter()
        .flat_map(|s| s.members().iter().map(|m| m.length()))
        .fold(0.0, f64::max);
    // Lengths of whole rods (a rod split at interior clamps counts whole).
    let rod_length = |r: &CompiledRod| r.node_arclengths.last().copied().unwrap_or(0.0);
    let longest = rods.iter().map(rod_length).fold(longest, f64::max);
    let longest = shells.iter().map(|s| s.length()).fold(longest, f64::max);
    let activation = spec.activation.unwrap_or(DEFAULT_ACTIVATION * longest);
    if !(activation.is_finite() && activation > 0.0) {
        return Err(SceneError::new(
            "contact.activation",
            format!("{activation}: must be finite and > 0 (m)"),
        ));
    }
    let line_load = match spec.stiffness {
        Some(k) => {
            if !(k.is_finite() && k > 0.0) {
                return Err(SceneError::new(
                    "contact.stiffness",
                    format!("{k}: must be finite and > 0 (N/m²)"),
                ));
            }
            // The line load that this stiffness rests at ĝ/2 (inverse of for_line_load).
            k * activation * (0.5 + std::f64::consts::LN_2)
        }
        None => {
            let g = Vector3::from(scene.gravity).norm();
            if g > 0.0 {
                rods.iter()
                    .map(|r| r.properties.linear_density * g)
                    .fold(0.0, f64::max)
            } else {
                rods.iter()
                    .map(|r| {
                        let s = &r.properties.stiffness;
                        s.ei1.max(s.ei2) / rod_length(r).powi(3)
                    })
                    .fold(0.0, f64::max)
            }
        }
    };
    let mut radii = Vec::with_capacity(scene.rods.len());
    for i in 0..scene.rods.len() {
        radii.push(rod_radius(scene, i)?);
    }
    let mut params = Vec::with_capacity(structures.len());
    let mut chains = Vec::with_capacity(structures.len());
    let mut member_radii = Vec::with_capacity(structures.len());
    for (k, s) in structures.iter().enumerate() {
        let chain: Vec<(usize, f64)> = (0..s.members().len())
            .map(|m| {
                rods.iter()
                    .enumerate()
                    .find_map(|(r, rod)| {
                        rod.parts
                            .iter()
                            .find(|p| p.structure == k && p.member == m)
                            .map(|p| (r, rod.node_arclengths[p.first_vertex]))
                    })
                    .unwrap_or((rods.len() + m, 0.0))
            })
            .collect();
        let radius = rods
            .iter()
            .zip(&radii)
            .filter(|(r, _)| r.parts.iter().any(|p| p.structure == k))
            .map(|(_, &r)| r)
            .fold(0.0, f64::max);
        // Each member keeps its rod's radius (a member of no rod: the structure's largest).
        let member_radius: Vec<f64> = chain
            .iter()
            .map(|&(r, _)| radii.get(r).copied().unwrap_or(radius))
            .collect();
        let p = ContactParams {
            self_contact: spec.self_contact,
            ..ContactParams::for_line_load(radius, activation, line_load)
        };
        p.validate().map_err(|e| SceneError::model("contact", e))?;
        // A rod starting inside an obstacle: named by rod and vertex.
        let rest = s.rest_state();
        for site in s.contact_sites() {
            let x = s.site_position(rest, &site);
            let radius = member_radius[site.member];
            for (o, obstacle) in obstacles.iter().enumerate() {
                let gap = obstacle.surface(&x).distance - radius;
                if !(gap > 0.0) {
                    let (rod, vertex) = rods
                        .iter()
                        .find_map(|r| {
                            r.parts
                                .iter()
                                .find(|q| q.structure == k && q.member == site.member)
                                .map(|q| (r.name.as_str(), q.first_vertex + site.vertex))
                        })
                        .unwrap_or(("?", site.vertex));
                    return Err(SceneError::new(
                        format!("obstacles[{o}]"),
                        format!(
                            "rod {rod:?} starts inside {:?}: its vertex {vertex} at {:?} is {:.3e} m from the surface, less than its contact radius {radius} m (move the obstacle or the rod, or lower contact_radius)",
                            names[o],
                            [x.x, x.y, x.z],
                            gap + radius
                        ),
                    ));
                }
            }
        }
        ContactProblem::with_radii(
            s,
            obstacles.clone(),
            p,
            s.rest_state(),
            &chain,
            &member_radius,
        )
        .map_err(|e| match e {
            ModelError::InvalidStructure { field, reason } => {
                let path = if field == "self_contact" {
                    "contact.self_contact".to_string()
                } else {
                    field
                };
                let rods_of: Vec<&str> = rods
                    .iter()
                    .filter(|r| r.parts.iter().any(|p| p.structure == k))
                    .map(|r| r.name.as_str())
                    .collect();
                SceneError::new(
                    path,
                    format!("{reason} (structure of rods {})", rods_of.join(", ")),
                )
            }
            e => SceneError::model("contact", e),
        })?;
        params.push(p);
        chains.push(chain);
        member_radii.push(member_radius);
    }
    let shell_params = super::shell_contact::shell_contact_params(
        scene, &spec, shells, &obstacles, &names, activation,
    )?;
    Ok(Some(CompiledContact {
        obstacles,
        names,
        params,
        shell_params,
        chains,
        radii: member_radii,
        rod_radii: radii,
    }))
}
