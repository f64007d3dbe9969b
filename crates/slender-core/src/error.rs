//! Errors raised when a model is built from invalid input.

use thiserror::Error;

/// A model could not be built because an input is invalid.
///
/// Every variant names the offending field and, where it applies, the valid range, so that a
/// user can fix the input without reading code.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModelError {
    /// A scalar parameter is NaN, infinite or outside its valid range.
    #[error("invalid `{field}` = {value}: must be {valid}")]
    InvalidParameter {
        /// Name of the parameter as the user wrote it (e.g. `ei1`, `length`).
        field: String,
        /// The rejected value.
        value: f64,
        /// Human-readable valid range (e.g. "finite and > 0").
        valid: String,
    },
    /// A discrete structure (mesh, polyline, support placement) is unusable.
    #[error("invalid `{field}`: {reason}")]
    InvalidStructure {
        /// Name of the field (e.g. `rest_positions`, `n_elements`).
        field: String,
        /// What is wrong and what would be valid.
        reason: String,
    },
}

impl ModelError {
    /// Shorthand for [`ModelError::InvalidParameter`].
    pub fn parameter(field: impl Into<String>, value: f64, valid: impl Into<String>) -> Self {
        Self::InvalidParameter {
            field: field.into(),
            value,
            valid: valid.into(),
        }
    }

    /// Shorthand for [`ModelError::InvalidStructure`].
    pub fn structure(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::InvalidStructure {
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn require_positive(field: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ModelError::parameter(field, value, "finite and > 0"))
    }
}

/// Checks that `value` is finite and non-negative.
pub fn require_non_negative(field: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ModelError::parameter(field, value, "finite and >= 0"))
    }
}

/// Checks that `value` is finite.
pub fn require_finite(field: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ModelError::parameter(field, value, "finite"))
    }
}
