//! `slender merge`: combines the stores of shard runs into one store.
//!
//! Records are copied byte for byte (atomically). A record present in two sources must hold
//! the same result; otherwise the merge stops with an error naming both files, because two
//! runs of the same code on the same parameters disagreeing means non-determinism.

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};

use super::record::decode_any;
use super::BenchmarkStore;

/// What a merge did.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct MergeSummary {
    /// Records copied into the destination.
    pub copied: usize,
    /// Records the destination already had, with the same result.
    pub identical: usize,
    /// Unreadable or torn source files left out (their cases will be recomputed).
    pub skipped: usize,
}

fn benchmark_dirs(root: &Path) -> Result<Vec<PathBuf>> {
    let mut v = Vec::new();
    for e in fs::read_dir(root).with_context(|| format!("reading store {}", root.display()))? {
        let p = e?.path();
        if p.is_dir() {
            v.push(p);
        }
    }
    v.sort();
    Ok(v)
}

/// Merges the store roots `sources` into `dest`.
pub fn merge_stores(dest: &Path, sources: &[PathBuf]) -> Result<MergeSummary> {
    let mut summary = MergeSummary::default();
    for src in sources {
        if src == dest {
            bail!("merge source {} is the destination", src.display());
        }
        for dir in benchmark_dirs(src)? {
            let benchmark = dir
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let from = BenchmarkStore::new(src, &benchmark);
            let to = BenchmarkStore::new(dest, &benchmark);
            for file in from.record_files()? {
                let bytes =
                    fs::read(&file).with_context(|| format!("reading {}", file.display()))?;
                let text = String::from_utf8_lossy(&bytes);
                let env = match decode_any(&text) {
                    Ok(env) if env.benchmark == benchmark => env,
                    Ok(_) => {
                        eprintln!("{}: record of another benchmark; left out", file.display());
                        summary.skipped += 1;
                        continue;
                    }
                    Err(why) => {
                        eprintln!("{}: {why}; left out", file.display());
                        summary.skipped += 1;
                        continue;
                    }
                };
                let name = file.file_name().expect("a record file has a name");
                let target = dest.join(&benchmark).join(name);
                if let Ok(existing) = fs::read(&target) {
                    if let Ok(old) = decode_any(&String::from_utf8_lossy(&existing)) {
                        if old.params != env.params
                            || old.record != env.record
                            || old.code_version != env.code_version
                        {
                            bail!(
                                "{} and {} hold different results for the same case",
                                file.display(),
                                target.display()
                            );
                        }
                        summary.identical += 1;
                        continue;
                    }
                }
                let key = Path::new(name)
                    .file_stem()
                    .map(|s| s.to_string_lossy().into_owned())
                    .unwrap_or_default();
                to.write_file(&key, &bytes)?;
                summary.copied += 1;
            }
        }
    }
    Ok(summary)
}
