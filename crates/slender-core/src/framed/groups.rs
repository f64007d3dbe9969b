//! The term groups of the rods with material frames (discrete Cosserat rod and SE(3) beam):
//! with a diagonal section stiffness the energy splits exactly into these parts. The groups
//! they share with the discrete elastic rod (`rod/groups.rs`) have its bits, so that one term
//! selection means the same in a structure that mixes formulations; shear is their own.

use crate::assembly::{TermGroup, TermSet};

/// Shear along d₁ and d₂ (κGA₁, κGA₂).
pub const SHEAR: TermGroup = TermGroup {
    bit: 4,
    name: "shear",
};
/// Extension along d₃ (EA).
pub const STRETCHING: TermGroup = crate::rod::groups::STRETCHING;
/// Bending about d₁ and d₂ (EI₂, EI₁).
pub const BENDING: TermGroup = crate::rod::groups::BENDING;
/// Twisting about d₃ (GJ).
pub const TWISTING: TermGroup = crate::rod::groups::TWISTING;
/// Gravity, point forces and point moments.
pub const EXTERNAL: TermGroup = crate::rod::groups::EXTERNAL;

/// Every group, in assembly order.
pub const ALL_GROUPS: [TermGroup; 5] = [SHEAR, STRETCHING, BENDING, TWISTING, EXTERNAL];

/// The internal (elastic) energy: everything but the external loads.
pub const INTERNAL: TermSet = TermSet::ALL.without(EXTERNAL.set());

/// Per component of a strain vector (shear₁, shear₂, extension, bending₁, bending₂, twist),
/// its group.
pub const COMPONENT_GROUPS: [TermGroup; 6] = [SHEAR, SHEAR, STRETCHING, BENDING, BENDING, TWISTING];

/// 1 for the components of a 6-strain whose group is in `selected`, 0 otherwise.
pub fn component_mask(selected: TermSet) -> [f64; 6] {
    COMPONENT_GROUPS.map(|g| if selected.contains(g) { 1.0 } else { 0.0 })
}
