//! `slender validate`: runs the benchmarks on their default grids and prints a pass/fail
//! table of the acceptance targets.

use std::path::Path;
use std::time::Instant;

use anyhow::Result;
use slender_core::solver::SolverParams;
use slender_validation::bend_twist::acceptance::bend_twist_checks;
use slender_validation::bend_twist::sweep::BendTwistSweep;
use slender_validation::cantilever::{
    cantilever_checks, shell_cantilever_checks, CantileverSweep, Check, ShellCantileverSweep,
};
use slender_validation::lateral_sweep::sensitivity::SensitivityStudy;
use slender_validation::lateral_sweep::{
    branch_switch_checks, convergence_checks, decision_checks, sensitivity_checks,
    LateralBucklingSweep,
};
use slender_validation::materials::{OMEGA_SHELL, SHELL_SETS};

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
    let lb_clock = Instant::now();
    let lb_dir = out.join("lateral-buckling");
    // The protocol on the default grid at n_L = 8 (quick and full) and n_L = 30 (full), and
    // the convergence of Γ_c at w/L ∈ {0.1, 0.5, 1} (meshes up to 30, or 60 in full).
    let lateral_sweep = LateralBucklingSweep::default_grid(OMEGA_SHELL, 8);
    let lateral = crate::lateral_sweep_report::run(&lateral_sweep, &lb_dir, store)?;
    let fine_sweep = LateralBucklingSweep::default_grid(OMEGA_SHELL, 30);
    let fine_dir = out.join("lateral-buckling-n30");
    let fine_clock = Instant::now();
    let fine = if full {
        Some(crate::lateral_sweep_report::run(
            &fine_sweep,
            &fine_dir,
            store,
        )?)
    } else {
        None
    };
    let fine_seconds = fine_clock.elapsed().as_secs_f64();
    let meshes: &[usize] = if full { &[15, 30, 60] } else { &[8, 15, 30] };
    let convergence = crate::lateral_sweep_report::run_convergence(
        OMEGA_SHELL,
        &[0.1, 0.5, 1.0],
        meshes,
        &lb_dir,
        store,
    )?;
    let lateral_sweep_seconds = lb_clock.elapsed().as_secs_f64();
    // The seed's §5.3 sensitivity study: a subset in quick, the 216 configurations in full.
    let study = if full {
        SensitivityStudy::full()
    } else {
        SensitivityStudy::quick()
    };
    let sens_clock = Instant::now();
    let sensitivity = crate::sensitivity_report::run(&study, &out.join("sensitivity"), store)?;
    let sensitivity_seconds = sens_clock.elapsed().as_secs_f64();
    let models_clock = Instant::now();
    let models = crate::model_comparison_report::run(&out.join("models"), store)?;
    let models_seconds = models_clock.elapsed().as_secs_f64();
    let (
        Some(cantilever),
        Some(bend_twist),
        Some(lateral),
        Some(convergence),
        Some(sensitivity),
        Some(models),
    ) = (
        cantilever,
        bend_twist,
        lateral,
        convergence,
        sensitivity,
        models,
    )
    else {
        crate::print_shard_done(store);
        return Ok(true);
    };
    let fine = match fine {
        Some(None) => {
            crate::print_shard_done(store);
            return Ok(true);
        }
        Some(Some(f)) => Some(f),
        None => None,
    };
    crate::cantilever_report::print_summary(&cantilever.summary);
    crate::bend_twist_report::print_summary(&bend_twist.summary);
    crate::model_comparison_report::print_summary(&models);
    let params = SolverParams::default();
    // Flat cables: the shell sets of the seed's Table 2 on the same Fig. 2 plot as the rods.
    let shell_clock = Instant::now();
    let shell_sweep = ShellCantileverSweep {
        gammas: sweep.gammas.clone(),
        element_counts: vec![8, 15, 30],
        width_ratio: 0.1,
        materials: SHELL_SETS.to_vec(),
    };
    let shell_records = crate::shell_cantilever_report::run(
        &shell_sweep,
        &cantilever.records,
        Some("bundle"),
        &out.join("cantilever-shell"),
    )?;
    crate::shell_cantilever_report::print_summary(&shell_records);
    let shell_checks = shell_cantilever_checks(&params)?;
    let shell_seconds = shell_clock.elapsed().as_secs_f64();
    crate::lateral_sweep_report::print_summary(&lateral);
    crate::lateral_sweep_report::print_convergence(&convergence);
    let lb_clock = Instant::now();
    let mut lateral_checks = crate::lateral_buckling_curves_report::run(&lb_dir)?;
    let grid = format!(
        "{} w/L × {} Γ_shell",
        lateral_sweep.width_ratios.len(),
        lateral_sweep.gammas.len()
    );
    lateral_checks.extend(decision_checks(&OMEGA_SHELL, 8, &grid, &lateral.score));
    if let Some(f) = &fine {
        crate::lateral_sweep_report::print_summary(f);
        lateral_checks.extend(decision_checks(&OMEGA_SHELL, 30, &grid, &f.score));
    }
    lateral_checks.extend(convergence_checks(&OMEGA_SHELL, &convergence));
    lateral_checks.extend(branch_switch_checks(
        OMEGA_SHELL,
        &lateral.critical,
        &slender_validation::lateral_sweep::solver_params(),
    )?);
    crate::sensitivity_report::print_summary(&sensitivity);
    lateral_checks.extend(sensitivity_checks(&sensitivity.scores));
    let lateral_seconds = lateral_sweep_seconds - fine_seconds + lb_clock.elapsed().as_secs_f64();
    let mut checks = cantilever_checks(&cantilever.records, &params)?;
    checks.extend(shell_checks);
    checks.extend(bend_twist_checks(&bend_twist.summary));
    checks.extend(models.checks.iter().cloned());
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
            sections: with_fine_section(vec![
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
                    title: "Cantilever under self-weight (flat cables, shells)".into(),
                    dir: "cantilever-shell".into(),
                    wall_seconds: shell_seconds,
                    stats: Default::default(),
                    about: "The same benchmark for strips of the seed's Table 2 (Ω_shell, Ω_IPS, \
                            Ω_combined), w/L = 0.1, n_L ∈ {8, 15, 30}, with the mid-edge director \
                            shell and the exact director clamp, against the heavy elastica with \
                            EI = D·w and with the narrow-strip stiffness E·w·h³/12."
                        .into(),
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
                    title: "Rod models side by side".into(),
                    dir: "models".into(),
                    wall_seconds: models_seconds,
                    stats: models.stats,
                    about: crate::model_comparison_report::about(&models),
                },
                Section {
                    title: "Lateral buckling of a heavy clamped strip".into(),
                    dir: "lateral-buckling".into(),
                    wall_seconds: lateral_seconds,
                    stats: Default::default(),
                    about: format!(
                        "The critical Γ_shell of a strip clamped with its width along gravity, against \
                         w/L (ν = {}), computed in code by two methods independent of any shell: the \
                         linear buckling load of the clamped Kirchhoff plate under its in-plane \
                         self-weight (Legendre Ritz), and the Vlasov warping-torsion beam with both \
                         weak-axis stiffness conventions (shooting and Hermite Ritz). Beside them the \
                         shell (Ω_shell, n_L = {}, square elements) over {} w/L × {} Γ_shell: Γ_c by \
                         bisection on the Hessian inertia and the seed's protocol (σ = {}, m_ls = {}, \
                         ε = {:e}).",
                        crate::lateral_buckling_curves_report::NU,
                        lateral_sweep.n_length,
                        lateral_sweep.width_ratios.len(),
                        lateral_sweep.gammas.len(),
                        lateral_sweep.sigma,
                        lateral_sweep.load_steps,
                        lateral_sweep.threshold
                    ),
                },
                Section {
                    title: "Sensitivity of the lateral-buckling protocol".into(),
                    dir: "sensitivity".into(),
                    wall_seconds: sensitivity_seconds,
                    stats: Default::default(),
                    about: format!(
                        "The seed's §5.3 study (Fig. 12): the share of correct 2-D/3-D decisions of \
                         the protocol over a (w/L, Γ/Γ_c) grid placed on the plate master curve, for \
                         {} configurations (Ω × n_L {:?} × m_ls {:?} × σ {:?}); w = L excluded from \
                         the score as in the seed.",
                        study.configurations().len(),
                        study.elements,
                        study.load_steps,
                        study.sigmas
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
            ], fine.is_some().then_some(fine_seconds), &fine_sweep),
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

/// Adds the n_L = 30 lateral-buckling section (full preset) after the n_L = 8 one.
fn with_fine_section(
    mut sections: Vec<Section>,
    seconds: Option<f64>,
    sweep: &LateralBucklingSweep,
) -> Vec<Section> {
    if let Some(wall_seconds) = seconds {
        let at = sections
            .iter()
            .position(|s| s.dir == "lateral-buckling")
            .map_or(sections.len(), |i| i + 1);
        sections.insert(
            at,
            Section {
                title: format!("Lateral buckling, n_L = {}", sweep.n_length),
                dir: "lateral-buckling-n30".into(),
                wall_seconds,
                stats: Default::default(),
                about: format!(
                    "The seed's protocol on the same {} w/L × {} Γ_shell grid with n_L = {} \
                     (the seed's Figs. 10–11 resolution).",
                    sweep.width_ratios.len(),
                    sweep.gammas.len(),
                    sweep.n_length
                ),
            },
        );
    }
    sections
}

/// A measured value for tables: fixed point, or scientific when small (a 1e-12 force
/// imbalance must not print as 0.00000).
pub(crate) fn format_measured(v: f64) -> String {
    if v != 0.0 && v.abs() < 1e-3 {
        format!("{v:.3e}")
    } else {
        format!("{v:.5}")
    }
}

fn print_table(checks: &[Check]) {
    for c in checks {
        println!(
            "{}  {:<11} {:>12}  target {:<8}  {}",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            format_measured(c.measured),
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
            "| {} | {} | {} | {} | {} |\n",
            if c.passed { "PASS" } else { "FAIL" },
            c.benchmark,
            c.description,
            format_measured(c.measured),
            c.target
        );
    }
    s
}
