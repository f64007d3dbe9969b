//! `slender solve` on a scene with a `[time]` table: the rods stepped in time by the core's
//! [`TimeRun`], every `output_every` steps a frame written like an equilibrium step
//! (`step_NNN/`: result.json with the frame's time and energies — and, with contact, its
//! contacts —, CSV, VTK, glTF, plus a `shape.vtp`), a ParaView collection `frames.pvd` of
//! the frames' `shape.vtp` with their times, `frames.gltf` (every frame as one animated glTF:
//! morph targets at the frames' times, [`super::gltf_animation`]) and `frames.csv` (time,
//! energies, tip and centroid of every rod, convergence; with contact the smallest gaps and
//! the number of active contacts).
//!
//! A time step that does not converge stops the run: no frame is written for it, its row in
//! `frames.csv` says `converged = false` with the reason, `report.json` says so, and the
//! exit code is 1.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use serde::Serialize;
use slender_core::scene::{CompiledScene, SceneStep, TimeRun};

use crate::output::write_atomic;

use super::{preview, step_dir, write_step, write_summaries_with, Outcome};

/// The `time` object of `report.json`.
#[derive(Serialize)]
pub(super) struct TimeSummary {
    scheme: &'static str,
    dt: f64,
    /// Steps the run asked for.
    steps: usize,
    /// Steps taken (fewer if one failed).
    steps_taken: usize,
    /// Time reached (s).
    t_end: f64,
    output_every: usize,
    frames: usize,
    converged: bool,
    /// Why the run stopped early, if it did.
    failure: Option<String>,
    /// Largest |E(t) − E(0)| over the frames, relative to the largest kinetic energy.
    max_relative_energy_change: f64,
    /// Largest kinetic energy over the frames (J).
    max_kinetic: f64,
}

fn scheme_name(s: slender_core::dynamics::Scheme) -> &'static str {
    use slender_core::dynamics::Scheme;
    match s {
        Scheme::EnergyConserving => "energy_conserving",
        Scheme::ImplicitMidpoint => "midpoint",
        Scheme::BackwardEuler => "backward_euler",
    }
}

/// Steps the scene in time and writes its frames into `dir`.
pub(super) fn solve_time_into(
    scene: &CompiledScene,
    dir: &Path,
    preview_on: bool,
) -> Result<Outcome> {
    let clock = Instant::now();
    let mut run = TimeRun::new(scene).map_err(|e| anyhow::anyhow!("{e}"))?;
    let time = *run.time_params();
    let names: Vec<String> = scene.rods.iter().map(|r| r.name.clone()).collect();
    let contact = scene.contact.is_some();
    let mut frames: Vec<SceneStep> = Vec::new();
    let mut csv = frames_header(&names, contact);
    let mut failure = None;
    let mut t_frame = Instant::now();
    let mut write_frame = |run: &TimeRun, frames: &mut Vec<SceneStep>, csv: &mut String| {
        let mut f = run.frame(frames.len());
        f.seconds = t_frame.elapsed().as_secs_f64();
        t_frame = Instant::now();
        frames_row(csv, &f, None, contact);
        write_step(scene, dir, &f)?;
        write_atomic(
            &step_dir(dir, f.step).join("shape.vtp"),
            super::vtk::rods_to_vtp(&scene.rods, &f.rods).as_bytes(),
        )?;
        frames.push(f);
        anyhow::Ok(())
    };
    write_frame(&run, &mut frames, &mut csv)?;
    while !run.finished() {
        let out = run.step();
        if !out.converged {
            let reason = out.failure.unwrap_or_default();
            failed_row(
                &mut csv,
                frames.len(),
                run.steps_taken() + 1,
                out.time,
                out.iterations,
                6 * names.len() + if contact { 3 } else { 0 },
                &reason,
            );
            failure = Some(reason);
            break;
        }
        if time.is_frame(run.steps_taken()) {
            write_frame(&run, &mut frames, &mut csv)?;
        }
    }
    let converged = failure.is_none();
    write_atomic(&dir.join("frames.csv"), csv.as_bytes())?;
    write_atomic(
        &dir.join("frames.pvd"),
        pvd(&frames, failure.as_deref()).as_bytes(),
    )?;
    write_atomic(
        &dir.join("frames.gltf"),
        &serde_json::to_vec(&super::gltf_animation::frames_to_gltf(
            &scene.rods,
            &frames,
            super::gltf::scene_up(scene.gravity),
        ))?,
    )?;
    let energies: Vec<_> = frames
        .iter()
        .filter_map(|f| f.time.as_ref().map(|t| t.energy))
        .collect();
    let max_kinetic = energies.iter().map(|e| e.kinetic).fold(0.0, f64::max);
    let e0 = energies.first().map_or(0.0, |e| e.total);
    let change = energies
        .iter()
        .map(|e| (e.total - e0).abs())
        .fold(0.0, f64::max);
    let summary = TimeSummary {
        scheme: scheme_name(time.params.scheme),
        dt: time.params.dt,
        steps: time.steps,
        steps_taken: run.steps_taken(),
        t_end: run.time(),
        output_every: time.output_every,
        frames: frames.len(),
        converged,
        failure: failure.clone(),
        max_relative_energy_change: if max_kinetic > 0.0 {
            change / max_kinetic
        } else {
            change
        },
        max_kinetic,
    };
    write_summaries_with(
        dir,
        &frames,
        converged,
        clock.elapsed().as_secs_f64(),
        Some(summary),
    )?;
    if preview_on {
        preview::write_preview(scene, &frames, &dir.join("preview"))?;
    }
    if let Some(f) = &failure {
        eprintln!("error: {f}");
    }
    Ok(if converged {
        Outcome::Ok
    } else {
        Outcome::NotConverged
    })
}

fn frames_header(names: &[String], contact: bool) -> String {
    let mut s = String::from(
        "frame,time_step,t,kinetic,elastic,gravity_and_loads,potential,total,converged,iterations",
    );
    if contact {
        s.push_str(",min_gap,min_segment_gap,contacts");
    }
    for n in names {
        for what in ["tip", "centroid"] {
            for c in ["x", "y", "z"] {
                let _ = write!(s, ",{n}_{what}_{c}");
            }
        }
    }
    s.push_str(",failure\n");
    s
}

fn frames_row(s: &mut String, f: &SceneStep, failure: Option<&str>, contact: bool) {
    let t = f.time.as_ref().expect("a time frame");
    let e = &t.energy;
    let _ = write!(
        s,
        "{},{},{:e},{:e},{:e},{:e},{:e},{:e},{},{}",
        t.frame,
        t.time_step,
        t.t,
        e.kinetic,
        e.elastic,
        e.gravity_and_loads,
        e.potential,
        e.total,
        t.converged,
        t.iterations
    );
    if contact {
        let cell = |v: Option<f64>| v.map_or(String::new(), |g| format!("{g:e}"));
        let n = f.obstacles.iter().map(|o| o.contacts.len()).sum::<usize>()
            + f.segment_contacts.as_ref().map_or(0, Vec::len);
        let _ = write!(s, ",{},{},{n}", cell(f.min_gap), cell(f.min_segment_gap));
    }
    for r in &f.rods {
        let tip = r.positions.last().copied().unwrap_or([f64::NAN; 3]);
        let n = r.positions.len() as f64;
        let mut c = [0.0; 3];
        for p in &r.positions {
            for k in 0..3 {
                c[k] += p[k] / n;
            }
        }
        for v in tip.iter().chain(&c) {
            let _ = write!(s, ",{v:e}");
        }
    }
    let _ = writeln!(s, ",{}", quote(failure.unwrap_or("")));
}

fn failed_row(
    s: &mut String,
    frame: usize,
    time_step: usize,
    t: f64,
    iterations: usize,
    empty: usize,
    reason: &str,
) {
    // No state to report: the energies, contacts and positions are left empty.
    let _ = write!(s, "{frame},{time_step},{t:e},,,,,,false,{iterations}");
    for _ in 0..empty {
        s.push(',');
    }
    let _ = writeln!(s, ",{}", quote(reason));
}

fn quote(text: &str) -> String {
    if text.is_empty() {
        String::new()
    } else {
        format!("\"{}\"", text.replace('"', "\"\"").replace('\n', " "))
    }
}

fn xml_escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace("--", "- -")
}

/// The ParaView collection of the frames' `shape.vtp` files with their times.
fn pvd(frames: &[SceneStep], failure: Option<&str>) -> String {
    let mut s =
        String::from("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n");
    if let Some(f) = failure {
        let _ = writeln!(
            s,
            "<!-- the run stopped early, after the last frame listed: {} -->",
            xml_escape(f)
        );
    }
    s.push_str("  <Collection>\n");
    for f in frames {
        let t = f.time.as_ref().map_or(0.0, |t| t.t);
        let _ = writeln!(
            s,
            "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"step_{:03}/shape.vtp\"/>",
            f.step
        );
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}
