//! `slender merge`: combines result stores (e.g. of `--shard` runs) into one.

use std::path::PathBuf;

use anyhow::Result;

use crate::store::merge::merge_stores;

/// The flags of `slender merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Destination store (created if missing).
    #[arg(long)]
    into: PathBuf,
    /// Source stores.
    #[arg(required = true)]
    sources: Vec<PathBuf>,
}

/// Merges and prints what was copied.
pub fn run(a: &MergeArgs) -> Result<bool> {
    let s = merge_stores(&a.into, &a.sources)?;
    println!(
        "merged into {}: {} records copied, {} already there, {} unreadable left out",
        a.into.display(),
        s.copied,
        s.identical,
        s.skipped
    );
    Ok(true)
}
