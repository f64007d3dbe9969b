//! The validation report: the acceptance table (`checks.csv`, `checks.md`, printed) and the
//! page `index.html` with one section per benchmark part.

pub mod checks;
mod page;

pub use page::{write_report, Report};

use crate::benchmarks::{SectionSpec, Tally};

/// One section of the page: what a benchmark says about it, and what it cost in this run.
pub struct Section {
    /// Directory, title, description, captions.
    pub spec: SectionSpec,
    /// Wall time and cases computed and reused.
    pub tally: Tally,
}
