//! The benchmarks, all of one shape: cases → records in the result store → checks → figures
//! → a report section.
//!
//! A benchmark is a value implementing [`Benchmark`] (one module per benchmark). `slender
//! validate` runs the list of [`suite`] in turn; the single-benchmark commands (`slender
//! cantilever`, `bend-twist`, `lateral-buckling`, `sensitivity`, `stick-slip`) build the same objects from
//! their flags and run them without the checks.
//!
//! - Adding a benchmark: a module here implementing [`Benchmark`] (its cases and store keys,
//!   records, files and figures, checks, sections with captions), an entry in [`suite`], and,
//!   if it has a command of its own, a file in `crate::commands` and a variant in `main.rs`.
//! - Adding a model axis to a benchmark (e.g. the rod model of the cantilever): a field of the
//!   benchmark's struct (set by `suite` and by its command's flags) and of its store key
//!   struct, so that records of different models never mix; sections per model, if wanted,
//!   come from [`Benchmark::sections`]. A comparison across models is a benchmark of its own
//!   whose cases are the other benchmarks' keys for each model: the store hands them over as
//!   reused records.

pub mod bend_twist;
pub mod cantilever;
mod context;
pub mod lateral_buckling;
pub mod rod_models;
pub mod scenes;
pub mod sensitivity;
pub mod stick_slip;

use anyhow::Result;
use clap::ValueEnum;
use slender_validation::cantilever::Check;
use slender_validation::rod_model::RodModel;

pub use context::{Context, Layout, Tally};

/// Sweep sizes.
#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum Preset {
    /// What CI runs.
    Quick,
    /// The paper-size sweeps.
    Full,
}

impl Preset {
    /// `quick` or `full`.
    pub fn name(self) -> &'static str {
        match self {
            Preset::Quick => "quick",
            Preset::Full => "full",
        }
    }
}

/// One part of the report page: a benchmark's output directory, what it shows, and the
/// captions of its figures.
pub struct SectionSpec {
    /// Subdirectory of the report with the section's files (and its name in the ledger).
    pub dir: String,
    /// Title.
    pub title: String,
    /// What it checks, one sentence.
    pub about: String,
    /// Caption of the figure with file stem `stem`, naming the seed's figure it reproduces.
    pub caption: fn(stem: &str) -> String,
}

/// A benchmark of the seed.
pub trait Benchmark: Sync {
    /// What the cases produce once every one is finished.
    type Records;

    /// The report sections, in page order (their `dir`s are [`Context::dir`]'s sections).
    fn sections(&self) -> Vec<SectionSpec>;

    /// Cases → records: every case through the store, and with [`Context::validating`] the
    /// cases the checks need. `None` if this run computes one shard only.
    fn records(&self, cx: &mut Context) -> Result<Option<Self::Records>>;

    /// Figures, data files and the printed summary of the records.
    fn write(&self, records: &Self::Records, cx: &mut Context) -> Result<()>;

    /// The acceptance checks (rows of the table of `slender validate`), in table order.
    fn checks(&self, records: &Self::Records, cx: &mut Context) -> Result<Vec<Check>>;
}

/// A benchmark of any records type, for lists of benchmarks.
pub trait AnyBenchmark: Sync {
    /// See [`Benchmark::sections`].
    fn sections(&self) -> Vec<SectionSpec>;
    /// Records, then files, then (when validating) the checks; `None` if this run computes one
    /// shard only (no files, no checks).
    fn run(&self, cx: &mut Context) -> Result<Option<Vec<Check>>>;
}

impl<B: Benchmark> AnyBenchmark for B {
    fn sections(&self) -> Vec<SectionSpec> {
        Benchmark::sections(self)
    }

    fn run(&self, cx: &mut Context) -> Result<Option<Vec<Check>>> {
        let Some(records) = self.records(cx)? else {
            cx.pause();
            return Ok(None);
        };
        self.write(&records, cx)?;
        let checks = if cx.validating() {
            self.checks(&records, cx)?
        } else {
            Vec::new()
        };
        cx.pause();
        Ok(Some(checks))
    }
}

/// The benchmarks of `slender validate` with `preset`, in report order.
pub fn suite(preset: Preset) -> Vec<Box<dyn AnyBenchmark>> {
    vec![
        Box::new(cantilever::Cantilever::validation()),
        Box::new(bend_twist::BendTwist::for_preset(preset)),
        Box::new(rod_models::RodModels::for_preset(preset)),
        Box::new(lateral_buckling::LateralBuckling::validation(
            preset,
            slender_validation::shell_model::ShellModel::Midedge,
        )),
        Box::new(lateral_buckling::LateralBuckling::validation(
            preset,
            slender_validation::shell_model::ShellModel::Bspline,
        )),
        Box::new(sensitivity::Sensitivity::for_preset(preset)),
        Box::new(stick_slip::StickSlip::for_preset(preset)),
        Box::new(scenes::Scenes),
    ]
}

/// Whether `model` is the discrete elastic rod: store keys leave the model out for it, so
/// that its keys and records are those of before the rod models (`serde(skip_serializing_if)`).
pub fn is_der(model: &RodModel) -> bool {
    *model == RodModel::Der
}

/// `, <model label>` in figure titles of a rod model other than the discrete elastic rod
/// (whose titles stay as before the rod models).
pub fn model_suffix(model: RodModel) -> String {
    if is_der(&model) {
        String::new()
    } else {
        format!(", {}", model.label())
    }
}

/// A file stem in words, the caption of a figure with nothing more to say.
pub fn words(stem: &str) -> String {
    stem.replace('_', " ")
}
