//! `slender solve`: equilibria of a scene file; the work is in [`crate::solve`].

use anyhow::Result;

pub use crate::solve::SolveArgs;

/// Solves the scene, prints the summary; `false` if a step did not converge.
pub fn run(a: &SolveArgs) -> Result<bool> {
    let ok = crate::solve::run(a)?;
    crate::solve::print_summary(&a.out)?;
    println!("wrote {}", a.out.display());
    if !ok {
        eprintln!("error: some step did not converge; see solver.csv and report.json");
    }
    Ok(ok)
}
