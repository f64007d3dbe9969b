//! The term groups of the B-spline shell (for [`TermSet`](crate::assembly::TermSet)
//! selections).

use crate::assembly::{TermGroup, TermSet};

/// St-Venant–Kirchhoff membrane (`membrane.rs`).
pub const MEMBRANE: TermGroup = TermGroup {
    bit: 0,
    name: "membrane",
};
/// Kirchhoff–Love bending (`bending.rs`).
pub const BENDING: TermGroup = TermGroup {
    bit: 1,
    name: "bending",
};
/// Self-weight (`gravity.rs`).
pub const GRAVITY: TermGroup = TermGroup {
    bit: 2,
    name: "gravity",
};
/// Point forces (`loads.rs`).
pub const POINT_LOADS: TermGroup = TermGroup {
    bit: 3,
    name: "point loads",
};

/// Every group, in assembly order.
pub const ALL_GROUPS: [TermGroup; 4] = [MEMBRANE, BENDING, GRAVITY, POINT_LOADS];

/// The internal (elastic) energy.
pub const INTERNAL: TermSet = MEMBRANE.set().with(BENDING.set());
