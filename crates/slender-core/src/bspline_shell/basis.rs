//! B-spline basis functions of one parameter on an open knot vector.
//!
//! Hand-written (Cox–de Boor recursion and its derivative formula, Piegl & Tiller, *The NURBS
//! Book* §2.2–2.3): the shell needs values and first and second derivatives of the p + 1
//! functions that live on one knot span, at fixed quadrature points, which is a few dozen
//! lines and not worth a dependency.
//!
//! An *open* knot vector repeats its end knots p + 1 times, so the curve interpolates its
//! first and last control points and its end tangent is fixed by the first (last) two: that
//! is what makes the clamp exact (design.md §3.4).

use crate::error::ModelError;

/// Largest degree supported.
pub const MAX_DEGREE: usize = 6;

/// Values and first and second derivatives of the p + 1 basis functions that are non-zero on
/// one knot span, at one parameter value: `[k][d]` is the d-th derivative of the span's k-th
/// function (global index [`KnotVector::first_function`] + k); entries k > p are zero.
pub type SpanBasis = [[f64; 3]; MAX_DEGREE + 1];

/// An open knot vector of degree p over increasing breakpoints.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    degree: usize,
    /// All knots, the end knots repeated p + 1 times.
    knots: Vec<f64>,
    /// The distinct knots (element boundaries), increasing.
    breakpoints: Vec<f64>,
}

impl KnotVector {
    /// Degree `degree` (1 ≤ p ≤ [`MAX_DEGREE`]) over `breakpoints` (at least two, strictly increasing, finite):
    /// one element per interval, C^(p−1) across interior breakpoints.
    pub fn open(degree: usize, breakpoints: &[f64]) -> Result<Self, ModelError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(ModelError::structure(
                "degree",
                format!("got {degree}; must be in 1..={MAX_DEGREE}"),
            ));
        }
        if breakpoints.len() < 2 {
            return Err(ModelError::structure(
                "breakpoints",
                format!("got {}; need at least 2", breakpoints.len()),
            ));
        }
        if breakpoints.iter().any(|b| !b.is_finite())
            || breakpoints.windows(2).any(|w| !(w[1] > w[0]))
        {
            return Err(ModelError::structure(
                "breakpoints",
                "must be finite and strictly increasing",
            ));
        }
        let (first, last) = (breakpoints[0], breakpoints[breakpoints.len() - 1]);
        let mut knots = vec![first; degree + 1];
        knots.extend_from_slice(&breakpoints[1..breakpoints.len() - 1]);
        knots.extend(std::iter::repeat_n(last, degree + 1));
        Ok(Self {
            degree,
            knots,
            breakpoints: breakpoints.to_vec(),
        })
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Number of elements (knot spans of non-zero length).
    pub fn n_elements(&self) -> usize {
        self.breakpoints.len() - 1
    }

    /// Number of basis functions (control points): elements + p.
    pub fn n_functions(&self) -> usize {
        self.n_elements() + self.degree
    }

    /// The element boundaries.
    pub fn breakpoints(&self) -> &[f64] {
        &self.breakpoints
    }

    /// Parameter interval [a, b] of element `e`.
    pub fn element_bounds(&self, e: usize) -> (f64, f64) {
        (self.breakpoints[e], self.breakpoints[e + 1])
    }

    /// Global index of the first of the p + 1 functions that are non-zero on element `e`.
    pub fn first_function(&self, e: usize) -> usize {
        e
    }

    /// The element containing parameter `x` (the last one at the end point; values outside
    /// the range are attributed to the nearest element).
    pub fn element_of(&self, x: f64) -> usize {
        let n = self.n_elements();
        self.breakpoints[1..n].partition_point(|&b| b <= x)
    }

    /// Greville abscissae: the parameter "position" of each control point, (t_{i+1} + … +
    /// t_{i+p})/p. Control points placed at x(ξ*_i) reproduce the linear map x(ξ) exactly.
    pub fn greville(&self) -> Vec<f64> {
        (0..self.n_functions())
            .map(|i| self.greville_at(i))
            .collect()
    }

    /// The Greville abscissa of function `i` (see [`Self::greville`]).
    pub fn greville_at(&self, i: usize) -> f64 {
        let p = self.degree;
        self.knots[i + 1..=i + p].iter().sum::<f64>() / p as f64
    }

    /// The integral of each basis function over the whole parameter range:
    /// (t_{i+p+1} − t_i)/(p + 1).
    pub fn integrals(&self) -> Vec<f64> {
        let p = self.degree;
        (0..self.n_functions())
            .map(|i| (self.knots[i + p + 1] - self.knots[i]) / (p + 1) as f64)
            .collect()
    }

    /// Values and first two derivatives of the functions non-zero on element `e` at `x`.
    /// `x` may lie slightly outside the element (the polynomial piece is extended).
    pub fn evaluate(&self, e: usize, x: f64) -> SpanBasis {
        let p = self.degree;
        // Index of the span's left knot in the full vector.
        let span = e + p;
        let t = &self.knots;
        // table[q][k] = N_{span−q+k, q}(x): the degree-q functions non-zero on the span.
        let mut table = [[0.0; 8]; 8];
        table[0][0] = 1.0;
        for q in 1..=p {
            for k in 0..=q {
                let j = span + k - q; // global index of N_{j,q}
                let left = if k >= 1 {
                    let den = t[j + q] - t[j];
                    if den > 0.0 {
                        (x - t[j]) / den * table[q - 1][k - 1]
                    } else {
                        0.0
                    }
                } else {
                    0.0
                };
                let right = if k < q {
                    let den = t[j + q + 1] - t[j + 1];
                    if den > 0.0 {
                        (t[j + q + 1] - x) / den * table[q - 1][k]
                    } else {
                        0.0
                    }
                } else {
                    0.0
                };
                table[q][k] = left + right;
            }
        }
        // d-th derivative of N_{j,q} from the degree q − d functions (derivative formula
        // N'_{j,q} = q [N_{j,q−1}/(t_{j+q} − t_j) − N_{j+1,q−1}/(t_{j+q+1} − t_{j+1})]).
        fn derivative(
            t: &[f64],
            table: &[[f64; 8]; 8],
            span: usize,
            d: usize,
            q: usize,
            j: usize,
        ) -> f64 {
            // N_{j,q} is non-zero on the span only for span − q ≤ j ≤ span.
            if j + q < span || j > span {
                return 0.0;
            }
            if d == 0 {
                return table[q][j + q - span];
            }
            if q == 0 {
                return 0.0;
            }
            let mut v = 0.0;
            let den = t[j + q] - t[j];
            if den > 0.0 {
                v += derivative(t, table, span, d - 1, q - 1, j) / den;
            }
            let den = t[j + q + 1] - t[j + 1];
            if den > 0.0 {
                v -= derivative(t, table, span, d - 1, q - 1, j + 1) / den;
            }
            q as f64 * v
        }
        std::array::from_fn(|k| {
            if k > p {
                return [0.0; 3];
            }
            let j = span - p + k;
            [
                table[p][k],
                derivative(t, &table, span, 1, p, j),
                derivative(t, &table, span, 2, p, j),
            ]
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graded() -> KnotVector {
        KnotVector::open(3, &[0.0, 0.05, 0.2, 0.45, 1.0]).unwrap()
    }

    #[test]
    fn partition_of_unity_and_its_derivatives() {
        let kv = graded();
        for e in 0..kv.n_elements() {
            let (a, b) = kv.element_bounds(e);
            for s in [0.0, 0.3, 0.77, 1.0] {
                let n = kv.evaluate(e, a + s * (b - a));
                let sum: [f64; 3] = std::array::from_fn(|d| n.iter().map(|f| f[d]).sum());
                assert!(n[4..].iter().all(|f| *f == [0.0; 3]));
                assert!((sum[0] - 1.0).abs() < 1e-14, "{sum:?}");
                assert!(sum[1].abs() < 1e-10 && sum[2].abs() < 1e-8, "{sum:?}");
            }
        }
    }

    #[test]
    fn greville_points_reproduce_the_parameter() {
        let kv = graded();
        let g = kv.greville();
        for e in 0..kv.n_elements() {
            let (a, b) = kv.element_bounds(e);
            let x = a + 0.4 * (b - a);
            let n = kv.evaluate(e, x);
            let f = kv.first_function(e);
            // The span has p + 1 functions; the rest of the fixed-size basis is zero.
            let span = || n.iter().take(kv.degree + 1).enumerate();
            let val: f64 = span().map(|(k, v)| v[0] * g[f + k]).sum();
            let der: f64 = span().map(|(k, v)| v[1] * g[f + k]).sum();
            assert!((val - x).abs() < 1e-14 && (der - 1.0).abs() < 1e-12);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        for kv in [
            graded(),
            KnotVector::open(2, &[0.0, 0.3, 0.5, 1.0]).unwrap(),
        ] {
            let p = kv.degree();
            for e in 0..kv.n_elements() {
                let (a, b) = kv.element_bounds(e);
                let x = a + 0.37 * (b - a);
                let h = 1e-5 * (b - a);
                let eval = |x: f64| kv.evaluate(e, x);
                let (n0, np, nm) = (eval(x), eval(x + h), eval(x - h));
                for k in 0..=p {
                    let d1 = (np[k][0] - nm[k][0]) / (2.0 * h);
                    let d2 = (np[k][1] - nm[k][1]) / (2.0 * h);
                    let s1 = n0.iter().map(|v| v[1].abs()).fold(1.0, f64::max);
                    let s2 = n0.iter().map(|v| v[2].abs()).fold(1.0, f64::max);
                    assert!((d1 - n0[k][1]).abs() < 1e-7 * s1, "N' {k}");
                    assert!((d2 - n0[k][2]).abs() < 1e-7 * s2, "N'' {k}");
                }
            }
        }
    }

    #[test]
    fn end_values_interpolate_and_fix_the_tangent() {
        let kv = graded();
        let n = kv.evaluate(0, 0.0);
        assert_eq!(n[0][0], 1.0);
        // Only the first two functions have a slope at the start: fixing two control points
        // fixes position and tangent.
        assert!(n[2][1] == 0.0 && n[3][1] == 0.0 && n[1][1] > 0.0);
        let last = kv.n_elements() - 1;
        let n = kv.evaluate(last, 1.0);
        assert!((n[3][0] - 1.0).abs() < 1e-15);
        assert!(n[0][1] == 0.0 && n[1][1] == 0.0);
    }

    #[test]
    fn locates_elements_and_rejects_bad_breakpoints() {
        let kv = graded();
        assert_eq!(kv.element_of(0.0), 0);
        assert_eq!(kv.element_of(0.05), 1);
        assert_eq!(kv.element_of(0.3), 2);
        assert_eq!(kv.element_of(1.0), 3);
        assert!(KnotVector::open(3, &[0.0, 0.0, 1.0]).is_err());
        assert!(KnotVector::open(0, &[0.0, 1.0]).is_err());
        assert!(KnotVector::open(MAX_DEGREE + 1, &[0.0, 1.0]).is_err());
        assert!(KnotVector::open(2, &[0.0, f64::NAN]).is_err());
    }
}
