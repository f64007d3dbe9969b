//! Linear algebra the solver needs beyond what faer and nalgebra offer directly.

pub mod banded;

pub use banded::{
    smallest_eigenpair, BandLdlt, EigenEstimate, FactorError, Inertia, SymmetricBandMatrix,
};
