//! The scene files of `examples/` as a benchmark: each solved in-process from its file; the
//! reactions must balance the loads, and the cantilever and the shell strip written as scenes
//! must reproduce the benchmarks. No sweep and no store: the cases are the examples, computed
//! on every run (and not in a shard run: they belong to the report).

use anyhow::Result;
use slender_validation::cantilever::Check;

use super::{words, Benchmark, Context, SectionSpec};
use crate::solve::checks::{scene_checks, EXAMPLES};

/// Section (no files of its own).
const SECTION: &str = "scenes";

/// The scene examples.
pub struct Scenes;

impl Benchmark for Scenes {
    /// The checks, measured while solving.
    type Records = Vec<Check>;

    fn sections(&self) -> Vec<SectionSpec> {
        vec![SectionSpec {
            dir: SECTION.into(),
            title: "Scene files: the examples".into(),
            about: "Every scene in examples/ solved from its file: the reactions at the \
                    supports must balance the applied loads (forces and moments), and the \
                    cantilever written as a scene must reproduce the benchmark's Δy/Δx."
                .into(),
            caption: words,
        }]
    }

    fn records(&self, cx: &mut Context) -> Result<Option<Vec<Check>>> {
        if cx.shard().is_some() {
            return Ok(None);
        }
        cx.enter(SECTION);
        Ok(Some(cx.compute(EXAMPLES.len(), scene_checks)?))
    }

    fn write(&self, _: &Vec<Check>, _: &mut Context) -> Result<()> {
        Ok(())
    }

    fn checks(&self, checks: &Vec<Check>, _: &mut Context) -> Result<Vec<Check>> {
        Ok(checks.clone())
    }
}
