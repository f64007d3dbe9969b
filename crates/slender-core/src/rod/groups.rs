//! The term groups of a discrete elastic rod (for [`TermSet`](crate::assembly::TermSet)
//! selections, e.g. checking one energy at a time).

use crate::assembly::{TermGroup, TermSet};

/// Stretching of the edges (`stretching.rs`).
pub const STRETCHING: TermGroup = TermGroup {
    bit: 0,
    name: "stretching",
};
/// Bending at the hinges (`bending.rs`).
pub const BENDING: TermGroup = TermGroup {
    bit: 1,
    name: "bending",
};
/// Twisting at the hinges (`twisting.rs`).
pub const TWISTING: TermGroup = TermGroup {
    bit: 2,
    name: "twisting",
};
/// Gravity, point forces and point moments (`loads.rs`).
pub const EXTERNAL: TermGroup = TermGroup {
    bit: 3,
    name: "external",
};

/// Every group, in assembly order.
pub const ALL_GROUPS: [TermGroup; 4] = [STRETCHING, BENDING, TWISTING, EXTERNAL];

/// The internal (elastic) energy: everything but the external loads.
pub const INTERNAL: TermSet = TermSet::ALL.without(EXTERNAL.set());
