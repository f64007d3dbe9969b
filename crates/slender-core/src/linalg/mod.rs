//! Linear algebra the solver needs beyond what faer and nalgebra offer directly: the storage
//! trait the Newton solver is generic over, the banded LDLᵀ (rods), the sparse LDLᵀ through
//! faer (shells), and the smallest eigenpair by spectrum slicing.

pub mod adaptive;
pub mod banded;
pub mod eigen;
pub mod sparse;
pub mod symmetric;

pub use adaptive::{AdaptiveLdlt, AdaptiveMatrix};
pub use banded::{BandLdlt, SymmetricBandMatrix};
pub use eigen::{smallest_eigenpair, smallest_eigenpair_near, EigenEstimate};
pub use sparse::{ScatterPlan, SparseLdlt, SparseSymmetricMatrix};
pub use symmetric::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};
