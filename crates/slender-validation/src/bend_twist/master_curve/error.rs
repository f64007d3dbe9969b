//! Why a master-curve quantity could not be computed.

/// Why a master-curve quantity could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BendTwistError {
    /// An input is NaN, infinite or outside its valid range.
    #[error("invalid {name} = {value}: must be {range}")]
    InvalidParameter {
        /// Which input (`x`, `y`, `c`, `rtol`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The valid range.
        range: String,
    },
    /// The numerics failed (not expected inside the documented ranges).
    #[error("bend-twist master curve failed at Y = {y}, c = {c}: {detail}")]
    NoConvergence {
        /// The aspect parameter `Y` (NaN for [`super::general_free_end_moments`]).
        y: f64,
        /// The torsion ratio `c` (NaN for [`super::general_free_end_moments`]).
        c: f64,
        /// What went wrong.
        detail: String,
    },
}
