//! The tensor-product B-spline patch of a rectangular strip: knot vectors along the length
//! (u = x ∈ [0, L], graded toward the clamp like the other models' meshes) and across the
//! width (v = z ∈ [−w/2, w/2], uniform), the control net, and the tensor-product basis on an
//! element.
//!
//! The rest control points sit at the Greville abscissae, (ξ*_i, 0, η*_j): B-splines reproduce
//! linear maps, so the rest surface is exactly the flat rectangle r̄(u, v) = (u, 0, v) and the
//! parameters are arc lengths (ā = I).

use crate::error::ModelError;
use crate::geometry::Vec3;

use super::basis::KnotVector;

/// Index of a basis-function derivative in a [`TensorBasis`] entry: value, ∂/∂u, ∂/∂v,
/// ∂²/∂u², ∂²/∂u∂v, ∂²/∂v².
pub const VALUE: usize = 0;
/// ∂/∂u.
pub const DU: usize = 1;
/// ∂/∂v.
pub const DV: usize = 2;
/// ∂²/∂u².
pub const DUU: usize = 3;
/// ∂²/∂u∂v.
pub const DUV: usize = 4;
/// ∂²/∂v².
pub const DVV: usize = 5;

/// Value and derivatives (see [`VALUE`] … [`DVV`]) of one tensor-product basis function.
pub type TensorBasis = [f64; 6];

/// The patch: knot vectors and the control net (control point (i, j) — i along the length,
/// j across — has index i·n_v + j).
#[derive(Clone, Debug, PartialEq)]
pub struct StripPatch {
    /// Knot vector along the length (parameter u = x, m).
    pub knots_u: KnotVector,
    /// Knot vector across the width (parameter v = z, m).
    pub knots_v: KnotVector,
    /// Rest control points (m).
    pub rest_points: Vec<Vec3>,
}

impl StripPatch {
    /// A flat strip of degree `degree` in both directions with element boundaries `stations`
    /// along the length (increasing from 0 to L) and `n_width` equal elements across `width`.
    pub fn new(
        degree: usize,
        stations: &[f64],
        width: f64,
        n_width: usize,
    ) -> Result<Self, ModelError> {
        let knots_u = KnotVector::open(degree, stations)?;
        let across: Vec<f64> = (0..=n_width)
            .map(|j| -0.5 * width + width * j as f64 / n_width as f64)
            .collect();
        let knots_v = KnotVector::open(degree, &across)?;
        let (gu, gv) = (knots_u.greville(), knots_v.greville());
        let rest_points = gu
            .iter()
            .flat_map(|&x| gv.iter().map(move |&z| Vec3::new(x, 0.0, z)))
            .collect();
        Ok(Self {
            knots_u,
            knots_v,
            rest_points,
        })
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.knots_u.degree()
    }

    /// Control points along the length.
    pub fn n_u(&self) -> usize {
        self.knots_u.n_functions()
    }

    /// Control points across the width.
    pub fn n_v(&self) -> usize {
        self.knots_v.n_functions()
    }

    /// Index of control point (i, j).
    pub fn control(&self, i: usize, j: usize) -> usize {
        i * self.n_v() + j
    }

    /// Row (position along the length) of control point `c`.
    pub fn row(&self, c: usize) -> usize {
        c / self.n_v()
    }

    /// Elements along the length and across the width.
    pub fn n_elements(&self) -> (usize, usize) {
        (self.knots_u.n_elements(), self.knots_v.n_elements())
    }

    /// The element containing (u, v) (clamped to the patch).
    pub fn element_of(&self, u: f64, v: f64) -> (usize, usize) {
        (self.knots_u.element_of(u), self.knots_v.element_of(v))
    }

    /// The (p+1)² control points of element (eu, ev) and their tensor-product basis at (u, v),
    /// in the order a·(p+1) + b (a along the length). `out` is cleared and filled.
    pub fn basis_at(
        &self,
        (eu, ev): (usize, usize),
        u: f64,
        v: f64,
        out: &mut Vec<(usize, TensorBasis)>,
    ) {
        out.clear();
        let p = self.degree();
        let bu = self.knots_u.evaluate(eu, u);
        let bv = self.knots_v.evaluate(ev, v);
        let (fu, fv) = (
            self.knots_u.first_function(eu),
            self.knots_v.first_function(ev),
        );
        for (a, nu) in bu.iter().enumerate().take(p + 1) {
            for (b, nv) in bv.iter().enumerate().take(p + 1) {
                out.push((
                    self.control(fu + a, fv + b),
                    [
                        nu[0] * nv[0],
                        nu[1] * nv[0],
                        nu[0] * nv[1],
                        nu[2] * nv[0],
                        nu[1] * nv[1],
                        nu[0] * nv[2],
                    ],
                ));
            }
        }
    }

    /// The surface point at (u, v) for control points `points`.
    pub fn point(&self, points: &[Vec3], u: f64, v: f64) -> Vec3 {
        let mut basis = Vec::new();
        self.basis_at(self.element_of(u, v), u, v, &mut basis);
        basis
            .iter()
            .fold(Vec3::zeros(), |acc, (c, n)| acc + points[*c] * n[VALUE])
    }
}
