//! Running a sweep through the store: load what is finished, compute the rest in parallel,
//! write each case the moment it is done.

use std::time::Instant;

use anyhow::Result;
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::Serialize;

use super::shard::Shard;
use super::BenchmarkStore;
use crate::progress::Progress;

/// Where a sweep keeps its records and which part of it this run computes.
#[derive(Clone, Debug)]
pub struct StoreOptions {
    /// Store root directory.
    pub root: std::path::PathBuf,
    /// `Some`: compute only this shard and write no report.
    pub shard: Option<Shard>,
}

/// The outcome of a sweep run.
#[derive(Clone, Debug)]
pub struct SweepRun<R> {
    /// Records in the sweep's case order; `None` for cases of other shards.
    pub records: Vec<Option<R>>,
    /// Cases computed by this run.
    pub computed: usize,
    /// Cases found finished in the store.
    pub reused: usize,
    /// Wall time of all this shard's cases when they were computed (s), stored or new.
    pub case_seconds: f64,
}

impl<R> SweepRun<R> {
    /// All records, if this run covers the whole sweep.
    pub fn complete(self) -> Option<Vec<R>> {
        self.records.into_iter().collect()
    }
}

/// Runs the cases `params` (in their fixed order) of `store`'s benchmark: every case of
/// `shard` (all if `None`) is loaded from the store or computed by `compute` and saved.
/// The records do not depend on the number of threads, on the shard split, or on how many
/// earlier runs were interrupted.
pub fn run_cases<P, R, F>(
    store: &BenchmarkStore,
    shard: Option<Shard>,
    params: &[P],
    compute: F,
) -> Result<SweepRun<R>>
where
    P: Serialize + Sync,
    R: Serialize + DeserializeOwned + Send,
    F: Fn(&P) -> Result<R> + Sync,
{
    store.clean_partial_files()?;
    let owned: Vec<usize> = (0..params.len())
        .filter(|&i| shard.is_none_or(|s| s.owns(i)))
        .collect();
    let stored: Vec<Option<(R, f64)>> = owned
        .par_iter()
        .map(|&i| store.load(&params[i]))
        .collect::<Result<_>>()?;
    let missing: Vec<usize> = owned
        .iter()
        .zip(&stored)
        .filter(|(_, s)| s.is_none())
        .map(|(&i, _)| i)
        .collect();
    let reused = owned.len() - missing.len();
    let label = match shard {
        Some(s) => format!("{} {s}", store.benchmark()),
        None => store.benchmark().to_string(),
    };
    if reused > 0 {
        eprintln!(
            "{label}: {reused} of {} cases found finished in the store",
            owned.len()
        );
    }
    let progress = Progress::new(&label, missing.len());
    let fresh: Vec<(R, f64)> = missing
        .par_iter()
        .map(|&i| {
            let clock = Instant::now();
            let r = compute(&params[i])?;
            let seconds = clock.elapsed().as_secs_f64();
            store.save(&params[i], &r, seconds)?;
            progress.tick();
            Ok((r, seconds))
        })
        .collect::<Result<_>>()?;
    progress.finish();
    let mut records: Vec<Option<R>> = (0..params.len()).map(|_| None).collect();
    let mut case_seconds = 0.0;
    for (&i, s) in owned.iter().zip(stored) {
        if let Some((r, t)) = s {
            records[i] = Some(r);
            case_seconds += t;
        }
    }
    for (&i, (r, t)) in missing.iter().zip(fresh) {
        records[i] = Some(r);
        case_seconds += t;
    }
    Ok(SweepRun {
        records,
        computed: missing.len(),
        reused,
        case_seconds,
    })
}

/// Counts of a sweep run, for the report.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct RunStats {
    /// Cases computed by this run.
    pub computed: usize,
    /// Cases reused from the store.
    pub reused: usize,
    /// Σ wall time of the cases when they were computed (s).
    pub case_seconds: f64,
}

impl RunStats {
    /// The counts of `run`.
    pub fn of<R>(run: &SweepRun<R>) -> Self {
        Self {
            computed: run.computed,
            reused: run.reused,
            case_seconds: run.case_seconds,
        }
    }
}
