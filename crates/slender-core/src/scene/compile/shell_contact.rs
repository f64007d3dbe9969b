//! The contact parameters of the scene's shell strips: every strip is held off every obstacle
//! by its mid-surface's half-thickness h/2 (the sites of `contact::shell_sites`: its mesh
//! vertices, weighted by area), with the scene's activation distance and a barrier stiffness
//! per unit area. Checked against the strips' starts: no strip may start inside an obstacle,
//! nor have a clamp posed inside one.

use std::sync::Arc;

use nalgebra::Vector3;

use crate::contact::{ContactParams, ContactSites, Obstacle};
use crate::shell::Shell;

use super::super::error::SceneError;
use super::super::shells::{CompiledShell, StripModel};
use super::super::spec::{ContactSpec, Scene};

/// The contact parameters of every strip of `scene` (in the order of `shells`), with the
/// obstacles `obstacles` (named `names`) and the activation distance `activation` (m).
///
/// The barrier stiffness (N/m³) is `contact.shell_stiffness`, or the one at which the
/// heaviest strip's weight per area p = ρ h |g| rests it at ĝ/2 (without gravity, the
/// pressure D/L³ of the stiffest strip): [`ContactParams::for_area_load`], as rods' comes from
/// their weight per length.
///
/// Errors: self-contact in a scene with strips (`contact.self_contact`: it acts on rods
/// only), a B-spline strip (`shells[i].model`: contact is modelled on the mid-edge strip's
/// vertices only), a bad `contact.shell_stiffness`, a strip starting inside an obstacle
/// (`obstacles[o]`), a clamp posed inside one (`shells[i].clamps[k]`).
pub(crate) fn shell_contact_params(
    scene: &Scene,
    spec: &ContactSpec,
    shells: &[CompiledShell],
    obstacles: &[Arc<dyn Obstacle>],
    names: &[String],
    activation: f64,
) -> Result<Vec<ContactParams>, SceneError> {
    if shells.is_empty() {
        return Ok(Vec::new());
    }
    if spec.self_contact {
        return Err(SceneError::new(
            "contact.self_contact",
            "true in a scene with [[shells]]: self-contact acts on rods only (cables touching themselves and each other); a strip touches obstacles only. Set it to false, or solve the strips in a scene of their own",
        ));
    }
    let mut models = Vec::with_capacity(shells.len());
    for (i, c) in shells.iter().enumerate() {
        match &c.model {
            StripModel::Midedge(s) => models.push(s),
            StripModel::Bspline(_) => {
                return Err(SceneError::new(
                    format!("shells[{i}].model"),
                    "\"bspline\" with [[obstacles]]: contact acts on the mid-edge strip's vertices, and a B-spline patch's control points are not on its surface (outside a plane they keep the surface outside, by the convex hull; not outside a curved obstacle). Use model = \"midedge\" (the default) in a scene with obstacles",
                ));
            }
        }
    }
    let area_load = match spec.shell_stiffness {
        Some(k) => {
            if !(k.is_finite() && k > 0.0) {
                return Err(SceneError::new(
                    "contact.shell_stiffness",
                    format!("{k}: must be finite and > 0 (N/m³)"),
                ));
            }
            // The area load this stiffness rests at ĝ/2 (inverse of for_area_load).
            k * activation * (0.5 + std::f64::consts::LN_2)
        }
        None => {
            let g = Vector3::from(scene.gravity).norm();
            let load = |s: &Shell| {
                let p = s.properties();
                if g > 0.0 {
                    p.density * p.thickness * g
                } else {
                    p.bending_stiffness() / p.length.powi(3)
                }
            };
            models.iter().map(|s| load(s)).fold(0.0, f64::max)
        }
    };
    let mut params = Vec::with_capacity(shells.len());
    for (i, (c, shell)) in shells.iter().zip(&models).enumerate() {
        let half = 0.5 * shell.properties().thickness;
        let p = ContactParams::for_area_load(half, activation, area_load);
        p.validate()
            .map_err(|e| SceneError::model("contact.shell_stiffness", e))?;
        // Where the strip starts (flat, its clamps at rest), and where its clamps hold their
        // edges once posed: no site may be inside an obstacle at either.
        let rest = shell.rest_state();
        let columns = shell.mesh().n_width + 1;
        for site in shell.contact_sites() {
            let x = shell.site_position(&rest, &site);
            for (o, obstacle) in obstacles.iter().enumerate() {
                let distance = obstacle.surface(&x).distance;
                if !(distance - half > 0.0) {
                    return Err(SceneError::new(
                        format!("obstacles[{o}]"),
                        format!(
                            "strip {:?} starts inside {:?}: its vertex at station {}, column {} at {:?} (the strip lies flat in y = 0 at rest) is {distance:.3e} m from the surface, not more than its half-thickness {half} m (move the obstacle)",
                            c.name,
                            names[o],
                            site.vertex / columns,
                            site.vertex % columns,
                            [x.x, x.y, x.z],
                        ),
                    ));
                }
            }
        }
        for (k, clamp) in c.clamps.iter().enumerate() {
            for &v in &shell.mesh().end_vertices[clamp.end.index()] {
                let x = clamp.pose.position(&shell.mesh().rest_positions[v]);
                for (o, obstacle) in obstacles.iter().enumerate() {
                    let distance = obstacle.surface(&x).distance;
                    if !(distance - half > 0.0) {
                        return Err(SceneError::new(
                            format!("shells[{i}].clamps[{k}]"),
                            format!(
                                "holds the strip's edge inside {:?} (obstacles[{o}]): its vertex at {:?} is {distance:.3e} m from the surface, not more than the half-thickness {half} m (change offset or rotate)",
                                names[o],
                                [x.x, x.y, x.z],
                            ),
                        ));
                    }
                }
            }
        }
        params.push(p);
    }
    Ok(params)
}
