//! The interface of a rigid obstacle: where its surface is, seen from a point.

use nalgebra::{Matrix3, Vector3};

/// The surface of an obstacle seen from a query point p: the signed distance d(p) and its first
/// two derivatives, so that a contact energy or constraint built on d has an exact gradient
/// and Hessian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// Signed distance (m) from p to the surface: positive outside the obstacle, negative inside.
    pub distance: f64,
    /// ∇d: the outward unit normal at the closest surface point (dimensionless).
    pub normal: Vector3<f64>,
    /// ∇²d = ∂n/∂p (1/m): zero for a plane, (I − n nᵀ)/|p − c| outside a sphere of centre c.
    /// Symmetric; it is the curvature of the level set of d through p.
    pub normal_derivative: Matrix3<f64>,
}

impl SurfacePoint {
    /// The closest point of the surface (m): p − d n.
    pub fn closest(&self, p: &Vector3<f64>) -> Vector3<f64> {
        p - self.normal * self.distance
    }
}

/// A rigid obstacle: a closed form or a mesh that answers closest-point queries.
///
/// `Send + Sync` so that the binary may query obstacles from several threads; the core itself
/// spawns none.
pub trait Obstacle: std::fmt::Debug + Send + Sync {
    /// The surface seen from `p` (m). Where d is not differentiable (the medial axis of a box,
    /// the axis of a cylinder) any one-sided value is returned; contacts stay far from there
    /// because the rod's radius is small against the obstacle.
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint;

    /// The largest α ∈ [0, 1] such that the whole segment p + [0, α]·dp keeps a distance of
    /// at least `clearance` (m, ≥ 0) from the surface, given that p does (the step cap that
    /// keeps a contact barrier's gaps positive; no tunnelling through thin parts).
    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64;

    /// True if [`Self::surface`]'s distance is signed (negative inside a solid); false for a
    /// surface without an inside (a mesh: an open panel), which a segment can only cross.
    fn signed(&self) -> bool {
        true
    }

    /// For a surface without an inside ([`Self::signed`] false): a point (m) where one of the
    /// surface's own edges passes through the triangle `corners` (m), or `None`. Two triangles
    /// that cross have an edge of one through the other, so this and [`Self::time_of_impact`]
    /// along the triangle's edges find every crossing of a shell face and the surface (a
    /// panel's corner poking through a face's interior is seen only here). Solids answer `None`:
    /// a face's depth inside them is searched instead.
    fn edge_through_triangle(&self, _corners: &[Vector3<f64>; 3]) -> Option<Vector3<f64>> {
        None
    }

    /// Coulomb friction coefficient μ ≥ 0 of this obstacle's surface (dimensionless; μ_s = μ_d).
    fn friction(&self) -> f64;

    /// Axis-aligned bounding box (min, max corners, m) for a broad phase; infinite components for
    /// unbounded obstacles such as a plane.
    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>);
}
