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
pub const EXAMPLES: [(&str, &str); 21] = [
    (
        "rod_models_cantilever",
        include_str!("../../../../examples/rod_models_cantilever.toml"),
    ),
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
    (
        "flat_cable_shell_cantilever",
        include_str!("../../../../examples/flat_cable_shell_cantilever.toml"),
    ),
    (
        "flat_cable_two_connectors",
        include_str!("../../../../examples/flat_cable_two_connectors.toml"),
    ),
    (
        "pinned_pinned_column",
        include_str!("../../../../examples/pinned_pinned_column.toml"),
    ),
    (
        "clamped_pinned_column",
        include_str!("../../../../examples/clamped_pinned_column.toml"),
    ),
    (
        "sliding_clip_cable",
        include_str!("../../../../examples/sliding_clip_cable.toml"),
    ),
    (
        "hanging_ring",
        include_str!("../../../../examples/hanging_ring.toml"),
    ),
    (
        "follower_cantilever",
        include_str!("../../../../examples/follower_cantilever.toml"),
    ),
    (
        "branched_harness",
        include_str!("../../../../examples/branched_harness.toml"),
    ),
    (
        "swinging_cable",
        include_str!("../../../../examples/swinging_cable.toml"),
    ),
    (
        "cable_over_bracket",
        include_str!("../../../../examples/cable_over_bracket.toml"),
    ),
    (
        "cable_dropped_on_bracket",
        include_str!("../../../../examples/cable_dropped_on_bracket.toml"),
    ),
    (
        "flat_cable_on_bracket",
        include_str!("../../../../examples/flat_cable_on_bracket.toml"),
    ),
    (
        "cable_through_rings",
        include_str!("../../../../examples/cable_through_rings.toml"),
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

/// Solves every example: one balance check per example with rods (worst relative force or
/// moment imbalance over its steps, target ≤ 1e-9; NaN if a step did not converge; for a
/// time-stepped example instead its energy conservation, see [`time_check`]) or with
/// strips only (their clamps' force, with their contacts', against the loads, ≤ 1e-6: the clamp force is a
/// Richardson-extrapolated energy difference), the
/// cantilever-benchmark check (relative difference of Δy/Δx, target ≤ 1e-10) and the two
/// shell-strip checks of [`shell_example_checks`].
pub fn scene_checks() -> Result<Vec<Check>> {
    let mut checks = Vec::new();
    for (name, text) in EXAMPLES {
        let spec = parse_scene(text, Syntax::Toml, name)?;
        let compiled = match spec.compile() {
            Ok(c) => c,
            Err(e) => bail!("{name}: {e}"),
        };
        if compiled.time.is_some() {
            checks.push(if compiled.contact.is_some() {
                contact_time_check(name, &compiled)?
            } else {
                time_check(name, &compiled)?
            });
            continue;
        }
        let (mut solver, first) = SceneSolver::new(&spec, &compiled);
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
        // Rod reactions only; a shell strip's clamp force is checked in shell_example_checks.
        if !compiled.rods.is_empty() {
            checks.push(check(
                format!(
                    "{name}: reactions balance the loads (worst relative imbalance, {} steps)",
                    steps.len()
                ),
                measured,
                "≤ 1e-9",
                measured <= 1e-9,
            ));
        }
        // Strips clamped at both ends or resting on obstacles: their clamps (and contacts)
        // carry the loads (the cantilever strip has its own checks in shell_example_checks).
        if compiled.rods.is_empty() && name != "flat_cable_shell_cantilever" {
            let worst = steps
                .iter()
                .flat_map(|s| &s.shells)
                .map(|s| s.relative_force_imbalance)
                .fold(0.0, f64::max);
            let measured = if converged { worst } else { f64::NAN };
            checks.push(check(
                format!(
                    "{name}: the strips' clamp forces (and contact forces) balance the loads (worst relative imbalance, {} steps)",
                    steps.len()
                ),
                measured,
                "≤ 1e-6",
                measured <= 1e-6,
            ));
        }
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
    checks.push(capstan_check()?);
    checks.extend(shell_example_checks()?);
    Ok(checks)
}

/// The capstan benchmark (`slender_validation::capstan`, its own scene, solved by its `run`):
/// at the end of each of its two pulls, the ratio of the pulled leg's tension to the held
/// leg's against e^{μπ} (the worse relative error; NaN unless every step converged and every
/// contact slides on Coulomb's cone against the slide), target [`capstan::TOLERANCE`].
fn capstan_check() -> Result<Check> {
    use slender_validation::capstan;
    let spec = parse_scene(capstan::SCENE, Syntax::Toml, "capstan")?;
    let (measured, ratios, mu) = match capstan::run(spec) {
        Ok(pulls) => {
            let all_slide = pulls
                .iter()
                .all(|(_, m)| m.contacts > 0 && m.sliding_against_the_slide == m.contacts);
            let worst = pulls
                .iter()
                .map(|(_, m)| m.relative_error())
                .fold(0.0, f64::max);
            let ratios: Vec<String> = pulls
                .iter()
                .map(|(_, m)| format!("{:.4}", m.ratio()))
                .collect();
            let mu = pulls.first().map_or(f64::NAN, |(_, m)| m.mu);
            let measured = if all_slide { worst } else { f64::NAN };
            (measured, ratios.join(" and "), mu)
        }
        Err(e) => (f64::NAN, format!("none ({e})"), f64::NAN),
    };
    Ok(check(
        format!(
            "capstan: a cable sliding over a rough bar (μ = {mu}, θ = π), pulled one way then the other: legs' tension ratios {ratios} vs e^(μπ) = {:.4}, worse relative error",
            capstan::capstan_ratio(mu, std::f64::consts::PI)
        ),
        measured,
        &format!("≤ {:e}", capstan::TOLERANCE),
        measured <= capstan::TOLERANCE,
    ))
}

/// A time-stepped example (undamped, energy-conserving scheme): the largest change of the
/// total energy over every step, relative to the largest kinetic energy, target ≤ 1e-5
/// (NaN if a step did not converge).
fn time_check(name: &str, compiled: &slender_core::scene::CompiledScene) -> Result<Check> {
    use slender_core::scene::TimeRun;
    let mut run = TimeRun::new(compiled).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let e0 = run.energy().total;
    let mut change: f64 = 0.0;
    let mut kinetic: f64 = 0.0;
    let mut converged = true;
    while !run.finished() {
        if !run.step().converged {
            converged = false;
            break;
        }
        let e = run.energy();
        change = change.max((e.total - e0).abs());
        kinetic = kinetic.max(e.kinetic);
    }
    let measured = if converged && kinetic > 0.0 {
        change / kinetic
    } else {
        f64::NAN
    };
    Ok(check(
        format!(
            "{name}: time stepping ({} steps), max |E(t) − E(0)| / max kinetic energy",
            run.steps_taken()
        ),
        measured,
        "≤ 1e-5",
        measured <= 1e-5,
    ))
}

/// A time-stepped example with contact (damped, so that it comes to rest): no penetration —
/// every gap to an obstacle and between segments positive after every step — and, at the end,
/// the supports' reactions and the contact forces balancing the loads: |Σ| / Σ|applied|,
/// target ≤ 1e-6 (the time steps' Newton tolerance, 1e-10 of a force scale that includes the
/// inertial forces, limits it; NaN if a step did not converge or a gap closed).
fn contact_time_check(name: &str, compiled: &slender_core::scene::CompiledScene) -> Result<Check> {
    use slender_core::scene::TimeRun;
    let mut run = TimeRun::new(compiled).map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
    let mut ok = true;
    let mut lowest = f64::INFINITY;
    while !run.finished() {
        if !run.step().converged {
            ok = false;
            break;
        }
        let f = run.frame(run.steps_taken());
        for g in [f.min_gap, f.min_segment_gap].into_iter().flatten() {
            lowest = lowest.min(g);
        }
    }
    let last = run.frame(run.steps_taken());
    let mut total = [0.0; 3];
    let mut applied = 0.0;
    for r in &last.rods {
        applied += norm(r.applied_force);
        add(&mut total, r.applied_force);
        for s in &r.supports {
            add(&mut total, s.force);
        }
    }
    for o in &last.obstacles {
        add(&mut total, o.force);
    }
    let measured = if ok && lowest > 0.0 {
        norm(total) / applied
    } else {
        f64::NAN
    };
    Ok(check(
        format!(
            "{name}: time stepping with contact ({} steps): no gap closed (smallest {lowest:.2e} m), at rest |supports + contacts + loads| / |loads|",
            run.steps_taken()
        ),
        measured,
        "≤ 1e-6",
        measured <= 1e-6,
    ))
}

fn add(a: &mut [f64; 3], b: [f64; 3]) {
    for k in 0..3 {
        a[k] += b[k];
    }
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The shell-strip example against the heavy-elastica master curve: relative error of the
/// centre line's Δy/Δx, target ≤ 1 % (the shell's accuracy at n_L = 15 with ν = 0); and its
/// clamp force against the weight, target ≤ 1e-6 (the force is a finite-difference
/// derivative of the energy, good to ~1e-8, not the 1e-9 of the rods' exact reactions).
fn shell_example_checks() -> Result<Vec<Check>> {
    use slender_core::scene::shells::centre_line_ratio;
    use slender_validation::cantilever::master_curve::master_ratio;
    let (_, text) = EXAMPLES
        .iter()
        .find(|(name, _)| *name == "flat_cable_shell_cantilever")
        .expect("the shell example is listed");
    let scene = parse_scene(text, Syntax::Toml, "flat_cable_shell_cantilever")?;
    let compiled = match scene.compile() {
        Ok(c) => c,
        Err(e) => bail!("flat_cable_shell_cantilever: {e}"),
    };
    let spec = &scene.shells[0];
    let m = &spec.material;
    let nu = m.poisson.unwrap_or(0.0);
    let d = m.young * spec.thickness.powi(3) / (12.0 * (1.0 - nu * nu));
    let g = slender_core::geometry::Vec3::from(scene.gravity).norm();
    let gamma = m.density * spec.thickness * g * spec.length.powi(3) / d;
    let (_, step) = SceneSolver::new(&scene, &compiled);
    let shell = &step.shells[0];
    let master = master_ratio(gamma)?;
    let error = (centre_line_ratio(shell) - master) / master;
    let measured = if shell.converged {
        error.abs()
    } else {
        f64::NAN
    };
    let balance = if shell.converged {
        shell.relative_force_imbalance
    } else {
        f64::NAN
    };
    Ok(vec![
        check(
            format!("flat_cable_shell_cantilever (shell strip, 15 × 2, ν = 0, Γ = {gamma:.3}): |Δy/Δx error| vs the heavy-elastica master curve"),
            measured,
            "≤ 1e-2",
            measured <= 1e-2,
        ),
        check(
            "flat_cable_shell_cantilever: clamp force (energy derivative on the held vertices) vs the weight, relative".into(),
            balance,
            "≤ 1e-6",
            balance <= 1e-6,
        ),
        bspline_strip_check(&scene, gamma, master)?,
    ])
}

/// The same strip as a C¹ B-spline patch (`model = "bspline"`) on 8 × 1 elements: its Δy/Δx
/// against the master curve and its clamp force against the weight (the worse of the two
/// relative errors; target 1 %).
fn bspline_strip_check(
    scene: &slender_core::scene::Scene,
    gamma: f64,
    master: f64,
) -> Result<Check> {
    use slender_core::scene::shells::centre_line_ratio;
    use slender_core::scene::spec::ShellModelSpec;
    let mut scene = scene.clone();
    let strip = &mut scene.shells[0];
    strip.model = Some(ShellModelSpec::Bspline);
    strip.elements = Some(8);
    strip.width_elements = Some(1);
    strip.grading = None;
    let compiled = match scene.compile() {
        Ok(c) => c,
        Err(e) => bail!("flat_cable_shell_cantilever as a B-spline strip: {e}"),
    };
    let (_, step) = SceneSolver::new(&scene, &compiled);
    let shell = &step.shells[0];
    let error = ((centre_line_ratio(shell) - master) / master).abs();
    let measured = if shell.converged {
        error.max(shell.relative_force_imbalance)
    } else {
        f64::NAN
    };
    Ok(check(
        format!("flat_cable_shell_cantilever with model = \"bspline\" (8 × 1, Γ = {gamma:.3}): worse of |Δy/Δx error| vs the master curve and the clamp force's relative imbalance"),
        measured,
        "≤ 1e-2",
        measured <= 1e-2,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_check_passes() {
        let checks = scene_checks().unwrap();
        // One balance (or, time-stepped, energy) check per rod example, the benchmark check,
        // the capstan check, three shell checks.
        assert_eq!(checks.len(), EXAMPLES.len() - 1 + 5);
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
