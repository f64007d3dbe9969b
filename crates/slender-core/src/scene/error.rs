//! Errors of a scene that parses but cannot be built: they name the place in the file.

use thiserror::Error;

use crate::error::ModelError;

/// A semantic error in a scene, located by its path in the file (e.g.
/// `rods[0].supports[1].vertex`).
#[derive(Clone, Debug, Error, PartialEq)]
#[error("{path}: {message}")]
pub struct SceneError {
    /// Path of the offending key, in TOML/JSON dotted-and-indexed notation.
    pub path: String,
    /// What is wrong and what would be valid.
    pub message: String,
}

impl SceneError {
    /// An error at `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
        }
    }

    /// A model error raised while building the part of the scene at `path`.
    pub fn model(path: impl Into<String>, e: ModelError) -> Self {
        Self::new(path, e.to_string())
    }
}
