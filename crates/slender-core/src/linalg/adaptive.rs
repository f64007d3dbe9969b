//! A Hessian storage chosen at run time: banded when the DOF ordering keeps every stencil in a
//! narrow band (a single rod: the fast hand-written banded LDLᵀ), sparse otherwise (joints,
//! rings, several members: faer's sparse LDLᵀ). Composite structures use it because their
//! pattern is only known once the scene is built.

use super::banded::{BandLdlt, SymmetricBandMatrix};
use super::sparse::{SparseLdlt, SparseSymmetricMatrix};
use super::symmetric::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};

/// Banded or sparse symmetric storage.
#[derive(Clone, Debug, PartialEq)]
pub enum AdaptiveMatrix {
    /// Banded storage.
    Band(SymmetricBandMatrix),
    /// Sparse storage with a fixed pattern.
    Sparse(SparseSymmetricMatrix),
}

/// The factorization matching an [`AdaptiveMatrix`].
#[derive(Clone, Debug, Default)]
pub enum AdaptiveLdlt {
    /// Nothing factored yet.
    #[default]
    Empty,
    /// Banded LDLᵀ.
    Band(BandLdlt),
    /// Sparse LDLᵀ (symbolic analysis reused).
    Sparse(SparseLdlt),
}

impl SymmetricMatrix for AdaptiveMatrix {
    type Factor = AdaptiveLdlt;

    fn dim(&self) -> usize {
        match self {
            Self::Band(m) => m.dim(),
            Self::Sparse(m) => SymmetricMatrix::dim(m),
        }
    }

    fn set_zero(&mut self) {
        match self {
            Self::Band(m) => m.set_zero(),
            Self::Sparse(m) => SymmetricMatrix::set_zero(m),
        }
    }

    fn add_same_pattern(&mut self, other: &Self) -> bool {
        match (self, other) {
            (Self::Band(a), Self::Band(b)) => a.add_same_pattern(b),
            (Self::Sparse(a), Self::Sparse(b)) => a.add_same_pattern(b),
            _ => false,
        }
    }

    fn add(&mut self, i: usize, j: usize, v: f64) {
        match self {
            Self::Band(m) => m.add(i, j, v),
            Self::Sparse(m) => SymmetricMatrix::add(m, i, j, v),
        }
    }

    #[inline]
    fn add_lower_block<const D: usize>(
        &mut self,
        dofs: &[usize; D],
        value: impl Fn(usize, usize) -> f64,
    ) {
        match self {
            Self::Band(m) => m.add_lower_block(dofs, value),
            Self::Sparse(m) => m.add_lower_block(dofs, value),
        }
    }

    fn diagonal(&self, i: usize) -> f64 {
        match self {
            Self::Band(m) => SymmetricMatrix::diagonal(m, i),
            Self::Sparse(m) => SymmetricMatrix::diagonal(m, i),
        }
    }

    fn diagonal_into(&self, out: &mut [f64]) {
        match self {
            Self::Band(m) => SymmetricMatrix::diagonal_into(m, out),
            Self::Sparse(m) => SymmetricMatrix::diagonal_into(m, out),
        }
    }

    fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        match self {
            Self::Band(m) => m.mul_vec(x, y),
            Self::Sparse(m) => SymmetricMatrix::mul_vec(m, x, y),
        }
    }

    fn gershgorin_bounds(&self) -> (f64, f64) {
        match self {
            Self::Band(m) => m.gershgorin_bounds(),
            Self::Sparse(m) => SymmetricMatrix::gershgorin_bounds(m),
        }
    }

    fn gershgorin_bounds_in(&self, radius: &mut Vec<f64>) -> (f64, f64) {
        match self {
            Self::Band(m) => m.gershgorin_bounds_in(radius),
            Self::Sparse(m) => SymmetricMatrix::gershgorin_bounds_in(m, radius),
        }
    }

    fn first_non_finite(&self) -> Option<usize> {
        match self {
            Self::Band(m) => SymmetricMatrix::first_non_finite(m),
            Self::Sparse(m) => SymmetricMatrix::first_non_finite(m),
        }
    }

    fn congruence_scaled(&self, s: &[f64], out: &mut Self) {
        match (self, &mut *out) {
            (Self::Band(a), Self::Band(o)) => a.congruence_scaled(s, o),
            (Self::Sparse(a), Self::Sparse(o)) => a.congruence_scaled(s, o),
            _ => {
                *out = self.clone();
                self.congruence_scaled(s, out);
            }
        }
    }
}

impl SymmetricFactor<AdaptiveMatrix> for AdaptiveLdlt {
    fn factorize(&mut self, a: &AdaptiveMatrix, shift: f64) -> Result<Inertia, FactorError> {
        match a {
            AdaptiveMatrix::Band(m) => {
                if !matches!(self, Self::Band(_)) {
                    *self = Self::Band(BandLdlt::new());
                }
                let Self::Band(f) = self else { unreachable!() };
                SymmetricFactor::factorize(f, m, shift)
            }
            AdaptiveMatrix::Sparse(m) => {
                if !matches!(self, Self::Sparse(_)) {
                    *self = Self::Sparse(SparseLdlt::new());
                }
                let Self::Sparse(f) = self else {
                    unreachable!()
                };
                f.factorize(m, shift)
            }
        }
    }

    fn try_solve_in_place(&self, b: &mut [f64]) -> Result<(), FactorError> {
        match self {
            Self::Empty => Err(FactorError::NotFactored),
            Self::Band(f) => f.try_solve_in_place(b),
            Self::Sparse(f) => f.try_solve_in_place(b),
        }
    }

    fn solve_block_in_place<const K: usize>(&self, bs: [&mut [f64]; K]) {
        match self {
            Self::Band(f) => f.solve_block_in_place(bs),
            _ => {
                for b in bs {
                    self.solve_in_place(b);
                }
            }
        }
    }
}
