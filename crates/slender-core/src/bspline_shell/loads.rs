//! Point forces at material points of the surface: a dead force F at parameters (u, v) does
//! the work F·(r(u, v) − r̄(u, v)) = Σ_c N_c(u, v) F·(P_c − P̄_c), a linear function of the
//! control points.

use serde::{Deserialize, Serialize};

use crate::geometry::Vec3;

/// A dead force at a material point of the strip.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointLoad {
    /// Position along the length at rest, u ∈ [0, L] (m).
    pub u: f64,
    /// Position across the width at rest, v ∈ [−w/2, w/2] (m).
    pub v: f64,
    /// Force at load factor 1 (N).
    pub force: [f64; 3],
}

/// A point load with the basis weights of its control points.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PointLoadTerm {
    pub force: Vec3,
    /// (control point, N_c(u, v)).
    pub weights: Vec<(usize, f64)>,
}
