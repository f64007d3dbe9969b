//! Turning a parsed scene into structures ready to solve, checking everything a file can get
//! wrong and naming the place when it does. One stage per file: a rod's section and material
//! (`section.rs`), its nodes, supports, loads and parts (`rod.rs`, `line_loads.rs`), the
//! check that double precision resolves a rod's bending (`precision.rs`), the grouping of
//! parts into structures by joints and closures (`structures.rs`), the prescribed motion
//! (`motion.rs`) and the time stepping (`time.rs`).

pub mod contact;
pub mod line_loads;
pub mod motion;
pub mod precision;
pub mod rod;
pub mod section;
pub mod shell_contact;
pub mod structures;
pub mod time;

use crate::geometry::Vec3;
use crate::solver::SolverParams;
use crate::structure::Structure;

use super::error::SceneError;
use super::magnitudes::MAGNITUDE_LIMIT;
use super::spec::{MotionStage, Scene, UnstablePolicy};

pub use contact::CompiledContact;
pub use motion::{MAX_STEP_ROTATION, MAX_STEP_TRANSLATION};
pub use rod::{CompiledRod, CompiledSupport, RodPart, DEFAULT_ELEMENTS};
pub(crate) use section::check_name;
pub use time::CompiledTime;

/// Newton steps past convergence that bring the residual of a scene down to round-off, so
/// that the reactions balance the loads (the default of `solver.polish_iterations` in scenes).
pub const SCENE_POLISH_ITERATIONS: usize = 3;

/// A scene ready to solve.
#[derive(Clone, Debug)]
pub struct CompiledScene {
    /// The rods, as in the file (their parts say which structure solves them).
    pub rods: Vec<CompiledRod>,
    /// The structures: groups of rod parts solved together.
    pub structures: Vec<Structure>,
    /// The shell strips (solved independently of the rods; each against the obstacles).
    pub shells: Vec<super::shells::CompiledShell>,
    /// Prescribed motion stages (validated).
    pub motion: Vec<MotionStage>,
    /// Solver parameters (validated; scene defaults filled in).
    pub solver: SolverParams,
    /// Gravitational acceleration (m/s²).
    pub gravity: [f64; 3],
    /// What to do with unstable equilibria.
    pub unstable: UnstablePolicy,
    /// Time stepping (`[time]`), validated; `None` for equilibria only.
    pub time: Option<CompiledTime>,
    /// Obstacles and contact parameters; `None` without obstacles and self-contact (every
    /// structure is then solved as it is).
    pub contact: Option<CompiledContact>,
}

impl CompiledScene {
    /// Rest positions (m) of every vertex of rod `rod`, stitched from its parts.
    pub fn rest_positions(&self, rod: usize) -> Vec<Vec3> {
        let r = &self.rods[rod];
        let mut out = vec![Vec3::zeros(); r.n_edges + 1];
        for part in &r.parts {
            let rest = self.structures[part.structure].members()[part.member].rest_state();
            for (k, p) in rest.positions().iter().enumerate() {
                out[part.first_vertex + k] = *p;
            }
        }
        out
    }
}

impl Scene {
    /// Validates the scene and builds its structures. Errors name the path in the file.
    pub fn compile(&self) -> Result<CompiledScene, SceneError> {
        if self.rods.is_empty() && self.shells.is_empty() {
            return Err(SceneError::new(
                "rods",
                "the scene has no rod and no shell; add at least one [[rods]] or [[shells]] table",
            ));
        }
        if !self.gravity.iter().all(|c| c.is_finite()) {
            return Err(SceneError::new(
                "gravity",
                format!(
                    "{:?}: every component must be a finite number",
                    self.gravity
                ),
            ));
        }
        let gravity = Vec3::from(self.gravity);
        if gravity.amax() > MAGNITUDE_LIMIT {
            return Err(SceneError::new(
                "gravity",
                format!(
                    "{:?}: components must have magnitude <= {MAGNITUDE_LIMIT:e}",
                    self.gravity
                ),
            ));
        }
        self.solver
            .validate()
            .map_err(|e| SceneError::model("solver", e))?;
        let time = match &self.time {
            Some(t) => Some(time::check_time(self, t)?),
            None => None,
        };
        let mut drafts = Vec::with_capacity(self.rods.len());
        let mut names: Vec<String> = Vec::new();
        for (i, spec) in self.rods.iter().enumerate() {
            let draft = rod::compile_rod(&format!("rods[{i}]"), i, spec, gravity, &self.solver)?;
            if names.contains(&draft.rod.name) {
                return Err(SceneError::new(
                    format!("rods[{i}].name"),
                    format!(
                        "{:?} is used by another rod; names must be unique",
                        draft.rod.name
                    ),
                ));
            }
            names.push(draft.rod.name.clone());
            drafts.push(draft);
        }
        // A cable may rest on obstacles without supports of its own: the rigid-body check is
        // left to the solve (a cable held by neither supports nor contacts does not converge).
        let free = time.is_some() || !self.obstacles.is_empty();
        // With self-contact every rod is part of one structure, so that separate cables touch
        // each other (contact acts within a structure).
        let one_structure = self.contact.as_ref().is_some_and(|c| c.self_contact);
        let structures =
            structures::build_structures(&mut drafts, &self.joints, free, one_structure)?;
        let shortest: Vec<f64> = drafts
            .iter()
            .map(|d| {
                d.members
                    .iter()
                    .map(|r| r.length())
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let rods: Vec<CompiledRod> = drafts.into_iter().map(|d| d.rod).collect();
        let mut shells = Vec::with_capacity(self.shells.len());
        for (i, spec) in self.shells.iter().enumerate() {
            let path = format!("shells[{i}]");
            let shell = super::shells::compile_shell(&path, i, spec, gravity)?;
            if names.contains(&shell.name) {
                return Err(SceneError::new(
                    format!("{path}.name"),
                    format!(
                        "{:?} is used by another rod or shell; names must be unique",
                        shell.name
                    ),
                ));
            }
            names.push(shell.name.clone());
            shells.push(shell);
        }
        let contact = contact::compile_contact(self, &rods, &structures, &shells)?;
        for (k, stage) in self.motion.iter().enumerate() {
            motion::check_stage(k, stage, &rods, &shortest, &shells, self.obstacles.len())?;
        }
        let mut solver = self.solver;
        solver
            .polish_iterations
            .get_or_insert(SCENE_POLISH_ITERATIONS);
        solver.follow_stable = self.unstable == UnstablePolicy::Follow;
        solver.chord_predictor = true;
        solver.chord_final_check = true;
        solver.deferred_energy_check = true;
        solver.lagged_first_step = true;
        Ok(CompiledScene {
            rods,
            structures,
            shells,
            motion: self.motion.clone(),
            solver,
            gravity: self.gravity,
            unstable: self.unstable,
            time,
            contact,
        })
    }
}
