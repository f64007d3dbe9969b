//! Point loads on a rod: dead forces on vertices and moments on edges, their validation and
//! their lumping with gravity into nodal forces.

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::moment::MomentLoad;
use super::state::RodState;

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

/// Errors name the load whose vertex does not exist on a rod of `n` edges or whose value is
/// not finite.
pub(super) fn validate_point_loads(
    forces: &[PointForce],
    moments: &[PointMoment],
    n: usize,
) -> Result<(), ModelError> {
    for pf in forces {
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
    for pm in moments {
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
    Ok(())
}

/// Dead nodal forces (N) at load factor 1: each vertex's lumped weight plus its point forces.
pub(super) fn nodal_forces(masses: &[f64], gravity: Vec3, forces: &[PointForce]) -> Vec<Vec3> {
    let mut f: Vec<Vec3> = masses.iter().map(|&m| gravity * m).collect();
    for pf in forces {
        f[pf.vertex] += pf.force;
    }
    f
}

/// The point moments as loads on edges (the edge starting at the vertex; the last edge for
/// the last vertex), split against the rest tangents of `rest`, the rod's rest state.
pub(super) fn moment_loads(moments: &[PointMoment], rest: &RodState) -> Vec<MomentLoad> {
    let n = rest.thetas().len();
    moments
        .iter()
        .map(|pm| {
            let edge = pm.vertex.min(n - 1);
            MomentLoad::new(edge, pm.moment, &rest.material_frame(edge))
        })
        .collect()
}
