//! Progress reporting: a bar with ETA on a terminal, plain log lines otherwise (CI logs).

use std::io::IsTerminal;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};

/// Counts finished work items and shows it.
pub struct Progress {
    bar: Option<ProgressBar>,
    done: AtomicUsize,
    total: usize,
    label: String,
    start: Instant,
}

impl Progress {
    /// A progress display for `total` items.
    pub fn new(label: &str, total: usize) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let b = ProgressBar::new(total as u64);
            b.set_style(
                ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} ({eta} left)")
                    .expect("static template")
                    .progress_chars("=> "),
            );
            b.set_message(label.to_string());
            b
        });
        Self {
            bar,
            done: AtomicUsize::new(0),
            total,
            label: label.to_string(),
            start: Instant::now(),
        }
    }

    /// Marks one item finished.
    pub fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        match &self.bar {
            Some(b) => b.inc(1),
            None => {
                // About ten lines per run in logs.
                let step = (self.total / 10).max(1);
                if done.is_multiple_of(step) || done == self.total {
                    eprintln!(
                        "{}: {done}/{} done ({:.1} s)",
                        self.label,
                        self.total,
                        self.start.elapsed().as_secs_f64()
                    );
                }
            }
        }
    }

    /// Removes the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
