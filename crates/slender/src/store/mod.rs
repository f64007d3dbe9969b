//! The result store: every finished case of a sweep as one file, keyed by its parameters and
//! the code version, written atomically (temporary file, fsync, rename).
//!
//! Layout: `<root>/<benchmark>/<key>.toml`, see [`record`] for the file format. A rerun loads
//! what is there and computes only the rest; a torn, edited or foreign file is recomputed.
//! Because each case is deterministic and a record holds the exact bits of its result,
//! killing a run at any moment and rerunning gives the records of an uninterrupted run.

pub mod merge;
pub mod record;
pub mod runner;
pub mod shard;

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;

use record::{decode, encode, key, Envelope, CODE_VERSION};

/// Extension of record files.
pub const RECORD_EXTENSION: &str = "toml";
/// Prefix of temporary files (left behind only by a killed process; ignored and removed).
const TMP_PREFIX: &str = ".partial-";

/// The records of one benchmark in a store directory.
#[derive(Clone, Debug)]
pub struct BenchmarkStore {
    dir: PathBuf,
    benchmark: String,
}

impl BenchmarkStore {
    /// The store of `benchmark` under `root` (created when the first record is written).
    pub fn new(root: &Path, benchmark: &str) -> Self {
        Self {
            dir: root.join(benchmark),
            benchmark: benchmark.to_string(),
        }
    }

    /// Benchmark name.
    pub fn benchmark(&self) -> &str {
        &self.benchmark
    }

    /// Removes temporary files a killed run left behind.
    pub fn clean_partial_files(&self) -> Result<()> {
        let Ok(entries) = fs::read_dir(&self.dir) else {
            return Ok(());
        };
        for e in entries.flatten() {
            if e.file_name().to_string_lossy().starts_with(TMP_PREFIX) {
                fs::remove_file(e.path())
                    .with_context(|| format!("removing {}", e.path().display()))?;
            }
        }
        Ok(())
    }

    fn path_of(&self, key: &str) -> PathBuf {
        self.dir.join(format!("{key}.{RECORD_EXTENSION}"))
    }

    /// The stored record of `params` and its wall time (s), or `None` if there is no valid
    /// one (missing, torn, corrupt, or of other parameters or code).
    pub fn load<P: Serialize, R: DeserializeOwned>(&self, params: &P) -> Result<Option<(R, f64)>> {
        let path = self.path_of(&key(&self.benchmark, params)?);
        let text = match fs::read(&path) {
            Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(e).with_context(|| format!("reading {}", path.display())),
        };
        match decode(&text, &self.benchmark, params) {
            Ok(found) => Ok(Some(found)),
            Err(why) => {
                eprintln!("{}: {why}; computing it again", path.display());
                Ok(None)
            }
        }
    }

    /// Writes the record of `params` atomically.
    pub fn save<P: Serialize, R: Serialize>(
        &self,
        params: &P,
        record: &R,
        seconds: f64,
    ) -> Result<()> {
        let key = key(&self.benchmark, params)?;
        let text = encode(&Envelope {
            benchmark: self.benchmark.clone(),
            code_version: CODE_VERSION.to_string(),
            seconds,
            params,
            record,
        })?;
        self.write_file(&key, text.as_bytes())
    }

    /// Writes the file of `key` through a temporary file, fsync and rename.
    pub(crate) fn write_file(&self, key: &str, bytes: &[u8]) -> Result<()> {
        fs::create_dir_all(&self.dir)
            .with_context(|| format!("creating {}", self.dir.display()))?;
        let tmp = self.dir.join(format!(
            "{TMP_PREFIX}{key}-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        let mut f =
            fs::File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        f.write_all(bytes)
            .and_then(|_| f.sync_all())
            .with_context(|| format!("writing {}", tmp.display()))?;
        let path = self.path_of(key);
        fs::rename(&tmp, &path).with_context(|| format!("renaming to {}", path.display()))?;
        Ok(())
    }

    /// Every record file of this benchmark (sorted by name).
    pub fn record_files(&self) -> Result<Vec<PathBuf>> {
        let mut v = Vec::new();
        let Ok(entries) = fs::read_dir(&self.dir) else {
            return Ok(v);
        };
        for e in entries {
            let p = e
                .with_context(|| format!("listing {}", self.dir.display()))?
                .path();
            let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
            if p.extension().is_some_and(|x| x == RECORD_EXTENSION)
                && !name.is_some_and(|n| n.starts_with(TMP_PREFIX))
            {
                v.push(p);
            }
        }
        v.sort();
        Ok(v)
    }
}
