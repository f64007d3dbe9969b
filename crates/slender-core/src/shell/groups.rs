//! The term groups of the shell (for [`TermSet`](crate::assembly::TermSet) selections).

use crate::assembly::{TermGroup, TermSet};

/// St-Venant–Kirchhoff membrane (`membrane.rs`).
pub const MEMBRANE: TermGroup = TermGroup {
    bit: 0,
    name: "membrane",
};
/// Mid-edge bending, including the clamp's director term (`bending.rs`).
pub const BENDING: TermGroup = TermGroup {
    bit: 1,
    name: "bending",
};
/// Self-weight (`gravity.rs`).
pub const GRAVITY: TermGroup = TermGroup {
    bit: 2,
    name: "gravity",
};

/// Every group, in assembly order.
pub const ALL_GROUPS: [TermGroup; 3] = [MEMBRANE, BENDING, GRAVITY];

/// The internal (elastic) energy.
pub const INTERNAL: TermSet = TermSet::ALL.without(GRAVITY.set());
