//! The cantilever under self-weight (seed §3, Figs. 2–5): rods over Γ × N × mesh × material
//! against the heavy-elastica master curve, and the flat cables (shells of the seed's Table 2)
//! on the same plot. Two report sections: the rods and the shells.

mod rods;
mod shells;

use anyhow::Result;
use slender_validation::cantilever::{
    shell_acceptance, CantileverRecord, CantileverSweep, Check, ShellCantileverRecord,
    ShellCantileverSweep,
};
use slender_validation::materials::SHELL_SETS;
use slender_validation::rod_model::RodModel;
use slender_validation::shell_model::ShellModel;

use super::{Benchmark, Context, SectionSpec};

/// Section (and output directory) of the rods.
const RODS: &str = "cantilever";
/// Section of the shells.
const SHELLS: &str = "cantilever-shell";

/// The cantilever benchmark.
pub struct Cantilever {
    /// The rod sweep.
    pub rods: CantileverSweep,
    /// The rod formulation of the rod sweep (part of its store keys).
    pub model: RodModel,
    /// The shell sweep, if shells are run.
    pub shells: Option<ShellCantileverSweep>,
}

/// The cantilever's records.
pub struct CantileverRecords {
    /// One per rod case, in sweep order.
    rods: Vec<CantileverRecord>,
    /// The extra rod cases of the checks (validating only).
    rod_check_cases: Vec<CantileverRecord>,
    /// One per shell case, in sweep order.
    shells: Option<Vec<ShellCantileverRecord>>,
    /// The shell cases of the checks (validating with shells only).
    shell_check_cases: Vec<ShellCantileverRecord>,
}

impl Cantilever {
    /// The benchmark of `slender validate`: the default rod sweep, and the three shell sets at
    /// w/L = 0.1, n_L ∈ {8, 15, 30} on the same Γ, with both shell models.
    pub fn validation() -> Self {
        let rods = CantileverSweep::default();
        let shells = ShellCantileverSweep {
            models: ShellModel::ALL.to_vec(),
            gammas: rods.gammas.clone(),
            element_counts: vec![8, 15, 30],
            width_ratio: 0.1,
            materials: SHELL_SETS.to_vec(),
        };
        Self {
            rods,
            model: RodModel::Der,
            shells: Some(shells),
        }
    }

    /// The rod set drawn with the shells on the seed's Fig. 2: the measured bundle if swept
    /// (the seed pairs it with the Ω_combined shells), else Ω_rod.
    fn fig2_rod(&self) -> Option<&'static str> {
        ["bundle", "rod"]
            .into_iter()
            .find(|m| self.rods.materials.iter().any(|s| s.name == *m))
    }
}

impl Benchmark for Cantilever {
    type Records = CantileverRecords;

    fn sections(&self) -> Vec<SectionSpec> {
        let s = &self.rods;
        let mut v = vec![SectionSpec {
            dir: RODS.into(),
            title: "Cantilever under self-weight (rods)".into(),
            about: format!(
                "Δy/Δx of a rod clamped horizontally, against the gravito-bending parameter Γ, \
                 for {} values of Γ in [{:.0e}, {:.0e}], element counts {:?}, three mesh \
                 families and two material sets; the master curve is the heavy elastica solved \
                 by multiple shooting.",
                s.gammas.len(),
                s.gammas.first().copied().unwrap_or(f64::NAN),
                s.gammas.last().copied().unwrap_or(f64::NAN),
                s.element_counts
            ),
            caption: rods::caption,
        }];
        if let Some(sweep) = &self.shells {
            let models: Vec<&str> = sweep.models.iter().map(|m| m.label()).collect();
            v.push(SectionSpec {
                dir: SHELLS.into(),
                title: "Cantilever under self-weight (flat cables, shells)".into(),
                about: format!(
                    "The same benchmark for strips of the seed's Table 2 (Ω_shell, Ω_IPS, \
                     Ω_combined), w/L = {}, n_L ∈ {:?}, with the {} (each with its exact \
                     clamp), against the heavy elastica with EI = D·w and with the narrow-strip \
                     stiffness E·w·h³/12.",
                    sweep.width_ratio,
                    sweep.element_counts,
                    models.join(" and the ")
                ),
                caption: shells::caption,
            });
        }
        v
    }

    fn records(&self, cx: &mut Context) -> Result<Option<CantileverRecords>> {
        cx.enter(RODS);
        self.rods.validate()?;
        let rods = rods::records(&self.rods.cases(), self.model, cx)?;
        let rod_check_cases = if cx.validating() {
            rods::records(
                &slender_validation::cantilever::acceptance::check_cases(),
                self.model,
                cx,
            )?
        } else {
            Some(Vec::new())
        };
        let (shells, shell_check_cases) = match &self.shells {
            Some(sweep) => {
                cx.enter(SHELLS);
                sweep.validate()?;
                let records = shells::records(&sweep.cases(), cx)?;
                let checks = if cx.validating() {
                    shells::records(&shell_acceptance::acceptance_cases(&sweep.models), cx)?
                } else {
                    Some(Vec::new())
                };
                (records.map(Some), checks)
            }
            None => (Some(None), Some(Vec::new())),
        };
        let (Some(rods), Some(rod_check_cases), Some(shells), Some(shell_check_cases)) =
            (rods, rod_check_cases, shells, shell_check_cases)
        else {
            return Ok(None);
        };
        Ok(Some(CantileverRecords {
            rods,
            rod_check_cases,
            shells,
            shell_check_cases,
        }))
    }

    fn write(&self, r: &CantileverRecords, cx: &mut Context) -> Result<()> {
        cx.enter(RODS);
        rods::write(&self.rods, self.model, &r.rods, &cx.dir(RODS), cx)?;
        if let (Some(sweep), Some(records)) = (&self.shells, &r.shells) {
            cx.enter(SHELLS);
            shells::write(
                sweep,
                records,
                &r.rods,
                self.fig2_rod(),
                &cx.dir(SHELLS),
                cx,
            )?;
        }
        Ok(())
    }

    fn checks(&self, r: &CantileverRecords, cx: &mut Context) -> Result<Vec<Check>> {
        cx.enter(RODS);
        let mut checks = slender_validation::cantilever::acceptance::checks_from_records(
            &r.rods,
            &r.rod_check_cases,
        );
        if let Some(sweep) = &self.shells {
            cx.enter(SHELLS);
            checks.extend(shell_acceptance::checks_from_records(
                &sweep.models,
                &r.shell_check_cases,
            ));
        }
        Ok(checks)
    }
}
