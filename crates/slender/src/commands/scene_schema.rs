//! `slender scene-schema`: the JSON Schema of the scene format.

use std::path::PathBuf;

use anyhow::Result;

/// The flags of `slender scene-schema`.
#[derive(clap::Args, Debug)]
pub struct SceneSchemaArgs {
    /// Write the schema to this file instead of printing it.
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Prints or writes the schema.
pub fn run(a: &SceneSchemaArgs) -> Result<bool> {
    crate::solve::write_schema(a.out.as_deref())?;
    Ok(true)
}
