//! Stencils: which global free DOF each local slot of a term is.

/// Marks a stencil slot that is not a free DOF (held by a support, a clamp's ghost edge, or
/// absent at a boundary).
pub const FIXED: usize = usize::MAX;

/// The free-DOF index of each of a term's `D` local slots ([`FIXED`] for slots that are not
/// free). Two slots may name the same DOF (e.g. a shell face touching one vertex twice).
pub type Stencil<const D: usize> = [usize; D];
