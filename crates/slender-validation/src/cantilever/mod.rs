//! The cantilever under self-weight (seed §3, Fig. 2).

pub mod case;
pub mod master_curve;

pub use case::{end_point_ratio, CantileverCase, CantileverRun, MeshKind};
