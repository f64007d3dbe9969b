//! Errors of the lateral-buckling master curves.

use super::generalized_eigen::PencilError;
use crate::ode::OdeError;

/// Why a critical load could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LateralBucklingError {
    /// An argument is NaN or outside its valid range.
    #[error("invalid {name} = {value}: must be {range}")]
    InvalidArgument {
        /// The argument's name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The valid range, in words.
        range: &'static str,
    },
    /// A discretisation size (elements, basis orders) is outside its valid range.
    #[error("invalid {name} = {value}: must be in [{min}, {max}]")]
    InvalidSize {
        /// The argument's name.
        name: &'static str,
        /// The rejected value.
        value: usize,
        /// Smallest accepted value.
        min: usize,
        /// Largest accepted value.
        max: usize,
    },
    /// The shooting integration failed.
    #[error("shooting integration failed at lambda = {lambda}: {source}")]
    Ode {
        /// The load parameter being tried.
        lambda: f64,
        /// The integrator's error.
        source: OdeError,
    },
    /// No sign change of the shooting determinant below the scan limit.
    #[error("no buckling load found below lambda = {lambda_max} (K = {k})")]
    NoRootFound {
        /// The warping parameter.
        k: f64,
        /// Where the scan stopped.
        lambda_max: f64,
    },
    /// The bisection on the shooting determinant failed after the scan bracketed a root
    /// (not expected: the bracket and tolerance are the scan's own).
    #[error("bisection of the shooting determinant failed (K = {k}): {detail}")]
    Bisection {
        /// The warping parameter.
        k: f64,
        /// What the root finder reported.
        detail: String,
    },
    /// A Ritz eigenproblem failed.
    #[error("{method}: {source}")]
    Pencil {
        /// Which Ritz method.
        method: &'static str,
        /// What went wrong.
        source: PencilError,
    },
}

/// `ν` must lie in the open interval `(−1, 0.5)` (positive definite isotropic plane
/// stress and plate bending).
pub(crate) fn check_poisson_ratio(nu: f64) -> Result<(), LateralBucklingError> {
    if nu > -1.0 && nu < 0.5 {
        Ok(())
    } else {
        Err(LateralBucklingError::InvalidArgument {
            name: "nu (Poisson's ratio)",
            value: nu,
            range: "in the open interval (-1, 0.5)",
        })
    }
}

/// The plate's `w/L` must be finite and positive (the Ritz bases need a nondegenerate
/// rectangle; the converged range of the defaults is narrower, see `critical_gamma`).
pub(crate) fn check_positive_aspect_ratio(w_over_l: f64) -> Result<(), LateralBucklingError> {
    if w_over_l > 0.0 && w_over_l.is_finite() {
        Ok(())
    } else {
        Err(LateralBucklingError::InvalidArgument {
            name: "w_over_l (width/length)",
            value: w_over_l,
            range: "finite and > 0",
        })
    }
}
