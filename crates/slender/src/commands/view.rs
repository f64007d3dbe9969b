//! `slender view`: the interactive cable-editing page; the work is in [`crate::view`].

use anyhow::Result;

pub use crate::view::ViewArgs;

/// Serves the page until the process is stopped.
pub fn run(a: &ViewArgs) -> Result<bool> {
    crate::view::run(a)
}
