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
    /// A Ritz eigenproblem failed.
    #[error("{method}: {source}")]
    Pencil {
        /// Which Ritz method.
        method: &'static str,
        /// What went wrong.
        source: PencilError,
    },
}
