//! The rod models side by side (seed §2, Fig. 5): the cantilever (error against Γ, order of
//! convergence, iterations and time per solve), Greenhill's heavy column and the bend–twist
//! grid on the discrete elastic rod, the discrete Cosserat rod (sine and tangent Darboux
//! vectors) and the SE(3) beam. A benchmark whose cases are, per model, cantilever solves,
//! Greenhill thresholds and the bend–twist benchmark's own store keys with the model set (so
//! the discrete elastic rod's bend–twist records are those of the bend–twist section, reused).

mod figures;

use std::sync::OnceLock;

use anyhow::Result;
use serde::{Deserialize, Serialize};
use slender_core::solver::SolverParams;
use slender_validation::bend_twist::acceptance::{summarize, BendTwistSummary};
use slender_validation::bend_twist::sweep::{BendTwistRecord, BendTwistSweep};
use slender_validation::cantilever::{CantileverCase, Check};
use slender_validation::materials::RodMaterialSet;
use slender_validation::model_comparison::{
    bend_twist_model_score, greenhill_threshold, model_checks, order_cases, orders_from_records,
    run_model_case, summarize_models, BendTwistModelScore, ModelCantileverRecord,
    ModelCantileverSweep, ModelConvergence, ModelSummary, GREENHILL,
};
use slender_validation::rod_model::RodModel;

use super::bend_twist::{grid_records, write_grid};
use super::{Benchmark, Context, Preset, SectionSpec};
use crate::output::{write_atomic, write_csv};

/// Section (and output directory).
const SECTION: &str = "models";
/// The store of cantilever solves per model.
const CANTILEVER_STORE: &str = "models-cantilever";
/// The store of Greenhill thresholds per model.
const GREENHILL_STORE: &str = "models-greenhill";
/// Elements of the Greenhill column (the checks' descriptions say 40).
const GREENHILL_ELEMENTS: usize = 40;
/// Largest Y of the bend–twist grid of the quick preset. The quick grid's two top rows
/// (Y = 6.6 and 10: 130–200 elements, Γ up to 2.5·10⁸) take three quarters of a shearable
/// model's time on the grid (≈ 100–150 s of 2-core wall time per model): `validate` would
/// take six minutes longer. Y = 4.3 keeps one point beyond the shear-tension limit.
const QUICK_MAX_Y: f64 = 5.0;

/// The comparison of rod models.
pub struct RodModels {
    /// The cantilever grid (models, Γ, N, meshes, material); the order-of-convergence cases
    /// (graded, N = 10…80, Γ = 1 and 100) are added to it.
    pub cantilever: ModelCantileverSweep,
    /// The bend–twist grid run on every model.
    pub bend_twist: BendTwistSweep,
    /// The section's description with the findings of this run, once written.
    findings: OnceLock<String>,
}

/// What the cases produced.
pub struct RodModelRecords {
    /// Cantilever solves: the grid, then the order cases not on it.
    cantilever: Vec<ModelCantileverRecord>,
    /// Per model, mesh and N.
    summary: Vec<ModelSummary>,
    /// Orders of convergence.
    orders: Vec<ModelConvergence>,
    /// Greenhill's Γ_c per model.
    greenhill: Vec<(RodModel, f64)>,
    /// Per model: the bend–twist records (sweep order) and their summary.
    bend_twist: Vec<(RodModel, Vec<BendTwistRecord>, BendTwistSummary)>,
    /// Per model: the bend–twist score against the master curve.
    scores: Vec<BendTwistModelScore>,
}

/// Everything a cantilever solve of the comparison depends on: the store key.
#[derive(Serialize)]
struct CantileverKey {
    model: RodModel,
    case: CantileverCase,
    solver: SolverParams,
}

/// Everything a Greenhill threshold depends on: the store key.
#[derive(Serialize)]
struct GreenhillKey {
    model: RodModel,
    material: RodMaterialSet,
    elements: usize,
    solver: SolverParams,
}

/// A stored Greenhill threshold.
#[derive(Serialize, Deserialize)]
struct GreenhillRecord {
    gamma_c: f64,
}

/// Greenhill row of `greenhill.csv`.
#[derive(Serialize)]
struct GreenhillRow {
    model: String,
    elements: usize,
    gamma_c: f64,
    relative_error: f64,
}

impl RodModels {
    /// The comparison of `slender validate` and `slender models`: every model; the cantilever
    /// on 25 values of Γ in [0.1, 10⁴], N ∈ {5, 10, 20, 50}, uniform and graded meshes, Ω_rod;
    /// the bend–twist quick grid (12 × 12, 20·Y elements) with `full`, its rows Y ≤ 5
    /// (12 × 10) with `quick` (see [`QUICK_MAX_Y`]). Not the seed's 25 × 25 grid at 100·Y:
    /// that is hours per shearable model.
    pub fn for_preset(preset: Preset) -> Self {
        let mut bend_twist = BendTwistSweep::quick();
        if preset == Preset::Quick {
            bend_twist.ys.retain(|&y| y <= QUICK_MAX_Y);
        }
        Self {
            cantilever: ModelCantileverSweep::default(),
            bend_twist,
            findings: OnceLock::new(),
        }
    }

    /// The cantilever cases: the grid, then the order cases not on it.
    fn cantilever_cases(&self) -> Vec<(RodModel, CantileverCase)> {
        let s = &self.cantilever;
        let mut cases = s.cases();
        for c in order_cases(&s.models, s.material) {
            if !cases.contains(&c) {
                cases.push(c);
            }
        }
        cases
    }
}

impl Benchmark for RodModels {
    type Records = RodModelRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let about = self.findings.get().cloned().unwrap_or_else(|| {
            "The seed's comparison of rod formulations (§2, Fig. 5) on slender's one solver: \
             the discrete elastic rod, the discrete Cosserat rod (sine and tangent Darboux \
             vectors) and the SE(3) beam on the cantilever, Greenhill's column and the \
             bend–twist grid."
                .into()
        });
        vec![SectionSpec {
            dir: SECTION.into(),
            title: "Rod models side by side".into(),
            about,
            caption: figures::caption,
        }]
    }

    fn records(&self, cx: &mut Context) -> Result<Option<RodModelRecords>> {
        cx.enter(SECTION);
        let solver = SolverParams::default();
        solver.validate()?;
        let models = &self.cantilever.models;
        let keys: Vec<CantileverKey> = self
            .cantilever_cases()
            .into_iter()
            .map(|(model, case)| CantileverKey {
                model,
                case,
                solver,
            })
            .collect();
        let cantilever = cx.cases(CANTILEVER_STORE, &keys, |k| {
            Ok(run_model_case(k.model, &k.case, &k.solver)?)
        })?;
        let keys: Vec<GreenhillKey> = models
            .iter()
            .map(|&model| GreenhillKey {
                model,
                material: self.cantilever.material,
                elements: GREENHILL_ELEMENTS,
                solver,
            })
            .collect();
        let greenhill = cx.cases(GREENHILL_STORE, &keys, |k| {
            Ok(GreenhillRecord {
                gamma_c: greenhill_threshold(k.model, k.material, k.elements, &k.solver)?,
            })
        })?;
        let mut bend_twist = Vec::new();
        for &model in models {
            bend_twist.push(grid_records(&self.bend_twist, model, cx)?);
        }
        let (Some(cantilever), Some(greenhill)) = (cantilever, greenhill) else {
            return Ok(None);
        };
        let Some(bend_twist) = bend_twist.into_iter().collect::<Option<Vec<_>>>() else {
            return Ok(None);
        };
        let grid = self.cantilever.cases().len();
        let summary = summarize_models(&cantilever[..grid]);
        let orders = orders_from_records(models, &cantilever);
        let bend_twist: Vec<_> = models
            .iter()
            .zip(bend_twist)
            .map(|(&m, records)| {
                let s = summarize(&records, self.bend_twist.elements_per_turn);
                (m, records, s)
            })
            .collect();
        let scores = bend_twist
            .iter()
            .map(|(m, records, _)| {
                bend_twist_model_score(m.name(), records, &self.cantilever.material)
            })
            .collect();
        Ok(Some(RodModelRecords {
            cantilever,
            summary,
            orders,
            greenhill: models
                .iter()
                .zip(greenhill)
                .map(|(&m, g)| (m, g.gamma_c))
                .collect(),
            bend_twist,
            scores,
        }))
    }

    fn write(&self, r: &RodModelRecords, cx: &mut Context) -> Result<()> {
        cx.enter(SECTION);
        let out = cx.dir(SECTION);
        std::fs::create_dir_all(&out)?;
        let grid = self.cantilever.cases().len();
        write_csv(&out.join("cantilever.csv"), &r.cantilever[..grid])?;
        write_csv(&out.join("cantilever_summary.csv"), &r.summary)?;
        write_atomic(
            &out.join("convergence.json"),
            serde_json::to_string_pretty(&r.orders)?.as_bytes(),
        )?;
        let rows: Vec<GreenhillRow> = r
            .greenhill
            .iter()
            .map(|&(m, g)| GreenhillRow {
                model: m.name().into(),
                elements: GREENHILL_ELEMENTS,
                gamma_c: g,
                relative_error: g / GREENHILL - 1.0,
            })
            .collect();
        write_csv(&out.join("greenhill.csv"), &rows)?;
        // Each model's bend–twist grid in its own folder, with the bend–twist section's files.
        for (model, records, summary) in &r.bend_twist {
            let dir = out.join(format!("bend-twist-{}", model.name()));
            write_grid(&self.bend_twist, *model, records, summary, &dir, cx)?;
        }
        write_csv(&out.join("bend_twist.csv"), &r.scores)?;
        figures::plot_errors(&self.cantilever, &r.cantilever[..grid], &out)?;
        figures::plot_orders(&r.orders, &out)?;
        figures::print_summary(r);
        let _ = self.findings.set(figures::findings(r, &self.bend_twist));
        Ok(())
    }

    fn checks(&self, r: &RodModelRecords, cx: &mut Context) -> Result<Vec<Check>> {
        cx.enter(SECTION);
        let mut checks = Vec::new();
        for &(model, g) in &r.greenhill {
            checks.extend(model_checks(
                model.name(),
                model.name(),
                &r.summary,
                &r.orders,
                g,
                r.scores.iter().find(|b| b.model == model.name()),
            ));
        }
        Ok(checks)
    }
}
