//! Second-order forward-mode differentiation on a small fixed stencil.
//!
//! Why: the mid-edge bending term chains a dihedral angle, an altitude and a tangent through
//! twelve-plus coordinates. Writing that Hessian by hand is error-prone; propagating value,
//! gradient and Hessian through each elementary operation gives the *exact* derivatives (to
//! round-off) at a cost of O(N²) per operation, which on a 13-variable stencil is cheap.
//! Every result is still checked against finite differences in `tests/shell_derivatives.rs`.

use nalgebra::{SMatrix, SVector};

/// A scalar function of N variables with its gradient and (symmetric) Hessian.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual2<const N: usize> {
    /// Value.
    pub v: f64,
    /// Gradient ∂f/∂x.
    pub g: SVector<f64, N>,
    /// Hessian ∂²f/∂x².
    pub h: SMatrix<f64, N, N>,
    /// True when f is known to be affine (h = 0): the stencil's coordinates and their
    /// differences. Products of affine factors then skip the Hessian terms of the factors.
    pub affine: bool,
    /// Variables k ≥ `active` do not enter f at all, so their first and second derivatives
    /// are zero: a structural bound (N when unknown), not a test of the values. Stencils
    /// number their variables so that early quantities depend on a prefix (a face's corners
    /// before the neighbour and the angle), and the products then loop over that prefix only.
    pub active: usize,
    /// True when only the value and gradient are wanted (`h` stays zero): set on the
    /// variables of a gradient-only evaluation and inherited by everything computed from
    /// them, so that the O(N²) Hessian loops are skipped where nobody reads the Hessian (the
    /// gradient is the same to the bit: it never reads a Hessian).
    pub first_order: bool,
}

impl<const N: usize> Dual2<N> {
    /// A constant.
    pub fn constant(v: f64) -> Self {
        Self {
            v,
            g: SVector::zeros(),
            h: SMatrix::zeros(),
            affine: true,
            active: 0,
            first_order: false,
        }
    }

    /// The independent variable number `i` with value `v`.
    pub fn variable(v: f64, i: usize) -> Self {
        let mut d = Self::constant(v);
        d.g[i] = 1.0;
        d.active = i + 1;
        d
    }

    /// The same function, marked as wanted to first order only (see
    /// [`first_order`](Self::first_order)) if `first_order`.
    #[inline]
    pub fn with_first_order(mut self, first_order: bool) -> Self {
        self.first_order = first_order;
        self
    }

    /// f(self) from f, f′, f″ at the value.
    #[inline]
    fn chain(&self, f: f64, df: f64, d2f: f64) -> Self {
        // Entry loops instead of matrix expressions: no N×N temporaries.
        let m = if self.first_order { 0 } else { self.active };
        let mut h = SMatrix::<f64, N, N>::zeros();
        for j in 0..m {
            let gj = self.g[j] * d2f;
            for i in 0..m {
                h[(i, j)] = self.h[(i, j)] * df + self.g[i] * gj;
            }
        }
        Self {
            v: f,
            g: self.g * df,
            h,
            affine: false,
            active: self.active,
            first_order: self.first_order,
        }
    }

    /// f(self, other) from the first and second partial derivatives of f at the values.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn chain2(&self, o: &Self, f: f64, fa: f64, fb: f64, faa: f64, fab: f64, fbb: f64) -> Self {
        let first_order = self.first_order || o.first_order;
        let active = self.active.max(o.active);
        let m = if first_order { 0 } else { active };
        let mut h = SMatrix::<f64, N, N>::zeros();
        for j in 0..m {
            let (aj, bj) = (self.g[j], o.g[j]);
            for i in 0..m {
                let (ai, bi) = (self.g[i], o.g[i]);
                h[(i, j)] = self.h[(i, j)] * fa
                    + o.h[(i, j)] * fb
                    + ai * aj * faa
                    + bi * bj * fbb
                    + (ai * bj + bi * aj) * fab;
            }
        }
        Self {
            v: f,
            g: self.g * fa + o.g * fb,
            h,
            affine: false,
            active,
            first_order,
        }
    }

    /// Square root (argument > 0).
    pub fn sqrt(&self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s, -0.25 / (s * self.v))
    }

    /// Tangent.
    pub fn tan(&self) -> Self {
        let t = self.v.tan();
        let d = 1.0 + t * t;
        self.chain(t, d, 2.0 * t * d)
    }

    /// Sine.
    pub fn sin(&self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(s, c, -s)
    }

    /// 1/self.
    pub fn recip(&self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }

    /// self − o, by reference (no copies of the operands).
    #[inline]
    pub fn minus(&self, o: &Self) -> Self {
        let affine = self.affine && o.affine;
        let first_order = self.first_order || o.first_order;
        Self {
            v: self.v - o.v,
            g: self.g - o.g,
            h: if affine || first_order {
                SMatrix::zeros()
            } else {
                self.h - o.h
            },
            affine,
            active: self.active.max(o.active),
            first_order,
        }
    }

    /// Scales by a constant.
    #[inline]
    pub fn scale(&self, c: f64) -> Self {
        Self {
            v: self.v * c,
            g: self.g * c,
            h: if self.affine || self.first_order {
                SMatrix::zeros()
            } else {
                self.h * c
            },
            affine: self.affine,
            active: self.active,
            first_order: self.first_order,
        }
    }

    /// atan2(self, x): the angle of the point (x, self).
    pub fn atan2(&self, x: &Self) -> Self {
        let (y0, x0) = (self.v, x.v);
        let r2 = x0 * x0 + y0 * y0;
        let r4 = r2 * r2;
        // With a = y, b = x: ∂/∂y = x/r², ∂/∂x = −y/r².
        self.chain2(
            x,
            y0.atan2(x0),
            x0 / r2,
            -y0 / r2,
            -2.0 * x0 * y0 / r4,
            (y0 * y0 - x0 * x0) / r4,
            2.0 * x0 * y0 / r4,
        )
    }
}

impl<const N: usize> std::ops::Add for Dual2<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        let affine = self.affine && o.affine;
        let first_order = self.first_order || o.first_order;
        Self {
            v: self.v + o.v,
            g: self.g + o.g,
            h: if affine || first_order {
                SMatrix::zeros()
            } else {
                self.h + o.h
            },
            affine,
            active: self.active.max(o.active),
            first_order,
        }
    }
}

impl<const N: usize> std::ops::Sub for Dual2<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        self.minus(&o)
    }
}

impl<const N: usize> std::ops::Mul for Dual2<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        sum_of_products(&[(&self, &o, 1.0)])
    }
}

/// Σ_k s_k·a_k·b_k in one pass over the N×N Hessian (the products of a cross or dot product
/// at once, without temporaries); the factors' own Hessians are skipped when affine.
#[inline]
pub fn sum_of_products<const N: usize>(terms: &[(&Dual2<N>, &Dual2<N>, f64)]) -> Dual2<N> {
    let mut out = Dual2 {
        v: 0.0,
        g: SVector::<f64, N>::zeros(),
        h: SMatrix::<f64, N, N>::zeros(),
        affine: false,
        active: 0,
        first_order: terms.iter().any(|(a, b, _)| a.first_order || b.first_order),
    };
    for &(a, b, s) in terms {
        let (sa, sb) = (s * a.v, s * b.v);
        out.v += s * a.v * b.v;
        // Entries outside the factors' active prefix would add zeros.
        let m = a.active.max(b.active);
        out.active = out.active.max(m);
        for i in 0..m {
            out.g[i] += a.g[i] * sb + b.g[i] * sa;
        }
        // Entry loops, each entry updated in the order h + a.h·sb + b.h·sa + (outer products):
        // matrix expressions here built N×N temporaries, and copying them was a fifth of a
        // shell assembly.
        // First order: the gradient only.
        let mh = if out.first_order { 0 } else { m };
        for j in 0..mh {
            let (aj, bj) = (s * a.g[j], s * b.g[j]);
            let outer = !(aj == 0.0 && bj == 0.0);
            for i in 0..mh {
                let mut x = out.h[(i, j)];
                if !a.affine {
                    x += a.h[(i, j)] * sb;
                }
                if !b.affine {
                    x += b.h[(i, j)] * sa;
                }
                if outer {
                    x += a.g[i] * bj + b.g[i] * aj;
                }
                out.h[(i, j)] = x;
            }
        }
    }
    out
}

impl<const N: usize> std::ops::Div for Dual2<N> {
    type Output = Self;
    #[allow(clippy::suspicious_arithmetic_impl)] // a / b = a · (1/b)
    fn div(self, o: Self) -> Self {
        self * o.recip()
    }
}

/// A 3-vector of [`Dual2`] scalars.
pub type DualVec3<const N: usize> = [Dual2<N>; 3];

/// Point `k` of a stencil whose variables are stored as consecutive triples.
#[inline]
pub fn point<const N: usize>(x: &[f64], k: usize) -> DualVec3<N> {
    [
        Dual2::variable(x[3 * k], 3 * k),
        Dual2::variable(x[3 * k + 1], 3 * k + 1),
        Dual2::variable(x[3 * k + 2], 3 * k + 2),
    ]
}

/// a − b.
#[inline]
pub fn sub3<const N: usize>(a: &DualVec3<N>, b: &DualVec3<N>) -> DualVec3<N> {
    // Written out: `array::from_fn` over by-value subtraction copied the N×N Hessians twice.
    [a[0].minus(&b[0]), a[1].minus(&b[1]), a[2].minus(&b[2])]
}

/// a × b.
#[inline]
pub fn cross3<const N: usize>(a: &DualVec3<N>, b: &DualVec3<N>) -> DualVec3<N> {
    [
        sum_of_products(&[(&a[1], &b[2], 1.0), (&a[2], &b[1], -1.0)]),
        sum_of_products(&[(&a[2], &b[0], 1.0), (&a[0], &b[2], -1.0)]),
        sum_of_products(&[(&a[0], &b[1], 1.0), (&a[1], &b[0], -1.0)]),
    ]
}

/// a · b.
#[inline]
pub fn dot3<const N: usize>(a: &DualVec3<N>, b: &DualVec3<N>) -> Dual2<N> {
    sum_of_products(&[
        (&a[0], &b[0], 1.0),
        (&a[1], &b[1], 1.0),
        (&a[2], &b[2], 1.0),
    ])
}

/// a · c for a constant vector c.
#[inline]
pub fn dot3_const<const N: usize>(a: &DualVec3<N>, c: &[f64; 3]) -> Dual2<N> {
    a[0].scale(c[0]) + a[1].scale(c[1]) + a[2].scale(c[2])
}

/// a × c for a constant vector c.
#[inline]
pub fn cross3_const<const N: usize>(a: &DualVec3<N>, c: &[f64; 3]) -> DualVec3<N> {
    [
        a[1].scale(c[2]) - a[2].scale(c[1]),
        a[2].scale(c[0]) - a[0].scale(c[2]),
        a[0].scale(c[1]) - a[1].scale(c[0]),
    ]
}
