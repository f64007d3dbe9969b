//! Contact of slender structures with their surroundings (issue 14).
//!
//! [`obstacle`] is the one interface every rigid obstacle implements (closest-point queries with
//! the derivatives an exact Hessian needs, and the time of impact that caps a step);
//! [`plane`], [`sphere`] and [`cylinder`] are obstacles. [`barrier`] is the contact energy of
//! one gap, [`sites`] says where a model's contact points are (its vertices) and which DOFs
//! move them ([`shell_sites`]: the mid-edge shell strip's vertices, weighted by area), and [`problem`] adds the contacts to any model as an
//! [`EquilibriumProblem`](crate::solver::EquilibriumProblem) for the unchanged solver.

pub mod barrier;
pub mod broad_phase;
pub mod cuboid;
pub mod cylinder;
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
