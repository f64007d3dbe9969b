//! What a benchmark runs in: the result store (and the shard of it this run computes), where
//! its files go, whether the acceptance checks are wanted, and the ledger of what each report
//! section cost (wall time, cases computed and reused).

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::store::runner::{run_cases, RunStats, StoreOptions};
use crate::store::shard::Shard;
use crate::store::BenchmarkStore;

/// Where a benchmark's report sections write their files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Every section in the output directory itself (the single-benchmark commands).
    Flat,
    /// Each section in its own subdirectory `OUT/<section dir>` (`slender validate`).
    PerSection,
}

/// What one report section cost in this run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tally {
    /// Wall time spent while the section was current (s).
    pub wall_seconds: f64,
    /// Cases computed and reused, and their compute time.
    pub stats: RunStats,
}

/// The run a benchmark executes in. A *case* is one solve of the discrete model (or one unit
/// of solves, e.g. one scene file, one branch continuation): through the store it is computed
/// or reused; outside it (pictures, scene checks) it is always computed.
pub struct Context<'a> {
    out: &'a Path,
    layout: Layout,
    store: &'a StoreOptions,
    validating: bool,
    ledger: Vec<(String, Tally)>,
    current: Option<(usize, Instant)>,
}

impl<'a> Context<'a> {
    /// A run writing under `out` with the store `store`; `validating`: the acceptance checks
    /// (and the cases they need) are computed too.
    pub fn new(out: &'a Path, layout: Layout, store: &'a StoreOptions, validating: bool) -> Self {
        Self {
            out,
            layout,
            store,
            validating,
            ledger: Vec::new(),
            current: None,
        }
    }

    /// Whether the acceptance checks are wanted (`slender validate`).
    pub fn validating(&self) -> bool {
        self.validating
    }

    /// The shard this run computes (`None`: all cases, and the report).
    pub fn shard(&self) -> Option<Shard> {
        self.store.shard
    }

    /// The directory of the report section `section`.
    pub fn dir(&self, section: &str) -> PathBuf {
        match self.layout {
            Layout::Flat => self.out.to_path_buf(),
            Layout::PerSection => self.out.join(section),
        }
    }

    /// From now on, wall time and cases count for `section` (until the next call).
    pub fn enter(&mut self, section: &str) {
        self.pause();
        let i = match self.ledger.iter().position(|(s, _)| s == section) {
            Some(i) => i,
            None => {
                self.ledger.push((section.to_string(), Tally::default()));
                self.ledger.len() - 1
            }
        };
        self.current = Some((i, Instant::now()));
    }

    /// Stops the clock of the current section.
    pub fn pause(&mut self) {
        if let Some((i, since)) = self.current.take() {
            self.ledger[i].1.wall_seconds += since.elapsed().as_secs_f64();
        }
    }

    fn add(&mut self, stats: RunStats) {
        let Some((i, _)) = self.current else {
            return;
        };
        let s = &mut self.ledger[i].1.stats;
        s.computed += stats.computed;
        s.reused += stats.reused;
        s.case_seconds += stats.case_seconds;
    }

    /// Runs the cases `keys` (in their fixed order) of the store's benchmark `store_name`:
    /// loads the finished ones, computes the rest of this run's shard with `compute` in
    /// parallel, saves each at once, and counts them for the current section. All records
    /// in key order, or `None` if this run covers one shard only.
    pub fn cases<P, R, F>(
        &mut self,
        store_name: &str,
        keys: &[P],
        compute: F,
    ) -> Result<Option<Vec<R>>>
    where
        P: Serialize + Sync,
        R: Serialize + DeserializeOwned + Send,
        F: Fn(&P) -> Result<R> + Sync,
    {
        let store = BenchmarkStore::new(&self.store.root, store_name);
        let run = run_cases(&store, self.store.shard, keys, compute)?;
        self.add(RunStats::of(&run));
        Ok(run.complete())
    }

    /// Computes `count` cases outside the store (pictures, scene checks) with `f`, counted for
    /// the current section as computed.
    pub fn compute<R>(&mut self, count: usize, f: impl FnOnce() -> Result<R>) -> Result<R> {
        let clock = Instant::now();
        let r = f()?;
        self.add(RunStats {
            computed: count,
            reused: 0,
            case_seconds: clock.elapsed().as_secs_f64(),
        });
        Ok(r)
    }

    /// Cases of `section` so far.
    pub fn stats(&self, section: &str) -> RunStats {
        self.tally(section).stats
    }

    /// What `section` cost so far (zero if it never ran).
    pub fn tally(&self, section: &str) -> Tally {
        let mut t = self
            .ledger
            .iter()
            .find(|(s, _)| s == section)
            .map(|(_, t)| *t)
            .unwrap_or_default();
        if let Some((i, since)) = self.current {
            if self.ledger[i].0 == section {
                t.wall_seconds += since.elapsed().as_secs_f64();
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A case: the store key.
    #[derive(Serialize)]
    struct Key {
        n: u32,
    }

    /// Its record.
    #[derive(Serialize, serde::Deserialize, Debug, PartialEq)]
    struct Doubled {
        v: u32,
    }

    fn keys(ns: &[u32]) -> Vec<Key> {
        ns.iter().map(|&n| Key { n }).collect()
    }

    /// Runs `ns` through the store `double` of `cx`; the doubled values, if complete.
    fn double(cx: &mut Context, ns: &[u32]) -> Option<Vec<u32>> {
        cx.cases("double", &keys(ns), |k| Ok(Doubled { v: 2 * k.n }))
            .unwrap()
            .map(|r| r.into_iter().map(|d| d.v).collect())
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("slender-context-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn the_ledger_counts_what_each_section_computed_and_reused() {
        let root = scratch("ledger");
        let store = StoreOptions {
            root: root.join("store"),
            shard: None,
        };
        let mut cx = Context::new(&root, Layout::PerSection, &store, true);
        cx.enter("a");
        assert_eq!(double(&mut cx, &[1, 2, 3]), Some(vec![2, 4, 6]));
        // Two of these are in the store already; two are new.
        assert_eq!(double(&mut cx, &[3, 4, 1, 5]), Some(vec![6, 8, 2, 10]));
        cx.compute(2, || Ok(())).unwrap();
        cx.enter("b");
        assert_eq!(double(&mut cx, &[5]), Some(vec![10]));
        cx.pause();
        let a = cx.tally("a").stats;
        assert_eq!((a.computed, a.reused), (3 + 2 + 2, 2));
        let b = cx.stats("b");
        assert_eq!((b.computed, b.reused), (0, 1));
        assert_eq!(cx.stats("never"), RunStats::default());
        assert_eq!(cx.dir("a"), root.join("a"));
        let _ = std::fs::remove_dir_all(&root);
    }

    #[test]
    fn a_shard_counts_its_own_cases_and_returns_no_records() {
        let root = scratch("shard");
        let store = StoreOptions {
            root: root.join("store"),
            shard: Some("1/2".parse().unwrap()),
        };
        let mut cx = Context::new(&root, Layout::Flat, &store, false);
        cx.enter("a");
        assert_eq!(double(&mut cx, &[1, 2, 3, 4, 5]), None);
        assert_eq!(cx.stats("a").computed, 2);
        assert_eq!(cx.dir("a"), root);
        let _ = std::fs::remove_dir_all(&root);
    }
}
