//! Lateral buckling of a heavy clamped strip (seed §5, Figs. 9–11): the protocol grid with the
//! shell's Γ_c per aspect ratio, optionally a second grid on a finer mesh (its own report
//! section), the mesh convergence of Γ_c, and, when validating, the master curves and the
//! branch switch of the stability route.

mod convergence;
mod grid;
mod master_curves;

use anyhow::Result;
use serde::{Deserialize, Serialize};
use slender_validation::cantilever::Check;
use slender_validation::lateral_sweep::{
    branch_switch, branch_switch_cases, branch_switch_check, convergence_checks, decision_checks,
    BranchSwitchCase, BuckledState, CriticalConvergence, LateralBucklingSweep,
};
use slender_validation::materials::{ShellMaterialSet, OMEGA_SHELL};
use slender_validation::shell_model::ShellModel;

use super::{words, Benchmark, Context, Preset, SectionSpec};
pub use convergence::ConvergenceStudy;
use grid::GridRecords;
pub(crate) use grid::{ProtocolKey, PROTOCOL_STORE};

/// Section (and output directory) of the grid, the convergence and the master curves of the
/// mid-edge shell; the B-spline shell's sections get the suffix `-bspline`.
const SECTION: &str = "lateral-buckling";
/// The store of branch switches.
const BRANCH_SWITCH_STORE: &str = "lateral-buckling-branch-switch";

/// The lateral-buckling benchmark.
pub struct LateralBuckling {
    /// The protocol grid (and its Γ_c per aspect ratio).
    pub grid: LateralBucklingSweep,
    /// A second grid on a finer mesh, in its own section (full preset: n_L = 30).
    pub fine: Option<LateralBucklingSweep>,
    /// The Γ_c convergence study of the grid's material (`None`: skipped).
    pub convergence: Option<ConvergenceStudy>,
}

/// What the cases produced.
pub struct LateralBucklingRecords {
    grid: GridRecords,
    fine: Option<GridRecords>,
    convergence: Option<Vec<CriticalConvergence>>,
    /// The branch switches of the checks (validating only).
    branch_switches: Vec<(BranchSwitchCase, Option<BuckledState>)>,
}

impl LateralBuckling {
    /// The benchmark of `slender validate` for `model`: Ω_shell on the default grid at
    /// n_L = 8 (and, for the mid-edge shell, n_L = 30 in full), the convergence of Γ_c at
    /// w/L ∈ {0.1, 0.5, 1} on the model's [`convergence_meshes`].
    pub fn validation(preset: Preset, model: ShellModel) -> Self {
        let full = preset == Preset::Full;
        Self {
            grid: LateralBucklingSweep::default_grid(OMEGA_SHELL, model, 8),
            fine: (full && model == ShellModel::Midedge)
                .then(|| LateralBucklingSweep::default_grid(OMEGA_SHELL, model, 30)),
            convergence: Some(ConvergenceStudy {
                widths: vec![0.1, 0.5, 1.0],
                meshes: convergence_meshes(model, preset),
            }),
        }
    }

    fn material(&self) -> ShellMaterialSet {
        self.grid.material
    }

    fn model(&self) -> ShellModel {
        self.grid.model
    }

    /// The main section of this model.
    fn section(&self) -> String {
        section(self.model())
    }
}

/// The meshes n_L of the Γ_c convergence study: for the mid-edge shell 8/15/30 (15/30/60 in
/// full), for the B-spline shell 8/16/32 (8/16/32/64 in full: the three finest extrapolate,
/// and n_L = 8 is the mesh the C¹ shell's targets check). On 4/8/16 the B-spline Γ_c is not
/// monotone (n_L = 4 lies far below, 8 and 16 above the limit), so no order can be observed
/// there; from n_L = 8 on it converges monotonically from above (observed p ≈ 1–1.7).
pub fn convergence_meshes(model: ShellModel, preset: Preset) -> Vec<usize> {
    match (model, preset) {
        (ShellModel::Midedge, Preset::Quick) => vec![8, 15, 30],
        (ShellModel::Midedge, Preset::Full) => vec![15, 30, 60],
        (ShellModel::Bspline, Preset::Quick) => vec![8, 16, 32],
        (ShellModel::Bspline, Preset::Full) => vec![8, 16, 32, 64],
    }
}

/// The main section of `model`'s benchmark.
fn section(model: ShellModel) -> String {
    match model {
        ShellModel::Midedge => SECTION.to_string(),
        ShellModel::Bspline => format!("{SECTION}-{model}"),
    }
}

/// Section of the finer grid.
fn fine_section(sweep: &LateralBucklingSweep) -> String {
    format!("{}-n{}", section(sweep.model), sweep.n_length)
}

/// Everything a branch switch depends on: its store key.
#[derive(Serialize)]
struct BranchSwitchKey {
    material: ShellMaterialSet,
    case: BranchSwitchCase,
    solver: slender_core::solver::SolverParams,
}

/// A stored branch switch (`None`: no converged switch).
#[derive(Serialize, Deserialize)]
struct BranchSwitchRecord {
    buckled: Option<BuckledState>,
}

impl Benchmark for LateralBuckling {
    type Records = LateralBucklingRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let s = &self.grid;
        let mut v = vec![SectionSpec {
            dir: self.section(),
            title: format!(
                "Lateral buckling of a heavy clamped strip ({})",
                s.model.label()
            ),
            about: format!(
                "The critical Γ_shell of a strip clamped with its width along gravity, against \
                 w/L (ν = {}), computed in code by two methods independent of any shell: the \
                 linear buckling load of the clamped Kirchhoff plate under its in-plane \
                 self-weight (Legendre Ritz), and the Vlasov warping-torsion beam with both \
                 weak-axis stiffness conventions (shooting and Hermite Ritz). Beside them the \
                 {} (Ω_shell, n_L = {}, square elements) over {} w/L × {} Γ_shell: Γ_c by \
                 bisection on the Hessian inertia and the seed's protocol (σ = {}, m_ls = {}, \
                 ε = {:e}).",
                master_curves::NU,
                s.model.label(),
                s.n_length,
                s.width_ratios.len(),
                s.gammas.len(),
                s.sigma,
                s.load_steps,
                s.threshold
            ),
            caption,
        }];
        if let Some(f) = &self.fine {
            v.push(SectionSpec {
                dir: fine_section(f),
                title: format!(
                    "Lateral buckling ({}), n_L = {}",
                    f.model.label(),
                    f.n_length
                ),
                about: format!(
                    "The seed's protocol on the same {} w/L × {} Γ_shell grid with n_L = {} \
                     (the seed's Figs. 10–11 resolution).",
                    f.width_ratios.len(),
                    f.gammas.len(),
                    f.n_length
                ),
                caption,
            });
        }
        v
    }

    fn records(&self, cx: &mut Context) -> Result<Option<LateralBucklingRecords>> {
        cx.enter(&self.section());
        let grid = grid::records(&self.grid, cx)?;
        let fine = match &self.fine {
            Some(f) => {
                cx.enter(&fine_section(f));
                grid::records(f, cx)?.map(Some)
            }
            None => Some(None),
        };
        cx.enter(&self.section());
        let convergence = match &self.convergence {
            Some(study) => {
                convergence::records(self.material(), self.model(), study, cx)?.map(Some)
            }
            None => Some(None),
        };
        let (Some(grid), Some(fine), Some(convergence)) = (grid, fine, convergence) else {
            return Ok(None);
        };
        // The branch switches start from the grid's Γ_c: a second stage.
        let branch_switches = if cx.validating() {
            let cases = branch_switch_cases(&grid.critical);
            let keys: Vec<BranchSwitchKey> = cases
                .iter()
                .map(|&case| BranchSwitchKey {
                    material: self.material(),
                    case,
                    solver: slender_validation::lateral_sweep::solver_params(),
                })
                .collect();
            let Some(found) = cx.cases(BRANCH_SWITCH_STORE, &keys, |k| {
                Ok(BranchSwitchRecord {
                    buckled: branch_switch(k.material, &k.case, &k.solver)?,
                })
            })?
            else {
                return Ok(None);
            };
            cases
                .into_iter()
                .zip(found.into_iter().map(|r| r.buckled))
                .collect()
        } else {
            Vec::new()
        };
        Ok(Some(LateralBucklingRecords {
            grid,
            fine,
            convergence,
            branch_switches,
        }))
    }

    fn write(&self, r: &LateralBucklingRecords, cx: &mut Context) -> Result<()> {
        let section = self.section();
        cx.enter(&section);
        let out = cx.dir(&section);
        grid::write(&self.grid, &r.grid, &out)?;
        grid::print_summary(&r.grid);
        if let Some(c) = &r.convergence {
            convergence::write(self.material(), c, &out)?;
            convergence::print(c);
        }
        if let (Some(sweep), Some(records)) = (&self.fine, &r.fine) {
            let section = fine_section(sweep);
            cx.enter(&section);
            grid::write(sweep, records, &cx.dir(&section))?;
            grid::print_summary(records);
        }
        Ok(())
    }

    fn checks(&self, r: &LateralBucklingRecords, cx: &mut Context) -> Result<Vec<Check>> {
        let section = self.section();
        cx.enter(&section);
        let material = self.material();
        // The master curves do not depend on the shell: checked once, in the mid-edge shell's
        // section.
        let mut checks = if self.model() == ShellModel::Midedge {
            master_curves::write_and_check(&cx.dir(&section))?
        } else {
            Vec::new()
        };
        let grid_label = |s: &LateralBucklingSweep| {
            format!("{} w/L × {} Γ_shell", s.width_ratios.len(), s.gammas.len())
        };
        checks.extend(decision_checks(
            &material,
            self.model(),
            self.grid.n_length,
            &grid_label(&self.grid),
            &r.grid.score,
        ));
        if let (Some(sweep), Some(records)) = (&self.fine, &r.fine) {
            checks.extend(decision_checks(
                &sweep.material,
                sweep.model,
                sweep.n_length,
                &grid_label(sweep),
                &records.score,
            ));
        }
        if let Some(c) = &r.convergence {
            checks.extend(convergence_checks(&material, c));
        }
        for (case, buckled) in &r.branch_switches {
            checks.push(branch_switch_check(&material, case, buckled.as_ref()));
        }
        Ok(checks)
    }
}

/// Caption of a figure of the grid sections.
fn caption(stem: &str) -> String {
    match stem {
        "phase_diagram" => "Counterpart of the seed's Figs. 9b–11b: 2-D/3-D decisions of the \
                            seed's protocol over (w/L, Γ_shell) on the plate master curve's \
                            ground truth, with Γ_c from the Hessian inertia and the Vlasov \
                            band."
            .into(),
        "height_map" => "Counterpart of the seed's Figs. 9a–11a: the free end's y-deviation \
                         after the protocol; its steep descent should follow the master curve."
            .into(),
        "convergence" => "Γ_c from the Hessian inertia against the mesh, relative to the plate \
                          master curve, with the Richardson-extrapolated converged values."
            .into(),
        "master_curves" => "Ground truth of the seed's Figs. 10–11: critical Γ_shell against \
                            w/L, Kirchhoff plate and Vlasov beam (both weak-axis stiffnesses)."
            .into(),
        _ => words(stem),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use slender_validation::lateral_sweep::acceptance::checked_mesh;

    #[test]
    fn every_preset_computes_the_mesh_its_targets_check() {
        for model in [ShellModel::Midedge, ShellModel::Bspline] {
            for preset in [Preset::Quick, Preset::Full] {
                let meshes = convergence_meshes(model, preset);
                assert!(
                    meshes.contains(&checked_mesh(model)),
                    "{model:?} {preset:?}: {meshes:?} lacks n_L = {}",
                    checked_mesh(model)
                );
                assert!(meshes.len() >= 3 && meshes.windows(2).all(|w| w[0] < w[1]));
            }
        }
    }
}
