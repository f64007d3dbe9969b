//! `slender`: physically validated equilibria of slender elastic structures.
//!
//! Layout: [`commands`] (one file per subcommand: flags and dispatch), [`benchmarks`] (one
//! module per benchmark, all of one shape: cases → store → checks → figures → report
//! section), [`view`] (the interactive page), [`report`] (the acceptance table and the page), [`store`] (the resumable result
//! store), [`plot`], [`solve`] (scene files).

mod benchmarks;
mod commands;
mod output;
#[allow(dead_code)]
mod plot;
mod progress;
mod report;
mod solve;
mod store;
mod view;

use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

use commands::{
    bend_twist, cantilever, lateral_buckling, master_curve, merge, models, scene_schema,
    sensitivity, solve as solve_cmd, stick_slip, validate, view as view_cmd,
};

/// Large deformations of cables, hoses and flat cables, with the validation to prove them.
#[derive(Parser, Debug)]
#[command(name = "slender", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// The cantilever benchmark (seed §3, Fig. 2): Δy/Δx against Γ, every discretization
    /// against the heavy-elastica master curve.
    Cantilever(cantilever::CantileverArgs),
    /// The bend–twist bifurcation benchmark (seed §4, Figs. 6–8): 2-D or 3-D over a grid in
    /// (X, Y), decided by the seed's protocol and by stability, against the master curve.
    BendTwist(bend_twist::BendTwistArgs),
    /// The rod models side by side (seed §2, Fig. 5): the cantilever, its order of convergence,
    /// Greenhill's column and the bend–twist grid on the discrete elastic rod, the discrete
    /// Cosserat rod and the SE(3) beam, with their acceptance checks (the `models` section of
    /// `slender validate`; exit code 1 if a target fails).
    Models(models::ModelsArgs),
    /// The bend–twist master curve alone at chosen Y and GJ/EI: the critical X_c1, X_c2 from
    /// the linearized stability ODE (CSV, table, PNG + SVG), no rod discretization.
    MasterCurve(master_curve::MasterCurveArgs),
    /// Run every benchmark and write the validation report OUT/index.html with a pass/fail
    /// table of the acceptance targets (exit code 1 if a target fails).
    Validate(validate::ValidateArgs),
    /// Combine result stores (e.g. of `--shard` runs) into one.
    Merge(merge::MergeArgs),
    /// Equilibria of a scene file (TOML or JSON): shapes (VTK, glTF, PNG), frames, strains,
    /// reactions and solver reports (JSON, CSV); prescribed support motion in steps.
    Solve(solve_cmd::SolveArgs),
    /// Print (or write with --out) the JSON Schema of the scene format.
    SceneSchema(scene_schema::SceneSchemaArgs),
    /// The lateral-buckling benchmark (seed §5): a heavy strip with its width along gravity,
    /// 2-D or 3-D over (w/L, Γ_shell) by the seed's protocol and by stability.
    LateralBuckling(lateral_buckling::LateralBucklingArgs),
    /// The sensitivity study of the lateral-buckling protocol (seed §5.3, Fig. 12): the
    /// percentage of correct 2-D/3-D decisions against the plate master curve, for every
    /// combination of Ω, n_L, m_ls and σ, as box plots.
    Sensitivity(sensitivity::SensitivityArgs),
    /// Stick–slip (Romero's fourth benchmark): a rod released on a rough inclined plane, over
    /// rods of several decades of stiffness and Γ, μ and tan α/μ around 1; stick/slide
    /// decisions, displacements and accelerations against Coulomb's law.
    StickSlip(stick_slip::StickSlipArgs),
    /// The interactive cable-editing page: starts a local server and prints its URL; drag
    /// supports, add clips, change gravity, see reactions, bend radius and stability live.
    View(view_cmd::ViewArgs),
}

/// Runs a subcommand; `Ok(false)`: it ran but something failed (exit code 1).
fn run(cli: Cli) -> Result<bool> {
    match &cli.command {
        Command::Cantilever(a) => cantilever::run(a),
        Command::BendTwist(a) => bend_twist::run(a),
        Command::Models(a) => models::run(a),
        Command::MasterCurve(a) => master_curve::run(a),
        Command::Validate(a) => validate::run(a),
        Command::Merge(a) => merge::run(a),
        Command::Solve(a) => solve_cmd::run(a),
        Command::SceneSchema(a) => scene_schema::run(a),
        Command::LateralBuckling(a) => lateral_buckling::run(a),
        Command::Sensitivity(a) => sensitivity::run(a),
        Command::StickSlip(a) => stick_slip::run(a),
        Command::View(a) => view_cmd::run(a),
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
