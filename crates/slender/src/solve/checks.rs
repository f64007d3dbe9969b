//! Acceptance checks of the scene examples, for `slender validate`: every example (embedded
//! in the binary) solved in-process; reactions must balance the loads, and the rod-core
//! cantilever written as a scene must reproduce the benchmark.

use anyhow::{bail, Result};
use slender_core::scene::solve::SceneSolver;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::{end_point_ratio, CantileverCase, Check, MeshKind};
use slender_validation::materials::OMEGA_ROD;

use super::scene_io::{parse_scene, Syntax};

/// The examples of `examples/`, embedded so that validation needs no files.
pub const EXAMPLES: [(&str, &str); 7] = [
    (
        "cantilever_tip_force",
        include_str!("../../../../examples/cantilever_tip_force.toml"),
    ),
    (
        "hanging_cable",
        include_str!("../../../../examples/hanging_cable.toml"),
    ),
    (
        "u_cable_moved",
        include_str!("../../../../examples/u_cable_moved.toml"),
    ),
    (
        "coiled_cable_lifted",
        include_str!("../../../../examples/coiled_cable_lifted.toml"),
    ),
    (
        "flat_cable_corner",
        include_str!("../../../../examples/flat_cable_corner.toml"),
    ),
    (
        "cantilever_benchmark",
        include_str!("../../../../examples/cantilever_benchmark.toml"),
    ),
    (
        "clipped_cable",
        include_str!("../../../../examples/clipped_cable.toml"),
    ),
];

fn check(description: String, measured: f64, target: &str, passed: bool) -> Check {
    Check {
        benchmark: "scenes".into(),
        description,
        measured,
        target: target.into(),
        passed: passed && measured.is_finite(),
    }
}

/// Solves every example: one balance check per example (worst relative force or moment
/// imbalance over its steps, target ≤ 1e-9; NaN if a step did not converge) and the
/// cantilever-benchmark check (relative difference of Δy/Δx, target ≤ 1e-10).
pub fn scene_checks() -> Result<Vec<Check>> {
    let mut checks = Vec::new();
    for (name, text) in EXAMPLES {
        let compiled = match parse_scene(text, Syntax::Toml, name)?.compile() {
            Ok(c) => c,
            Err(e) => bail!("{name}: {e}"),
        };
        let (mut solver, first) = SceneSolver::new(&compiled);
        let mut steps = vec![first];
        for k in 1..=solver.motion_steps() {
            steps.push(solver.run_motion_step(k));
        }
        let converged = steps.iter().all(|s| s.converged);
        let worst = steps
            .iter()
            .flat_map(|s| &s.rods)
            .map(|r| r.relative_force_imbalance.max(r.relative_moment_imbalance))
            .fold(0.0, f64::max);
        let measured = if converged { worst } else { f64::NAN };
        checks.push(check(
            format!(
                "{name}: reactions balance the loads (worst relative imbalance, {} steps)",
                steps.len()
            ),
            measured,
            "≤ 1e-9",
            measured <= 1e-9,
        ));
        if name == "cantilever_benchmark" {
            let p: Vec<_> = steps[0].rods[0]
                .positions
                .iter()
                .map(|p| slender_core::geometry::Vec3::from(*p))
                .collect();
            let ratio = end_point_ratio(&p);
            let case = CantileverCase {
                material: OMEGA_ROD,
                mesh: MeshKind::Graded,
                n_elements: 20,
                gamma: 10.0,
            };
            let tight = SolverParams {
                force_tolerance: 1e-14,
                energy_tolerance: 1e-30,
                ..SolverParams::default()
            };
            let run = case.run(&tight)?;
            let diff = ((ratio - run.ratio) / run.ratio).abs();
            let measured = if converged && run.report.converged() {
                diff
            } else {
                f64::NAN
            };
            checks.push(check(
                "cantilever as a scene vs the rod-core benchmark (Ω_rod, graded, N = 20, Γ = 10): relative difference of Δy/Δx".into(),
                measured,
                "≤ 1e-10",
                measured <= 1e-10,
            ));
        }
    }
    Ok(checks)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_check_passes() {
        let checks = scene_checks().unwrap();
        assert_eq!(checks.len(), EXAMPLES.len() + 1);
        for c in &checks {
            eprintln!("{:e}  {}", c.measured, c.description);
            assert!(
                c.passed,
                "{}: {} (target {})",
                c.description, c.measured, c.target
            );
        }
    }

    #[test]
    fn the_embedded_examples_are_the_example_files() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
        let n = std::fs::read_dir(&dir)
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .path()
                    .extension()
                    .is_some_and(|x| x == "toml")
            })
            .count();
        assert_eq!(n, EXAMPLES.len(), "embed every example in EXAMPLES");
    }
}
