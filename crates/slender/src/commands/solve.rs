//! `slender solve`: equilibria of a scene file; the work is in [`crate::solve`].

use anyhow::Result;

use crate::solve::Outcome;
pub use crate::solve::SolveArgs;

/// Solves the scene, prints the summary and the verdict; `false` if a step did not converge
/// or an equilibrium is unstable (exit code 1: the outputs are written and say which).
pub fn run(a: &SolveArgs) -> Result<bool> {
    let outcome = crate::solve::run(a)?;
    let through = crate::solve::print_summary(&a.out)?;
    println!("wrote {}", a.out.display());
    let timed = a.out.join("frames.csv").exists();
    match outcome {
        Outcome::Ok if timed => {
            println!("verdict: every time step converged (frames.csv, frames.pvd, step_*/)");
            Ok(true)
        }
        Outcome::NotConverged if timed => {
            eprintln!(
                "error: a time step did not converge; the run stopped there (see frames.csv and report.json)"
            );
            Ok(false)
        }
        Outcome::Ok if through > 0 => {
            // Converged and stable, but the shape is the coarse mesh's, not the cable's.
            println!(
                "verdict: every step converged to a stable equilibrium, but rod edges or strip faces run through obstacles between their vertices (WARNING above): refine the mesh there"
            );
            Ok(true)
        }
        Outcome::Ok => {
            println!("verdict: every step converged to a stable equilibrium");
            Ok(true)
        }
        Outcome::Unstable => {
            eprintln!(
                "verdict: UNSTABLE — some equilibrium has negative Hessian eigenvalues and was kept (unstable = \"keep\", or follower loads: the Hessian is the frozen loads' and none of its modes is followed); see steps.csv and report.json"
            );
            Ok(false)
        }
        Outcome::NotConverged => {
            eprintln!("error: some step did not converge; see solver.csv and report.json");
            Ok(false)
        }
    }
}
