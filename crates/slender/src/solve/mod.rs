//! `slender solve SCENE --out DIR`: equilibria of a scene file and their output files.
//!
//! Everything is written into a temporary directory next to DIR and renamed at the end, so a
//! bad scene or an interrupted run leaves no partial output.

pub mod checks;
pub mod gltf;
pub mod gltf_animation;
pub mod mesh_file;
pub mod preview;
pub mod scene_io;
pub mod time;
pub mod vtk;

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use serde::Serialize;
use slender_core::scene::solve::SceneSolver;
use slender_core::scene::{CompiledScene, SceneStep};

use crate::output::{write_atomic, write_csv};

/// Marker that a directory was written by `slender solve` (it may then be replaced).
const MARKER: &str = "report.json";

/// Options of `slender solve`.
#[derive(clap::Args, Debug)]
pub struct SolveArgs {
    /// Scene file (.toml, or .json).
    pub scene: PathBuf,
    /// Output directory (replaced if it holds a previous `slender solve` output).
    #[arg(long, default_value = "out/solve")]
    pub out: PathBuf,
    /// Skip the PNG/SVG preview (faster).
    #[arg(long)]
    pub no_preview: bool,
}

/// Prints the JSON Schema of the scene format, or writes it to `out`.
pub fn write_schema(out: Option<&Path>) -> Result<()> {
    let text = serde_json::to_string_pretty(&scene_io::scene_schema())? + "\n";
    match out {
        Some(p) => write_atomic(p, text.as_bytes()),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

/// Runs `slender solve`. Ok(false): outputs written but some step did not converge.
pub fn run(args: &SolveArgs) -> Result<Outcome> {
    let scene = scene_io::read_scene(&args.scene)?;
    let compiled = scene
        .compile()
        .map_err(|e| anyhow::anyhow!("{}: {e}", args.scene.display()))?;
    check_out_dir(&args.out)?;
    let tmp = temp_dir_for(&args.out)?;
    let result = if compiled.time.is_some() {
        time::solve_time_into(&compiled, &tmp, !args.no_preview)
    } else {
        solve_into(&scene, &compiled, &tmp, !args.no_preview)
    };
    match result {
        Ok(ok) => {
            if args.out.exists() {
                fs::remove_dir_all(&args.out)
                    .with_context(|| format!("replacing {}", args.out.display()))?;
            }
            fs::rename(&tmp, &args.out)
                .with_context(|| format!("renaming {} to {}", tmp.display(), args.out.display()))?;
            Ok(ok)
        }
        Err(e) => {
            let _ = fs::remove_dir_all(&tmp);
            Err(e)
        }
    }
}

/// Refuses an output directory that holds something other than a previous solve's output.
fn check_out_dir(out: &Path) -> Result<()> {
    if out.exists() {
        if !out.is_dir() {
            bail!("--out {}: exists and is not a directory", out.display());
        }
        let empty = fs::read_dir(out)?.next().is_none();
        if !empty && !out.join(MARKER).exists() {
            bail!(
                "--out {}: directory is not empty and was not written by `slender solve` (no {MARKER}); choose another directory",
                out.display()
            );
        }
    }
    Ok(())
}

fn temp_dir_for(out: &Path) -> Result<PathBuf> {
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let parent = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    fs::create_dir_all(&parent).with_context(|| format!("creating {}", parent.display()))?;
    let tmp = parent.join(format!(".{name}.partial-{}", std::process::id()));
    if tmp.exists() {
        fs::remove_dir_all(&tmp)?;
    }
    fs::create_dir(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
    Ok(tmp)
}

/// One row of `steps.csv`: the solve time and outcome of every step.
#[derive(Serialize)]
struct StepRow {
    step: usize,
    stage: Option<usize>,
    stage_fraction: f64,
    seconds: f64,
    pieces: usize,
    converged: bool,
    iterations: usize,
    max_residual: f64,
    max_relative_force_imbalance: f64,
    max_relative_moment_imbalance: f64,
    /// Every equilibrium of the step is stable (null modes allowed).
    stable: bool,
    /// Largest number of unstable modes of an equilibrium of the step.
    unstable_modes: usize,
    /// An unstable equilibrium was met and its unstable mode followed to a stable one.
    followed_unstable_mode: bool,
    /// Rod edges whose centerline, and strip faces whose mid-surface, runs through an obstacle
    /// between their vertices (a mesh coarser than the obstacle: see `SceneStep::edges_through_obstacles`).
    edges_through_obstacles: usize,
}

/// One row of `solver.csv`.
#[derive(Serialize)]
struct SolverRow {
    step: usize,
    rod: String,
    part: usize,
    converged: bool,
    reason: String,
    iterations: usize,
    load_steps: usize,
    rejected_steps: usize,
    residual: f64,
    relative_residual: f64,
    energy: f64,
    inertia_negative: Option<usize>,
    inertia_zero: Option<usize>,
    inertia_positive: Option<usize>,
    lambda_min: Option<f64>,
    lambda_min_normalized: Option<f64>,
}

/// One row of `reactions.csv`.
#[derive(Serialize)]
struct ReactionRow {
    step: usize,
    rod: String,
    support: usize,
    kind: String,
    vertex: usize,
    x: f64,
    y: f64,
    z: f64,
    fx: f64,
    fy: f64,
    fz: f64,
    mx: f64,
    my: f64,
    mz: f64,
}

/// One row of `<rod>_vertices.csv`.
#[derive(Serialize)]
struct VertexRow {
    vertex: usize,
    x: f64,
    y: f64,
    z: f64,
    kappa1: f64,
    kappa2: f64,
    twist: f64,
    /// Mean axial strain of the adjacent edges.
    strain: f64,
}

/// One row of `<shell>_vertices.csv`.
#[derive(Serialize)]
struct ShellVertexRow {
    vertex: usize,
    /// Station along the length (0 at the clamp).
    station: usize,
    /// Column across the width.
    column: usize,
    x: f64,
    y: f64,
    z: f64,
}

/// One row of `<rod>_edges.csv`.
#[derive(Serialize)]
struct EdgeRow {
    edge: usize,
    strain: f64,
    m1x: f64,
    m1y: f64,
    m1z: f64,
    m2x: f64,
    m2y: f64,
    m2z: f64,
    tx: f64,
    ty: f64,
    tz: f64,
}

/// Summary written to `report.json`.
#[derive(Serialize)]
struct Report<'a> {
    converged: bool,
    /// Every equilibrium of every step is stable.
    stable: bool,
    steps: usize,
    total_seconds: f64,
    /// Per step: everything but the per-vertex arrays.
    summary: Vec<StepSummary<'a>>,
    /// Time stepping (`[time]` scenes only): the run and how it ended.
    #[serde(skip_serializing_if = "Option::is_none")]
    time: Option<time::TimeSummary>,
}

#[derive(Serialize)]
struct StepSummary<'a> {
    step: usize,
    stage: Option<usize>,
    seconds: f64,
    pieces: usize,
    converged: bool,
    stable: bool,
    rods: Vec<RodSummary<'a>>,
    structures: &'a [slender_core::scene::StructureResult],
    shells: Vec<ShellSummary<'a>>,
    /// Rod edges and strip faces running through an obstacle between their vertices (absent
    /// when none).
    #[serde(skip_serializing_if = "<[_]>::is_empty")]
    edges_through_obstacles: &'a [slender_core::scene::EdgeThroughObstacle],
}

/// A shell strip in `report.json`: solver report, total load and clamp force (no moment).
#[derive(Serialize)]
struct ShellSummary<'a> {
    name: &'a str,
    converged: bool,
    elements: [usize; 2],
    applied_force: [f64; 3],
    clamp_force: [f64; 3],
    relative_force_imbalance: f64,
    rod_predictor_used: bool,
    report: &'a slender_core::solver::SolveReport,
}

#[derive(Serialize)]
struct RodSummary<'a> {
    name: &'a str,
    converged: bool,
    supports: &'a [slender_core::scene::SupportResult],
    applied_force: [f64; 3],
    applied_moment: [f64; 3],
    relative_force_imbalance: f64,
    relative_moment_imbalance: f64,
    reports: &'a [slender_core::solver::SolveReport],
}

fn solve_into(
    spec: &slender_core::scene::Scene,
    scene: &CompiledScene,
    dir: &Path,
    preview: bool,
) -> Result<Outcome> {
    let clock = Instant::now();
    let t0 = Instant::now();
    let (mut solver, mut first) = SceneSolver::new(spec, scene);
    first.seconds = t0.elapsed().as_secs_f64();
    let mut steps = vec![first];
    write_step(scene, dir, &steps[0])?;
    for k in 1..=solver.motion_steps() {
        let t = Instant::now();
        let mut step = solver.run_motion_step(k);
        step.seconds = t.elapsed().as_secs_f64();
        write_step(scene, dir, &step)?;
        let failed = !step.converged;
        steps.push(step);
        if failed {
            // Later steps would start from a state that is not an equilibrium.
            break;
        }
    }
    let converged = steps.iter().all(|s| s.converged) && steps.len() == solver.motion_steps() + 1;
    let stable = steps.iter().all(|s| s.stable);
    write_summaries(dir, &steps, converged, clock.elapsed().as_secs_f64())?;
    if preview {
        preview::write_preview(scene, &steps, &dir.join("preview"))?;
    }
    Ok(if !converged {
        Outcome::NotConverged
    } else if !stable {
        Outcome::Unstable
    } else {
        Outcome::Ok
    })
}

/// How a scene solve ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Every step converged to a stable equilibrium.
    Ok,
    /// Every step converged, but some equilibrium is unstable (kept as the scene asked).
    Unstable,
    /// Some step did not converge.
    NotConverged,
}

fn step_dir(dir: &Path, step: usize) -> PathBuf {
    dir.join(format!("step_{step:03}"))
}

fn write_step(scene: &CompiledScene, dir: &Path, step: &SceneStep) -> Result<()> {
    let d = step_dir(dir, step.step);
    write_atomic(&d.join("result.json"), &serde_json::to_vec_pretty(step)?)?;
    for r in &step.rods {
        let rows: Vec<VertexRow> = (0..r.positions.len())
            .map(|i| VertexRow {
                vertex: i,
                x: r.positions[i][0],
                y: r.positions[i][1],
                z: r.positions[i][2],
                kappa1: r.curvature[i][0],
                kappa2: r.curvature[i][1],
                twist: r.twist[i],
                strain: {
                    let adjacent: Vec<f64> = [i.checked_sub(1), Some(i)]
                        .into_iter()
                        .flatten()
                        .filter_map(|j| r.edge_strain.get(j).copied())
                        .collect();
                    adjacent.iter().sum::<f64>() / adjacent.len() as f64
                },
            })
            .collect();
        write_csv(&d.join(format!("{}_vertices.csv", r.name)), &rows)?;
        let rows: Vec<EdgeRow> = r
            .frames
            .iter()
            .zip(&r.edge_strain)
            .enumerate()
            .map(|(j, (f, &strain))| EdgeRow {
                edge: j,
                strain,
                m1x: f[0][0],
                m1y: f[0][1],
                m1z: f[0][2],
                m2x: f[1][0],
                m2y: f[1][1],
                m2z: f[1][2],
                tx: f[2][0],
                ty: f[2][1],
                tz: f[2][2],
            })
            .collect();
        write_csv(&d.join(format!("{}_edges.csv", r.name)), &rows)?;
    }
    for sh in &step.shells {
        let rows: Vec<ShellVertexRow> = sh
            .positions
            .iter()
            .enumerate()
            .map(|(v, p)| ShellVertexRow {
                vertex: v,
                station: v / (sh.elements[1] + 1),
                column: v % (sh.elements[1] + 1),
                x: p[0],
                y: p[1],
                z: p[2],
            })
            .collect();
        write_csv(&d.join(format!("{}_vertices.csv", sh.name)), &rows)?;
    }
    let title = format!("slender step {}", step.step);
    write_atomic(
        &d.join("shape.vtk"),
        vtk::rods_to_vtk(&title, &scene.rods, &step.rods, &step.shells).as_bytes(),
    )?;
    write_atomic(
        &d.join("shape.gltf"),
        &serde_json::to_vec(&gltf::rods_to_gltf(
            &scene.rods,
            &step.rods,
            &step.shells,
            gltf::scene_up(scene.gravity),
        ))?,
    )?;
    Ok(())
}

/// The `solver.csv` row of one solve (`rod` is the rod's or the shell's name).
fn solver_row(
    step: usize,
    name: &str,
    part: usize,
    rep: &slender_core::solver::SolveReport,
) -> SolverRow {
    SolverRow {
        step,
        rod: name.to_string(),
        part,
        converged: rep.converged(),
        reason: match &rep.status {
            slender_core::solver::SolveStatus::Converged => String::new(),
            slender_core::solver::SolveStatus::NotConverged { reason } => reason.clone(),
        },
        iterations: rep.iterations,
        load_steps: rep.load_steps,
        rejected_steps: rep.rejected_steps,
        residual: rep.residual,
        relative_residual: rep.relative_residual,
        energy: rep.energy,
        inertia_negative: rep.inertia.map(|i| i.negative),
        inertia_zero: rep.inertia.map(|i| i.zero),
        inertia_positive: rep.inertia.map(|i| i.positive),
        lambda_min: rep.lambda_min,
        lambda_min_normalized: rep.lambda_min_normalized,
    }
}

fn write_summaries(dir: &Path, steps: &[SceneStep], converged: bool, total: f64) -> Result<()> {
    write_summaries_with(dir, steps, converged, total, None)
}

fn write_summaries_with(
    dir: &Path,
    steps: &[SceneStep],
    converged: bool,
    total: f64,
    time: Option<time::TimeSummary>,
) -> Result<()> {
    let mut step_rows = Vec::new();
    let mut solver_rows = Vec::new();
    let mut reaction_rows = Vec::new();
    for s in steps {
        let mut iterations = 0;
        let mut max_residual: f64 = 0.0;
        let mut max_f: f64 = 0.0;
        let mut max_m: f64 = 0.0;
        for r in &s.rods {
            max_f = max_f.max(r.relative_force_imbalance);
            max_m = max_m.max(r.relative_moment_imbalance);
            for (part, rep) in r.reports.iter().enumerate() {
                iterations += rep.iterations;
                max_residual = max_residual.max(rep.residual);
                solver_rows.push(solver_row(s.step, &r.name, part, rep));
            }
            for sup in &r.supports {
                reaction_rows.push(ReactionRow {
                    step: s.step,
                    rod: r.name.clone(),
                    support: sup.support,
                    kind: format!("{:?}", sup.kind).to_lowercase(),
                    vertex: sup.vertex,
                    x: sup.position[0],
                    y: sup.position[1],
                    z: sup.position[2],
                    fx: sup.force[0],
                    fy: sup.force[1],
                    fz: sup.force[2],
                    mx: sup.moment[0],
                    my: sup.moment[1],
                    mz: sup.moment[2],
                });
            }
        }
        for sh in &s.shells {
            let rep = &sh.report;
            iterations += rep.iterations;
            max_residual = max_residual.max(rep.residual);
            solver_rows.push(solver_row(s.step, &sh.name, 0, rep));
            max_f = max_f.max(sh.relative_force_imbalance);
        }
        step_rows.push(StepRow {
            step: s.step,
            stage: s.stage,
            stage_fraction: s.stage_fraction,
            seconds: s.seconds,
            pieces: s.pieces,
            converged: s.converged,
            iterations,
            max_residual,
            max_relative_force_imbalance: max_f,
            max_relative_moment_imbalance: max_m,
            stable: s.stable,
            unstable_modes: s
                .structures
                .iter()
                .map(|x| x.stability.unstable_modes)
                .max()
                .unwrap_or(0),
            followed_unstable_mode: s
                .structures
                .iter()
                .any(|x| x.stability.followed_unstable_mode),
            edges_through_obstacles: s.edges_through_obstacles.len(),
        });
    }
    write_csv(&dir.join("steps.csv"), &step_rows)?;
    write_csv(&dir.join("solver.csv"), &solver_rows)?;
    write_csv(&dir.join("reactions.csv"), &reaction_rows)?;
    let report = Report {
        converged,
        stable: steps.iter().all(|s| s.stable),
        steps: steps.len(),
        total_seconds: total,
        time,
        summary: steps
            .iter()
            .map(|s| StepSummary {
                step: s.step,
                stage: s.stage,
                seconds: s.seconds,
                pieces: s.pieces,
                converged: s.converged,
                stable: s.stable,
                structures: &s.structures,
                edges_through_obstacles: &s.edges_through_obstacles,
                rods: s
                    .rods
                    .iter()
                    .map(|r| RodSummary {
                        name: &r.name,
                        converged: r.converged,
                        supports: &r.supports,
                        applied_force: r.applied_force,
                        applied_moment: r.applied_moment,
                        relative_force_imbalance: r.relative_force_imbalance,
                        relative_moment_imbalance: r.relative_moment_imbalance,
                        reports: &r.reports,
                    })
                    .collect(),
                shells: s
                    .shells
                    .iter()
                    .map(|r| ShellSummary {
                        name: &r.name,
                        converged: r.converged,
                        elements: r.elements,
                        applied_force: r.applied_force,
                        clamp_force: r.clamp_force,
                        relative_force_imbalance: r.relative_force_imbalance,
                        rod_predictor_used: r.rod_predictor_used,
                        report: &r.report,
                    })
                    .collect(),
            })
            .collect(),
    };
    write_atomic(&dir.join(MARKER), &serde_json::to_vec_pretty(&report)?)?;
    Ok(())
}

/// One line per step for the terminal (per frame, at most about 20 lines, for a time-stepped
/// scene). Returns the number of rod edges and strip faces that run through an obstacle, over the steps.
pub fn print_summary(out: &Path) -> Result<usize> {
    let frames = out.join("frames.csv");
    if frames.exists() {
        let text = fs::read_to_string(frames)?;
        let mut r = csv::Reader::from_reader(text.as_bytes());
        let rows: Vec<csv::StringRecord> = r.records().collect::<Result<_, _>>()?;
        println!("frame  time step  t (s)       kinetic (J)  total energy (J)  converged");
        let every = rows.len().div_ceil(20).max(1);
        for (k, row) in rows.iter().enumerate() {
            if k % every == 0 || k + 1 == rows.len() {
                println!(
                    "{:>5}  {:>9}  {:<10}  {:<11}  {:<16}  {}",
                    &row[0], &row[1], &row[2], &row[3], &row[7], &row[8]
                );
            }
        }
        return Ok(0);
    }
    let text = fs::read_to_string(out.join("steps.csv"))?;
    let mut total_through = 0;
    let mut r = csv::Reader::from_reader(text.as_bytes());
    println!(
        "step  converged  stability             seconds   pieces  rel. force/moment imbalance"
    );
    for row in r.records() {
        let row = row?;
        // A step that did not converge is no equilibrium: its stability is not known.
        let stability = match (&row[5], &row[10], &row[11], &row[12]) {
            ("false", ..) => "— (no equilibrium)".to_string(),
            (_, "true", _, "true") => "stable (followed)".to_string(),
            (_, "true", _, _) => "stable".to_string(),
            (_, _, n, _) => format!("UNSTABLE ({n} modes)"),
        };
        println!(
            "{:>4}  {:>9}  {:<20}  {:>8.3}  {:>6}  {:.1e} / {:.1e}",
            &row[0],
            &row[5],
            stability,
            row[3].parse::<f64>().unwrap_or(f64::NAN),
            &row[4],
            row[8].parse::<f64>().unwrap_or(f64::NAN),
            row[9].parse::<f64>().unwrap_or(f64::NAN),
        );
        let through: usize = row.get(13).and_then(|c| c.parse().ok()).unwrap_or(0);
        total_through += through;
        if through > 0 {
            println!(
                "      WARNING: {through} element(s) (rod edges, strip faces) run through an \
                 obstacle between their vertices (contact acts at vertices): mesh finer than \
                 the obstacle; see edges_through_obstacles in step_{:0>3}/result.json",
                &row[0]
            );
        }
    }
    Ok(total_through)
}
