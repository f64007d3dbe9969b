//! `slender validate`: runs the benchmarks on their default grids and prints a pass/fail
//! table of the acceptance targets.

use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use slender_core::solver::SolverParams;
use slender_validation::bend_twist::acceptance::bend_twist_checks;
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::{cantilever_checks, CantileverSweep, Check};

use crate::output::{write_atomic, write_csv};
use crate::report_html::{write_report, Report, Section};
use crate::store::runner::StoreOptions;

/// Runs the validation; returns whether every target passed. With a shard, computes that
/// shard of every sweep into the store and writes no report.
pub fn run(out: &Path, full: bool, store: &StoreOptions, jobs: usize) -> Result<bool> {
    let clock = Instant::now();
    let sweep = CantileverSweep::default();
    let cantilever = crate::cantilever_report::run(&sweep, &out.join("cantilever"), store)?;
    let cantilever_seconds = clock.elapsed().as_secs_f64();
    let bt_sweep = if full {
        BendTwistSweep::full()
    } else {
        BendTwistSweep::quick()
    };
    let bt_clock = Instant::now();
    let bend_twist = crate::bend_twist_report::run(&bt_sweep, &out.join("bend-twist"), store)?;
    let bend_twist_seconds = bt_clock.elapsed().as_secs_f64();
    let (Some(cantilever), Some(bend_twist)) = (cantilever, bend_twist) else {
        crate::print_shard_done(store);
        return Ok(true);
    };
    crate::cantilever_report::print_summary(&cantilever.summary);
    crate::bend_twist_report::print_summary(&bend_twist.summary);
    let lb_clock = Instant::now();
    let lateral_checks = crate::lateral_buckling_curves_report::run(&out.join("lateral-buckling"))?;
    let lateral_seconds = lb_clock.elapsed().as_secs_f64();
    let mut checks = cantilever_checks(&cantilever.records, &SolverParams::default())?;
    checks.extend(bend_twist_checks(&bend_twist.summary));
    checks.extend(lateral_checks);
    let scene_clock = Instant::now();
    checks.extend(crate::solve::checks::scene_checks()?);
    let scene_seconds = scene_clock.elapsed().as_secs_f64();
    write_csv(&out.join("checks.csv"), &checks)?;
    write_atomic(&out.join("checks.md"), markdown(&checks).as_bytes())?;
    println!();
    print_table(&checks);
    let failed = checks.iter().filter(|c| !c.passed).count();
    let page = write_report(
        out,
        &Report {
            checks: &checks,
            sections: vec![
                Section {
                    title: "Cantilever under self-weight (rods)".into(),
                    dir: "cantilever".into(),
                    wall_seconds: cantilever_seconds,
                    stats: cantilever.stats,
                    about: format!(
                        "Δy/Δx of a rod clamped horizontally, against the gravito-bending parameter Γ, \
                         for {} values of Γ in [{:.0e}, {:.0e}], element counts {:?}, three mesh \
                         families and two material sets; the master curve is the heavy elastica solved \
                         by multiple shooting.",
                        sweep.gammas.len(),
                        sweep.gammas.first().copied().unwrap_or(f64::NAN),
                        sweep.gammas.last().copied().unwrap_or(f64::NAN),
                        sweep.element_counts
                    ),
                },
                Section {
                    title: "Bend–twist bifurcation of a naturally curved rod".into(),
                    dir: "bend-twist".into(),
                    wall_seconds: bend_twist_seconds,
                    stats: bend_twist.stats,
                    about: format!(
                        "A coil clamped at the top, hanging under gravity: 2-D or 3-D over a {}×{} grid \
                         in (X, Y) with {}·Y elements, decided by the seed's protocol and by stability, \
                         against the master curve from the linearized stability ODE.",
                        bt_sweep.xs.len(),
                        bt_sweep.ys.len(),
                        bt_sweep.elements_per_turn
                    ),
                },
                Section {
                    title: "Lateral buckling of a heavy clamped strip: master curves".into(),
                    dir: "lateral-buckling".into(),
                    wall_seconds: lateral_seconds,
                    stats: Default::default(),
                    about: format!(
                        "The critical Γ_shell of a strip clamped with its width along gravity, against \
                         w/L (ν = {}), computed in code by two methods independent of any shell: the \
                         linear buckling load of the clamped Kirchhoff plate under its in-plane \
                         self-weight (Legendre Ritz), and the Vlasov warping-torsion beam with both \
                         weak-axis stiffness conventions (shooting and Hermite Ritz). The shell model \
                         and its lateral-buckling sweep are not in this version yet.",
                        crate::lateral_buckling_curves_report::NU
                    ),
                },
                Section {
                    title: "Scene files: the examples".into(),
                    dir: "scenes".into(),
                    wall_seconds: scene_seconds,
                    stats: Default::default(),
                    about: "Every scene in examples/ solved from its file: the reactions at the \
                            supports must balance the applied loads (forces and moments), and the \
                            cantilever written as a scene must reproduce the benchmark's Δy/Δx."
                        .into(),
                },
            ],
            preset: if full { "full" } else { "quick" },
            jobs,
            wall_seconds: clock.elapsed().as_secs_f64(),
        },
    )?;
    println!(
        "\n{} of {} targets passed ({:.1} s); report {}",
        checks.len() - failed,
        checks.len(),
        clock.elapsed().as_secs_f64(),
        page.display()
    );
    Ok(failed == 0)
}

fn print_table(checks: &[Check]) {
    for c in checks {
        println!(
            "{}  {:<11} {:>12.5}  target {:<8}  {}",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.measured,
            c.target,
            c.description
        );
    }
}

fn markdown(checks: &[Check]) -> String {
    let mut s =
        String::from("| result | benchmark | check | measured | target |\n|---|---|---|---|---|\n");
    for c in checks {
        s += &format!(
            "| {} | {} | {} | {:.5} | {} |\n",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.description,
            c.measured,
            c.target
        );
    }
    s
}
