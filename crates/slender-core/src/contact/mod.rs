//! Contact of slender structures with their surroundings (issue 14).
//!
//! [`obstacle`] is the one interface every rigid obstacle implements (closest-point queries with
//! the derivatives an exact Hessian needs, and the time of impact that caps a step);
//! [`plane`], [`sphere`], [`cylinder`], [`cuboid`], [`torus`] (a ring a cable runs through: a
//! sliding clip) and [`mesh`] are obstacles. [`barrier`] is the contact energy of
//! one gap, [`sites`] says where a model's contact points are (its vertices) and which DOFs
//! move them ([`shell_sites`]: the mid-edge shell strip's vertices, weighted by area), and [`problem`] adds the contacts to any model as an
//! [`EquilibriumProblem`](crate::solver::EquilibriumProblem) for the unchanged solver.

pub mod barrier;
pub mod broad_phase;
pub mod cuboid;
pub mod cylinder;
pub mod edge_penetration;
pub mod friction;
pub mod frictional_step;
pub mod mesh;
pub mod obstacle;
pub mod plane;
pub mod problem;
mod radii;
pub mod segment_distance;
pub mod shell_sites;
pub mod sites;
pub mod sphere;
pub mod torus;

pub use cuboid::Cuboid;
pub use cylinder::Cylinder;
pub use friction::{Friction, FrictionUpdate};
pub use frictional_step::step_with_friction;
pub use mesh::TriangleMesh;
pub use obstacle::{Obstacle, SurfacePoint};
pub use plane::Plane;
pub use problem::{
    ContactForce, ContactParams, ContactProblem, SegmentContact, SegmentSide, CONTACT, FRICTION,
};
pub use sites::{ContactEdge, ContactSite, ContactSites, SiteDof};
pub use sphere::Sphere;
pub use torus::Torus;

use nalgebra::Vector3;

/// The largest α ∈ [0, 1] such that the segment r + [0, α]·dr stays at distance ≥ `radius`
/// from the origin (|r| ≥ `radius` assumed): the time of impact against a ball (or, in the
/// plane across its axis, a cylinder).
pub(crate) fn ball_time_of_impact(r: Vector3<f64>, dr: Vector3<f64>, radius: f64) -> f64 {
    // |r + α dr|² = radius²: a α² + 2 b α + c = 0 with c ≥ 0.
    let a = dr.norm_squared();
    let b = r.dot(&dr);
    let c = r.norm_squared() - radius * radius;
    if a == 0.0 || b >= 0.0 || c <= 0.0 {
        // Not approaching, or already at the clearance (then no step inward is allowed).
        return if c <= 0.0 && b < 0.0 { 0.0 } else { 1.0 };
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return 1.0; // The line passes outside.
    }
    // Smaller root, in the cancellation-free form c / (−b + √disc).
    let alpha = c / (-b + disc.sqrt());
    alpha.clamp(0.0, 1.0)
}

/// Conservative-advancement iterations of [`conservative_advancement`].
const ADVANCE_ITERATIONS: usize = 64;

/// The time of impact of the segment p + [0, 1]·dp against the surface whose exact signed
/// distance is `distance` (1-Lipschitz), for a point that keeps `clearance` (m) at α = 0:
/// conservative advancement, a move of the current distance minus the clearance never
/// reaching the inflated surface. Returns α ∈ [0, 1] (stops once the room left is 1e-3 of the
/// room at the start, or after [`ADVANCE_ITERATIONS`] moves).
pub(crate) fn conservative_advancement(
    distance: impl Fn(&Vector3<f64>) -> f64,
    p: &Vector3<f64>,
    dp: &Vector3<f64>,
    clearance: f64,
) -> f64 {
    let length = dp.norm();
    if length == 0.0 {
        return 1.0;
    }
    let mut alpha = 0.0;
    let mut room0: Option<f64> = None;
    for _ in 0..ADVANCE_ITERATIONS {
        let room = distance(&(p + dp * alpha)) - clearance;
        // The room is positive at the start: the point keeps at least its clearance.
        let start = *room0.get_or_insert(room);
        if room <= 1e-3 * start {
            return alpha;
        }
        alpha += room / length;
        if alpha >= 1.0 {
            return 1.0;
        }
    }
    alpha
}

/// `p` if every coordinate is finite, else an error naming `field` (an obstacle's point or
/// centre, m).
pub(crate) fn finite_point(
    field: &str,
    p: Vector3<f64>,
) -> Result<Vector3<f64>, crate::ModelError> {
    if p.iter().all(|v| v.is_finite()) {
        Ok(p)
    } else {
        Err(crate::ModelError::structure(
            field,
            format!("must be finite, got {p:?}"),
        ))
    }
}

/// The unit vector along `v` (any finite, non-zero length), else an error naming `field` (an
/// obstacle's axis or normal).
pub(crate) fn unit_direction(
    field: &str,
    v: Vector3<f64>,
) -> Result<Vector3<f64>, crate::ModelError> {
    let length = v.norm();
    if length.is_finite() && length > 0.0 {
        Ok(v / length)
    } else {
        Err(crate::ModelError::structure(
            field,
            format!("must be finite and non-zero, got {v:?}"),
        ))
    }
}

/// Test aid: the distance's gradient (the normal) and the normal's derivative at `p` against
/// central differences (step 1e-6 m), to `tol_normal` and `tol_curvature`.
#[cfg(test)]
pub(crate) fn assert_surface_derivatives(
    o: &dyn Obstacle,
    p: &Vector3<f64>,
    tol_normal: f64,
    tol_curvature: f64,
) {
    let s = o.surface(p);
    let h = 1e-6;
    for k in 0..3 {
        let mut e = Vector3::zeros();
        e[k] = h;
        let (sp, sm) = (o.surface(&(p + e)), o.surface(&(p - e)));
        let fd = (sp.distance - sm.distance) / (2.0 * h);
        assert!(
            (fd - s.normal[k]).abs() < tol_normal,
            "{p:?} ∂{k}: {fd} vs {}",
            s.normal[k]
        );
        let fd_n = (sp.normal - sm.normal) / (2.0 * h);
        for i in 0..3 {
            assert!(
                (fd_n[i] - s.normal_derivative[(i, k)]).abs() < tol_curvature,
                "{p:?} ∂n{i}/∂{k}: {} vs {}",
                fd_n[i],
                s.normal_derivative[(i, k)]
            );
        }
    }
}
