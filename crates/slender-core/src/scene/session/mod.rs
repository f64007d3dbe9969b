//! The incremental simulation API: a compiled scene with its last equilibrium, edited and
//! re-solved warm — the engine behind interactive cable editing (`slender view`) and behind
//! `slender solve`'s prescribed motion (one code path).
//!
//! A [`Session`] owns the scene as edited (so that it can be saved), its structures, one state,
//! one backup state and one solver (Newton workspace, symbolic factorization, eigen buffers)
//! per structure. Moving a support is a load path of the structures that hold it (the
//! solver's continuation splits a large move into steps); a re-solve that does not converge
//! restores the last equilibrium and says so; an equilibrium that is unstable is, by default,
//! followed along its unstable mode to a stable one (and reported). Edits that change the
//! structure (adding a clip, removing a support) recompile the scene and carry the last
//! equilibrium over (see [`RodSnapshot`](crate::rod::RodSnapshot)).

use nalgebra::Rotation3;

use crate::contact::Friction;
use crate::geometry::Vec3;
use crate::linalg::AdaptiveMatrix;
use crate::rod::{ClampHold, RodSnapshot};
use crate::solver::{follow_unstable_mode, EquilibriumSolver, SolveReport, SolveStatus};
use crate::structure::{MemberState, StructureState};

use super::carry::FramedSnapshot;
use super::compile::{CompiledScene, MAX_STEP_ROTATION, MAX_STEP_TRANSLATION};
use super::contact_report::{add_strip_contacts, contact_problem, contact_report};
use super::contact_solve::solve_with_contact;
pub use super::contact_solve::{FRICTION_PIECES, MAX_FRICTION_SOLVES};
use super::error::SceneError;
use super::result::{scene_results_with, SceneStep, StabilityResult};
use super::shell_contact_run::StripContact;
use super::shell_run::{move_steps, pose_change, ShellRun, StripLoad, MAX_MOVE_STEPS};
use super::shells::{CompiledShell, ShellResult};
use super::spec::{
    MotionStage, PointForceSpec, PointMomentSpec, RodEnd, Scene, ShellClampSpec, ShellForceSpec,
    SupportKind, SupportSpec, UnstablePolicy, VertexRef,
};
use crate::bspline_shell::StripEnd;

mod length;
mod obstacle;

/// Kick of a branch switch: the largest coordinate change, as a fraction of the structure's
/// length.
const SWITCH_AMPLITUDE: f64 = 1e-2;
/// Newton iterations allowed for the minimization after a branch-switch kick.
const SWITCH_ITERATIONS: usize = 2000;
/// Largest number of load steps one edit may need before it is refused as too large.
const MAX_EDIT_STEPS: f64 = 1000.0;

/// Where a support is: its vertex position and its orientation relative to the file's rest
/// orientation (identity for pins and sliders; for a twist hold, a rotation about its edge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SupportPose {
    /// Position (m) of the support's vertex.
    pub position: Vec3,
    /// Orientation relative to rest.
    pub rotation: Rotation3<f64>,
}

/// Indices of structures, held inline up to four.
pub type StructureList = smallvec::SmallVec<[usize; 4]>;

/// The outcome of one edit.
#[derive(Clone, Debug, PartialEq)]
pub struct EditReport {
    /// True if every re-solved structure converged (else the last equilibrium was kept).
    pub converged: bool,
    /// Why not, if not.
    pub reason: Option<String>,
    /// Structures re-solved (inline up to four: an edit of a few structures allocates
    /// nothing).
    pub structures: StructureList,
    /// Newton iterations over them.
    pub iterations: usize,
    /// Load steps over them.
    pub load_steps: usize,
    /// Largest relative residual of the re-solved structures.
    pub relative_residual: f64,
    /// True if every equilibrium of the scene is stable now.
    pub stable: bool,
    /// True if an unstable equilibrium was followed to a stable one during this edit.
    pub followed_unstable_mode: bool,
}

#[derive(Clone)]
struct Run {
    state: StructureState,
    backup: StructureState,
    solver: EquilibriumSolver<StructureState, AdaptiveMatrix>,
    report: SolveReport,
    stability: StabilityResult,
    /// The friction state of its contacts (empty without contact), kept across edits.
    friction: Vec<Friction>,
    /// The friction state of `backup`.
    backup_friction: Vec<Friction>,
    /// The report of `backup`'s solve.
    backup_report: SolveReport,
}

impl Run {
    /// Remembers the current equilibrium (and friction state) to fall back to.
    fn save(&mut self) {
        self.backup.clone_from(&self.state);
        self.backup_friction.clone_from(&self.friction);
        self.backup_report.clone_from(&self.report);
    }

    /// Back to the remembered equilibrium, and to the report of its solve (its residual and
    /// stability, not those of the solve that failed: the edit's own report has those).
    fn restore(&mut self) {
        self.state.clone_from(&self.backup);
        self.friction.clone_from(&self.backup_friction);
        self.report.clone_from(&self.backup_report);
    }
}

/// What [`Session::set_force`] needs to undo a force change: the vertex's dead nodal force
/// before it (N), or the index of the follower load changed.
enum ForceBefore {
    Dead(Vec3),
    Follower(usize),
}

/// A report of a solve that did not start (`reason`).
pub(crate) fn unsolved(reason: String) -> SolveReport {
    SolveReport {
        status: SolveStatus::NotConverged { reason },
        load_reached: 0.0,
        iterations: 0,
        load_steps: 0,
        rejected_steps: 0,
        snaps: 0,
        branch_switches: 0,
        residual: f64::NAN,
        relative_residual: f64::NAN,
        force_scale: f64::NAN,
        residual_floor: f64::NAN,
        energy_decrement: f64::NAN,
        energy: f64::NAN,
        inertia: None,
        lambda_min: None,
        lambda_min_normalized: None,
        modes: None,
    }
}

/// A new solver for structure `k` (from its contact problem with contact: with self-contact
/// its Hessian pattern is dense).
fn new_solver(
    scene: &CompiledScene,
    k: usize,
    state: &StructureState,
) -> EquilibriumSolver<StructureState, AdaptiveMatrix> {
    if let Some(Ok(p)) = contact_problem(scene, k, state, &[]) {
        return EquilibriumSolver::new(&p, state, scene.solver);
    }
    EquilibriumSolver::new(&scene.structures[k], state, scene.solver)
}

/// The friction state of structure `k` at its start `state`: contacts already within the
/// activation distance of a rough surface stick where they are.
fn initial_friction(scene: &CompiledScene, k: usize, state: &StructureState) -> Vec<Friction> {
    match contact_problem(scene, k, state, &[]) {
        Some(Ok(p)) => {
            p.update_friction(state, None);
            p.friction_state()
        }
        _ => Vec::new(),
    }
}

/// Solves structure `k` of `scene` in `run` from load `from` to `to` (in place): the structure
/// alone, or with its contacts, whose stick/slide set is then updated and the equilibrium
/// re-solved (at load `to`, warm) until the set settles (at most [`MAX_FRICTION_SOLVES`]
/// times; not settling is reported as not converged).
fn solve_structure(
    scene: &CompiledScene,
    k: usize,
    run: &mut Run,
    from: f64,
    to: f64,
) -> SolveReport {
    let problem = match contact_problem(scene, k, &run.state, &run.friction) {
        None => {
            return run
                .solver
                .solve_in_place(&scene.structures[k], &mut run.state, from, to)
        }
        Some(Err(e)) => return unsolved(e),
        Some(Ok(p)) => p,
    };
    let report = solve_with_contact(&problem, &mut run.solver, &mut run.state, from, to);
    if report.converged() {
        run.friction = problem.friction_state();
    }
    report
}

/// A scene being solved and edited (see the module docs).
#[derive(Clone)]
pub struct Session {
    spec: Scene,
    scene: CompiledScene,
    runs: Vec<Run>,
    /// The shell strips (the models are in `scene.shells`).
    shells: Vec<ShellRun>,
    /// Per rod, per support: where it is now.
    poses: Vec<Vec<SupportPose>>,
    /// Per rod, per support: where it was at rest (the saved scene moves it from there).
    rest_poses: Vec<Vec<SupportPose>>,
    /// Per obstacle, its rigid motion from the file's shape: rotation about the file's
    /// reference point, then translation (m) (see `move_obstacle_by`).
    obstacle_moves: Vec<(Rotation3<f64>, Vec3)>,
    unstable: UnstablePolicy,
    /// Pose of the moving support when the current motion stage started.
    stage_start: Option<SupportPose>,
    /// Buffers of [`Self::move_support`], kept so that an interactive drag allocates nothing
    /// but its report: the vertices a support holds in one part, the structures re-solved.
    held: Vec<usize>,
    affected: Vec<usize>,
}

impl Session {
    /// Compiles `spec` and solves the loaded scene (loads ramped from the rest state).
    ///
    /// A `[time]` table is ignored here (kept in the spec): a session solves equilibria, with
    /// the supports an equilibrium needs; [`TimeRun`](super::TimeRun) steps a scene in time.
    pub fn new(spec: Scene) -> Result<Self, SceneError> {
        let scene = Scene {
            time: None,
            ..spec.clone()
        }
        .compile()?;
        Ok(Self::from_compiled(spec, scene))
    }

    /// Solves the loaded scene `scene`, compiled from `spec`.
    pub fn from_compiled(spec: Scene, scene: CompiledScene) -> Self {
        let n_obstacles = spec.obstacles.len();
        let unstable = scene.unstable;
        let mut runs = Vec::with_capacity(scene.structures.len());
        for (k, s) in scene.structures.iter().enumerate() {
            let rest = s.rest_state().clone();
            let solver = new_solver(&scene, k, &rest);
            let friction = initial_friction(&scene, k, &rest);
            let mut run = Run {
                backup: rest.clone(),
                stability: StabilityResult::of(&unsolved(String::new())),
                state: rest,
                solver,
                report: unsolved(String::new()),
                backup_friction: friction.clone(),
                backup_report: unsolved(String::new()),
                friction,
            };
            run.report = solve_structure(&scene, k, &mut run, 0.0, 1.0);
            run.stability = StabilityResult::of(&run.report);
            run.save();
            runs.push(run);
        }
        let mut scene = scene;
        let params = scene.solver;
        let contact = scene.contact.clone();
        let shells = scene
            .shells
            .iter_mut()
            .enumerate()
            .map(|(i, s)| {
                let with = contact.as_ref().map(|c| StripContact {
                    obstacles: c.obstacles.clone(),
                    params: c.shell_params[i],
                });
                ShellRun::with_contact(s, &params, with)
            })
            .collect();
        let poses = rest_poses(&scene, &runs);
        let mut me = Self {
            spec,
            rest_poses: poses.clone(),
            poses,
            scene,
            runs,
            shells,
            unstable,
            obstacle_moves: vec![(Rotation3::identity(), Vec3::zeros()); n_obstacles],
            stage_start: None,
            held: Vec::new(),
            affected: Vec::new(),
        };
        for k in 0..me.runs.len() {
            me.stabilize(k);
        }
        me
    }

    /// The scene as edited (save it to get the same equilibrium back: see [`Self::saved`]).
    pub fn spec(&self) -> &Scene {
        &self.spec
    }

    /// The compiled scene.
    pub fn compiled(&self) -> &CompiledScene {
        &self.scene
    }

    /// The state of structure `k`.
    pub fn state(&self, k: usize) -> &StructureState {
        &self.runs[k].state
    }

    /// The last solve report of structure `k`.
    pub fn report(&self, k: usize) -> &SolveReport {
        &self.runs[k].report
    }

    /// Where support `support` of rod `rod` is now.
    pub fn pose(&self, rod: usize, support: usize) -> Option<SupportPose> {
        self.poses.get(rod)?.get(support).copied()
    }

    /// What to do with unstable equilibria from now on.
    pub fn set_unstable_policy(&mut self, p: UnstablePolicy) {
        self.unstable = p;
        self.spec.unstable = p;
        for run in self.runs.iter_mut() {
            run.solver.params.follow_stable = p == UnstablePolicy::Follow;
        }
    }

    /// The results of the current equilibria (allocates: for output, not for re-solves).
    pub fn results(
        &self,
        step: usize,
        stage: Option<usize>,
        stage_fraction: f64,
        pieces: usize,
    ) -> SceneStep {
        let states: Vec<StructureState> = self.runs.iter().map(|r| r.state.clone()).collect();
        let reports: Vec<SolveReport> = self.runs.iter().map(|r| r.report.clone()).collect();
        let stability: Vec<StabilityResult> =
            self.runs.iter().map(|r| r.stability.clone()).collect();
        let friction: Vec<&[Friction]> = self.runs.iter().map(|r| r.friction.as_slice()).collect();
        let mut contacts = contact_report(&self.scene, &states, &friction);
        let strips: Vec<_> = self
            .shells
            .iter()
            .zip(&self.scene.shells)
            .map(|(run, c)| run.contacts(c))
            .collect();
        add_strip_contacts(&self.scene, &strips, &mut contacts);
        let (rods, structures) = scene_results_with(
            &self.scene,
            &states,
            &reports,
            &stability,
            &contacts.external,
        );
        let shells: Vec<ShellResult> = self
            .shells
            .iter()
            .zip(&self.scene.shells)
            .map(|(run, c)| run.result(c))
            .collect();
        let converged = rods.iter().all(|r| r.converged) && shells.iter().all(|s| s.converged);
        let stable = structures.iter().all(|s| s.stability.stable);
        SceneStep {
            step,
            stage,
            stage_fraction,
            seconds: 0.0,
            pieces,
            rods,
            structures,
            shells,
            converged,
            stable,
            time: None,
            obstacles: contacts.obstacles,
            min_gap: contacts.min_gap,
            segment_contacts: contacts.segment_contacts,
            min_segment_gap: contacts.min_segment_gap,
            edges_through_obstacles: contacts.edges_through_obstacles,
        }
    }

    /// Follows an unstable equilibrium of structure `k` to a stable one when the policy says
    /// so; records what happened.
    fn stabilize(&mut self, k: usize) -> bool {
        let run = &mut self.runs[k];
        run.stability = StabilityResult::of(&run.report);
        if self.unstable != UnstablePolicy::Follow
            || !run.report.converged()
            || run.stability.unstable_modes == 0
        {
            return false;
        }
        let s = &self.scene.structures[k];
        let length: f64 = s.members().iter().map(|m| m.length()).sum();
        let left = run.stability.unstable_modes;
        let switched = match contact_problem(&self.scene, k, &run.state, &run.friction) {
            None => follow_unstable_mode(
                s,
                &mut run.solver,
                &mut run.state,
                1.0,
                SWITCH_AMPLITUDE * length,
                SWITCH_ITERATIONS,
            ),
            Some(Err(_)) => None,
            Some(Ok(problem)) => follow_unstable_mode(
                &problem,
                &mut run.solver,
                &mut run.state,
                1.0,
                SWITCH_AMPLITUDE * length,
                SWITCH_ITERATIONS,
            ),
        };
        match switched {
            Some(switch) => {
                run.report = switch.report;
                run.stability = StabilityResult {
                    followed_unstable_mode: true,
                    left_unstable_modes: left,
                    energy_drop: switch.energy_drop,
                    ..StabilityResult::of(&run.report)
                };
                true
            }
            None => false,
        }
    }

    /// Makes the unstable equilibria stable now (branch switch), whatever the policy.
    pub fn follow_stable(&mut self) -> EditReport {
        let policy = self.unstable;
        self.unstable = UnstablePolicy::Follow;
        let mut followed = false;
        let ks: Vec<usize> = (0..self.runs.len()).collect();
        for &k in &ks {
            followed |= self.stabilize(k);
        }
        self.unstable = policy;
        let mut r = self.summary(&ks, None);
        r.followed_unstable_mode = followed;
        r
    }

    /// The end of a converged edit of structures `ks` (the move's buffer, kept for the next
    /// edit): each follows an unstable equilibrium to a stable one when the policy says so,
    /// and the report sums them up.
    fn stabilized(&mut self, ks: Vec<usize>) -> EditReport {
        let mut followed = false;
        for &k in &ks {
            followed |= self.stabilize(k);
        }
        let mut r = self.summary(&ks, None);
        r.followed_unstable_mode = followed;
        self.affected = ks;
        r
    }

    fn summary(&self, ks: &[usize], reason: Option<String>) -> EditReport {
        let mut r = EditReport {
            converged: reason.is_none(),
            reason,
            structures: StructureList::from_slice(ks),
            iterations: 0,
            load_steps: 0,
            relative_residual: 0.0,
            stable: self.runs.iter().all(|r| r.stability.stable),
            followed_unstable_mode: false,
        };
        for &k in ks {
            let rep = &self.runs[k].report;
            r.iterations += rep.iterations;
            r.load_steps += rep.load_steps;
            r.relative_residual = r.relative_residual.max(rep.relative_residual);
            r.followed_unstable_mode |= self.runs[k].stability.followed_unstable_mode;
        }
        r
    }

    /// Point force `force` of rod `rod` in the scene file; an error naming it if there is none.
    fn rod_force(&self, rod: usize, force: usize) -> Result<&PointForceSpec, SceneError> {
        self.spec
            .rods
            .get(rod)
            .and_then(|r| r.forces.get(force))
            .ok_or_else(|| {
                SceneError::new(
                    format!("rods[{rod}].forces[{force}]"),
                    format!(
                        "no such force (rods: {}, point forces of this rod: {})",
                        self.spec.rods.len(),
                        self.spec.rods.get(rod).map_or(0, |r| r.forces.len())
                    ),
                )
            })
    }

    /// Point force `force` of strip `shell` in the scene, or the error naming it.
    fn shell_force(&self, shell: usize, force: usize) -> Result<&ShellForceSpec, SceneError> {
        self.spec
            .shells
            .get(shell)
            .and_then(|s| s.forces.get(force))
            .ok_or_else(|| {
                SceneError::new(
                    format!("shells[{shell}].forces[{force}]"),
                    format!(
                        "no such force (shells: {}, point forces of this strip: {})",
                        self.spec.shells.len(),
                        self.spec.shells.get(shell).map_or(0, |s| s.forces.len())
                    ),
                )
            })
    }

    /// The report of an edit of a shell strip (`what`, e.g. "the move"), solved on its own: no
    /// rod structure was re-solved.
    fn strip_summary(&self, report: &SolveReport, what: &str) -> EditReport {
        let reason = match &report.status {
            SolveStatus::Converged => None,
            SolveStatus::NotConverged { reason } => Some(format!(
                "{what} did not converge ({reason}); the last equilibrium is kept"
            )),
        };
        EditReport {
            converged: reason.is_none(),
            reason,
            structures: StructureList::new(),
            iterations: report.iterations,
            load_steps: report.load_steps,
            relative_residual: report.relative_residual,
            stable: self.runs.iter().all(|r| r.stability.stable),
            followed_unstable_mode: false,
        }
    }

    /// Moves support `support` of rod `rod` to `target` and re-solves warm from the last
    /// equilibrium. A move that does not converge leaves the support and the equilibrium where
    /// they were and says so. Errors (nothing changed): an unknown support, a non-finite pose,
    /// a rotation of a pin or slider, a translation of a twist hold, a move too large.
    pub fn move_support(
        &mut self,
        rod: usize,
        support: usize,
        target: SupportPose,
    ) -> Result<EditReport, SceneError> {
        // Formatted only for an error: a drag's edits allocate nothing but their report.
        let path = || format!("rods[{rod}].supports[{support}]");
        let Some(cur) = self.pose(rod, support) else {
            return Err(SceneError::new(
                path(),
                format!(
                    "no such support (rods: {}, supports of this rod: {})",
                    self.scene.rods.len(),
                    self.scene.rods.get(rod).map_or(0, |r| r.supports.len())
                ),
            ));
        };
        if target.position.iter().any(|c| !c.is_finite())
            || target.rotation.matrix().iter().any(|c| !c.is_finite())
        {
            return Err(SceneError::new(path(), "the target pose must be finite"));
        }
        let rotation = rotation_vector(&(target.rotation * cur.rotation.inverse()));
        let translation = target.position - cur.position;
        let crod = &self.scene.rods[rod];
        let sup = &crod.supports[support];
        match sup.kind {
            SupportKind::Pin | SupportKind::Slider if rotation.norm() > 1e-12 => {
                return Err(SceneError::new(
                    format!("{}.rotation", path()),
                    "a pin or slider has no orientation: only translate it",
                ));
            }
            SupportKind::TwistHold if translation.norm() > 0.0 => {
                return Err(SceneError::new(
                    format!("{}.position", path()),
                    "a twist hold has no position: only turn it about its edge",
                ));
            }
            _ => {}
        }
        let shortest = crod
            .parts
            .iter()
            .map(|p| self.scene.structures[p.structure].members()[p.member].length())
            .fold(f64::INFINITY, f64::min);
        let steps = (rotation.norm() / MAX_STEP_ROTATION)
            .max(translation.norm() / (MAX_STEP_TRANSLATION * shortest))
            .ceil()
            .max(1.0);
        if !(steps <= MAX_EDIT_STEPS) {
            return Err(SceneError::new(
                path(),
                format!(
                    "the move ({:.3e} m, {:.3e} rad) is too large for one edit (at most {} m and {} rad)",
                    translation.norm(),
                    rotation.norm(),
                    MAX_EDIT_STEPS * MAX_STEP_TRANSLATION * shortest,
                    MAX_EDIT_STEPS * MAX_STEP_ROTATION
                ),
            ));
        }
        // Set the load paths of the parts holding the support.
        let mut affected = std::mem::take(&mut self.affected);
        affected.clear();
        let held = &mut self.held;
        for part in &crod.parts {
            let k = part.structure;
            let structure = &mut self.scene.structures[k];
            let local = |v: usize| v - part.first_vertex;
            let run = &self.runs[k];
            let ms = &run.state.members[part.member];
            match sup.kind {
                SupportKind::Clamp | SupportKind::Pin | SupportKind::Clip => {
                    held.clear();
                    held.extend(
                        sup.held
                            .iter()
                            .filter(|&&h| part.contains(h))
                            .map(|&h| local(h)),
                    );
                    if held.is_empty() {
                        continue;
                    }
                    let pivot = if part.contains(sup.vertex) {
                        ms.positions()[local(sup.vertex)]
                    } else {
                        cur.position
                    };
                    structure
                        .member_mut(part.member)
                        .set_support_motion(held, pivot, rotation, translation)
                        .map_err(|e| SceneError::model(path(), e))?;
                }
                SupportKind::Slider => {
                    if !part.contains(sup.vertex) {
                        continue;
                    }
                    let lv = local(sup.vertex);
                    let Some(i) = structure
                        .sliders()
                        .iter()
                        .position(|s| s.member == part.member && s.vertex == lv)
                    else {
                        continue;
                    };
                    structure.set_slider_motion(i, translation);
                }
                SupportKind::TwistHold => {
                    let e = sup.edge.expect("edge");
                    if !(e >= part.first_vertex && e + 1 < part.first_vertex + part.n_vertices) {
                        continue;
                    }
                    let le = e - part.first_vertex;
                    let Some(i) = structure
                        .holds()
                        .iter()
                        .position(|h| h.member == part.member && h.edge == le)
                    else {
                        continue;
                    };
                    let rs = ms.as_der().expect("twist holds hold discrete elastic rods");
                    let t = rs
                        .frames()
                        .edge(crate::rod::frames::EdgeId::Real(le))
                        .tangent;
                    structure.set_hold_motion(i, rotation.dot(&t));
                }
            }
            if !affected.contains(&k) {
                affected.push(k);
            }
        }
        let mut reason = None;
        for &k in &affected {
            let run = &mut self.runs[k];
            run.save();
            let user = run.solver.params;
            let piece = 1.0 / steps;
            run.solver.params.initial_load_step = user.initial_load_step.min(piece);
            run.solver.params.max_load_step = user.max_load_step.min(piece);
            let report = solve_structure(&self.scene, k, run, 0.0, 1.0);
            run.solver.params = user;
            if !report.converged() && reason.is_none() {
                reason = Some(match &report.status {
                    SolveStatus::NotConverged { reason } => reason.clone(),
                    SolveStatus::Converged => String::new(),
                });
            }
            run.report = report;
        }
        for &k in &affected {
            let structure = &mut self.scene.structures[k];
            structure.clear_paths();
        }
        if reason.is_some() {
            // The edit's report has the failed solves' figures; then back to the last
            // equilibrium: the support stays where it was.
            let summary = self.summary(&affected, reason.clone());
            for &k in &affected {
                let run = &mut self.runs[k];
                run.restore();
                run.report.status = SolveStatus::NotConverged {
                    reason: format!(
                        "the move did not converge ({}); the last equilibrium is kept",
                        reason.as_deref().unwrap_or("")
                    ),
                };
            }
            self.affected = affected;
            return Ok(summary);
        }
        self.poses[rod][support] = target;
        Ok(self.stabilized(affected))
    }

    /// Moves a support by a rotation vector (rad, about its vertex) and a translation (m).
    pub fn move_support_by(
        &mut self,
        rod: usize,
        support: usize,
        rotation: Vec3,
        translation: Vec3,
    ) -> Result<EditReport, SceneError> {
        let Some(cur) = self.pose(rod, support) else {
            return self.move_support(
                rod,
                support,
                SupportPose {
                    position: Vec3::zeros(),
                    rotation: Rotation3::identity(),
                },
            );
        };
        self.move_support(
            rod,
            support,
            SupportPose {
                position: cur.position + translation,
                rotation: Rotation3::new(rotation) * cur.rotation,
            },
        )
    }

    /// Changes gravity (m/s²) and re-solves warm (the change is a load path).
    pub fn set_gravity(&mut self, g: [f64; 3]) -> Result<EditReport, SceneError> {
        if g.iter().any(|c| !c.is_finite())
            || g.iter()
                .any(|c| c.abs() > super::magnitudes::MAGNITUDE_LIMIT)
        {
            return Err(SceneError::new(
                "gravity",
                format!("{g:?}: must be finite and of sensible magnitude"),
            ));
        }
        let g = Vec3::from(g);
        let old = Vec3::from(self.spec.gravity);
        // Every structure is re-solved (the list kept in the move's buffer: no allocation).
        let mut ks = std::mem::take(&mut self.affected);
        ks.clear();
        ks.extend(0..self.runs.len());
        for s in self.scene.structures.iter_mut() {
            for m in 0..s.members().len() {
                s.member_mut(m).save_loads();
                s.member_mut(m)
                    .set_gravity_change(old, g)
                    .map_err(|e| SceneError::model("gravity", e))?;
            }
        }
        let mut reason = None;
        for &k in &ks {
            let run = &mut self.runs[k];
            run.save();
            let report = solve_structure(&self.scene, k, run, 0.0, 1.0);
            if !report.converged() && reason.is_none() {
                reason = Some(format!("{:?}", report.status));
            }
            run.report = report;
        }
        for s in self.scene.structures.iter_mut() {
            s.clear_paths();
        }
        // The strips, warm at the new gravity (one Newton solve each), in order until one
        // fails: the first `changed_shells` have the new gravity.
        let mut changed_shells = 0;
        if reason.is_none() {
            for (i, (run, c)) in self
                .shells
                .iter_mut()
                .zip(self.scene.shells.iter_mut())
                .enumerate()
            {
                let report = run.set_load(c, StripLoad::Gravity(old), StripLoad::Gravity(g));
                if report.converged() {
                    changed_shells += 1;
                } else {
                    reason = Some(format!("shells[{i}]: {:?}", report.status));
                    break;
                }
            }
        }
        if reason.is_some() {
            for i in 0..changed_shells {
                self.shells[i].undo_load(&mut self.scene.shells[i], StripLoad::Gravity(old));
            }
            // The loads exactly as they were (not x + Δ − Δ).
            for s in self.scene.structures.iter_mut() {
                for m in 0..s.members().len() {
                    s.member_mut(m).restore_loads();
                }
            }
            let summary = self.summary(&ks, reason);
            for run in self.runs.iter_mut() {
                run.restore();
            }
            self.affected = ks;
            return Ok(summary);
        }
        self.spec.gravity = [g.x, g.y, g.z];
        self.scene.gravity = self.spec.gravity;
        Ok(self.stabilized(ks))
    }

    /// The force in space now (N) of point force `force` of rod `rod`: the file's value for a
    /// dead force; for a follower force, that value turned with the rod's material frame at
    /// its vertex in the current equilibrium. `None` for an unknown rod or force.
    pub fn force_now(&self, rod: usize, force: usize) -> Option<[f64; 3]> {
        let spec = self.spec.rods.get(rod)?.forces.get(force)?;
        if !spec.follower {
            return Some(spec.force);
        }
        let compiled = &self.scene.rods[rod];
        let v = *compiled.force_vertices.get(force)?;
        let part = compiled.load_part(v)?;
        let member = &self.scene.structures[part.structure].members()[part.member];
        let state = self.runs[part.structure].state.members[part.member].as_der()?;
        let now = member.as_der()?.follower_force_in(
            state,
            v - part.first_vertex,
            Vec3::from(spec.force),
        )?;
        Some(now.into())
    }

    /// The moment in space now (N m) of point moment `moment` of rod `rod`: the file's value
    /// for a dead moment; for a follower moment, that value turned with the rod's material
    /// frame at its vertex in the current equilibrium. `None` for an unknown rod or moment.
    pub fn moment_now(&self, rod: usize, moment: usize) -> Option<[f64; 3]> {
        let spec = self.spec.rods.get(rod)?.moments.get(moment)?;
        if !spec.follower {
            return Some(spec.moment);
        }
        let compiled = &self.scene.rods[rod];
        let v = *compiled.moment_vertices.get(moment)?;
        let part = compiled.load_part(v)?;
        let member = &self.scene.structures[part.structure].members()[part.member];
        let state = self.runs[part.structure].state.members[part.member].as_der()?;
        let now = member.as_der()?.follower_moment_in(
            state,
            v - part.first_vertex,
            Vec3::from(spec.moment),
        )?;
        Some(now.into())
    }

    /// Sets point force `force` of rod `rod` (the file's `forces[force]`) to `value` (N) and
    /// re-solves its structure warm: the force changes along the load path from its old
    /// value, so a change too large for one Newton solve is split by the continuation. A
    /// follower force's value is given at rest, as in the file, and turns with the rod along
    /// the path (its old and new values both do). A change that does not converge leaves the
    /// force and the equilibrium where they were and says so. Errors (nothing changed): an
    /// unknown rod or force, a non-finite or absurd value.
    pub fn set_force(
        &mut self,
        rod: usize,
        force: usize,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let path = || format!("rods[{rod}].forces[{force}]");
        let spec = self.rod_force(rod, force)?;
        let follower = spec.follower;
        check_force_value(&path, value)?;
        let (old, new) = (Vec3::from(spec.force), Vec3::from(value));
        let compiled = &self.scene.rods[rod];
        let v = compiled.force_vertices[force];
        let part = compiled
            .load_part(v)
            .expect("every vertex of a rod is on a part");
        let (k, m, local) = (part.structure, part.member, v - part.first_vertex);
        // Saved before a follower change refreshes the state's frozen loads.
        self.runs[k].save();
        let before = if follower {
            let state = &mut self.runs[k].state.members[m];
            self.scene.structures[k]
                .member_mut(m)
                .set_follower_force_change(state, local, old, new)
                .map(ForceBefore::Follower)
        } else {
            self.scene.structures[k]
                .member_mut(m)
                .set_force_change(local, old, new)
                .map(ForceBefore::Dead)
        }
        .map_err(|e| SceneError::model(path(), e))?;
        let run = &mut self.runs[k];
        let report = solve_structure(&self.scene, k, run, 0.0, 1.0);
        let reason = (!report.converged()).then(|| {
            format!(
                "the force change did not converge ({:?}); the last equilibrium is kept",
                report.status
            )
        });
        run.report = report;
        let structure = &mut self.scene.structures[k];
        structure.clear_paths();
        if reason.is_some() {
            // Back to the old force, bit for bit.
            match before {
                ForceBefore::Dead(f) => structure.member_mut(m).undo_force_change(local, f),
                ForceBefore::Follower(i) => {
                    structure.member_mut(m).undo_follower_force_change(i, old)
                }
            }
            let summary = self.summary(&[k], reason);
            self.runs[k].restore();
            return Ok(summary);
        }
        self.spec.rods[rod].forces[force].force = value;
        let followed = self.stabilize(k);
        let mut r = self.summary(&[k], None);
        r.followed_unstable_mode = followed;
        Ok(r)
    }

    /// Sets point moment `moment` of rod `rod` (the file's `moments[moment]`) to `value` (N m)
    /// and re-solves its structure warm. A dead moment's old value is blended into the new one
    /// along the load path (see `rod/moment_change.rs`); a follower moment's value is given at
    /// rest, as in the file, and its change turns with the rod like a follower force's. A
    /// change too large for one Newton solve is split by the continuation; one that does not
    /// converge leaves the moment and the equilibrium where they were and says so. Errors
    /// (nothing changed): an unknown rod or moment, a non-finite or absurd value.
    pub fn set_moment(
        &mut self,
        rod: usize,
        moment: usize,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let path = || format!("rods[{rod}].moments[{moment}]");
        let Some(spec) = self.spec.rods.get(rod).and_then(|r| r.moments.get(moment)) else {
            return Err(no_moment(&self.spec, rod, moment));
        };
        check_moment_value(&path, value)?;
        let follower = spec.follower;
        let (old, new) = (Vec3::from(spec.moment), Vec3::from(value));
        let compiled = &self.scene.rods[rod];
        let v = compiled.moment_vertices[moment];
        let part = compiled
            .load_part(v)
            .expect("every vertex of a rod is on a part");
        let (k, m, local) = (part.structure, part.member, v - part.first_vertex);
        // Saved before the change gives the state the new moment's angle or refreshes its
        // frozen follower loads.
        self.runs[k].save();
        let index = {
            let state = &mut self.runs[k].state.members[m];
            let member = self.scene.structures[k].member_mut(m);
            if follower {
                member.set_follower_moment_change(state, local, old, new)
            } else {
                member.set_moment_change(state, local, old, new)
            }
            .map_err(|e| SceneError::model(path(), e))?
        };
        let run = &mut self.runs[k];
        let report = solve_structure(&self.scene, k, run, 0.0, 1.0);
        let converged = report.converged();
        run.report = report;
        let structure = &mut self.scene.structures[k];
        if !converged {
            // Back to the old moment, bit for bit, and to the state before the change.
            if follower {
                structure
                    .member_mut(m)
                    .undo_follower_moment_change(index, old);
            } else {
                structure.member_mut(m).undo_moment_change(index);
            }
            structure.clear_paths();
            let reason = format!(
                "the moment change did not converge ({:?}); the last equilibrium is kept",
                self.runs[k].report.status
            );
            let summary = self.summary(&[k], Some(reason));
            self.runs[k].restore();
            return Ok(summary);
        }
        if !follower {
            structure
                .member_mut(m)
                .finish_moment_change(&mut self.runs[k].state.members[m]);
        }
        structure.clear_paths();
        self.spec.rods[rod].moments[moment].moment = value;
        let followed = self.stabilize(k);
        let mut r = self.summary(&[k], None);
        r.followed_unstable_mode = followed;
        Ok(r)
    }

    /// Sets point force `force` of shell strip `shell` (the file's `shells[shell].forces[force]`,
    /// a dead force) to `value` (N) and re-solves the strip warm from its last equilibrium (one
    /// Newton solve, as for gravity: a strip's loads are at full scale). A change that does not
    /// converge leaves the force and the equilibrium where they were and says so. Errors
    /// (nothing changed): an unknown strip or force, a non-finite or absurd value.
    pub fn set_shell_force(
        &mut self,
        shell: usize,
        force: usize,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let path = || format!("shells[{shell}].forces[{force}]");
        let spec = self.shell_force(shell, force)?;
        check_force_value(&path, value)?;
        let old = StripLoad::PointForce(force, Vec3::from(spec.force));
        let new = StripLoad::PointForce(force, Vec3::from(value));
        let report = self.shells[shell].set_load(&mut self.scene.shells[shell], old, new);
        if report.converged() {
            self.spec.shells[shell].forces[force].force = value;
        }
        Ok(self.strip_summary(&report, "the force change"))
    }

    /// Adds a dead point force `value` (N) to shell strip `shell` at the vertex (`station`,
    /// `column`) of its grid (station 0 … elements along the length, column 0 … width_elements
    /// across, as the scene's `shells[].forces` name it) and re-solves the strip warm: its model
    /// is rebuilt with the new force at zero (the same unknowns, the same equilibrium), then the
    /// force is set as [`Self::set_shell_force`] sets it; it becomes the last of the strip's
    /// forces. A change that does not converge leaves the strip as it was and says so. Errors
    /// (nothing changed): an unknown strip, a vertex off the grid, a non-finite or absurd value.
    pub fn add_shell_force(
        &mut self,
        shell: usize,
        station: usize,
        column: usize,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let Some(spec) = self.spec.shells.get(shell) else {
            return Err(SceneError::new(
                format!("shells[{shell}]"),
                format!("no such strip (the scene has {})", self.spec.shells.len()),
            ));
        };
        let k = spec.forces.len();
        check_force_value(&|| format!("shells[{shell}].forces[{k}]"), value)?;
        let mut with = spec.clone();
        with.forces.push(ShellForceSpec {
            station,
            column,
            force: [0.0; 3],
        });
        let compiled = self.compile_shell_spec(shell, &with)?;
        let before = self.install_shell(shell, with, compiled);
        if value == [0.0; 3] {
            let report = self.shells[shell].report().clone();
            return Ok(self.strip_summary(&report, "the new force"));
        }
        match self.set_shell_force(shell, k, value) {
            Ok(report) if report.converged => Ok(report),
            other => {
                // Back to the strip without the force (its equilibrium was kept).
                self.install_shell(shell, before.0, before.1);
                other
            }
        }
    }

    /// Removes point force `force` of shell strip `shell`: it is first brought to zero warm
    /// (as [`Self::set_shell_force`] does), then taken out of the strip's model. A change that
    /// does not converge keeps the force and the equilibrium and says so. Errors (nothing
    /// changed): an unknown strip or force.
    pub fn remove_shell_force(
        &mut self,
        shell: usize,
        force: usize,
    ) -> Result<EditReport, SceneError> {
        let nonzero = self.shell_force(shell, force)?.force != [0.0; 3];
        let mut without = self.spec.shells[shell].clone();
        without.forces.remove(force);
        // Compiled first: nothing changes unless it compiles.
        let compiled = self.compile_shell_spec(shell, &without)?;
        let report = if nonzero {
            let r = self.set_shell_force(shell, force, [0.0; 3])?;
            if !r.converged {
                return Ok(r);
            }
            r
        } else {
            let report = self.shells[shell].report().clone();
            self.strip_summary(&report, "the removal")
        };
        self.install_shell(shell, without, compiled);
        Ok(report)
    }

    /// Strip `shell` compiled from `spec` with the scene's gravity.
    fn compile_shell_spec(
        &self,
        shell: usize,
        spec: &super::spec::ShellSpec,
    ) -> Result<CompiledShell, SceneError> {
        super::shells::compile_shell(
            &format!("shells[{shell}]"),
            shell,
            spec,
            Vec3::from(self.spec.gravity),
        )
    }

    /// Puts `compiled` (from `spec`) in place of strip `shell`'s model, which only its loads
    /// may differ from: the strip's unknowns, its state (the clamp poses live there) and its
    /// solver carry over. Returns the spec and model it replaced.
    fn install_shell(
        &mut self,
        shell: usize,
        spec: super::spec::ShellSpec,
        compiled: CompiledShell,
    ) -> (super::spec::ShellSpec, CompiledShell) {
        (
            std::mem::replace(&mut self.spec.shells[shell], spec),
            std::mem::replace(&mut self.scene.shells[shell], compiled),
        )
    }

    /// Adds a support to rod `rod` where the rod is now (a clip or pin holds the current
    /// position and tangent; a slider or twist hold its current line or angle) and re-solves.
    /// Clamps are added in the scene file, not here.
    pub fn add_support(
        &mut self,
        rod: usize,
        support: SupportSpec,
    ) -> Result<EditReport, SceneError> {
        if support.kind == SupportKind::Clamp {
            return Err(SceneError::new(
                format!("rods[{rod}].supports"),
                "clamps are added in the scene file; add a clip, pin, slider or twist hold here",
            ));
        }
        let mut spec = self.spec.clone();
        let Some(r) = spec.rods.get_mut(rod) else {
            return Err(SceneError::new("rods", format!("{rod}: no such rod")));
        };
        r.supports.push(support);
        self.rebuild(spec)
    }

    /// Adds a dead point force to rod `rod` at the vertex of the file's mesh nearest to rest
    /// arc length `at` (m) and sets it to `value` (N): the force is added at zero, which
    /// leaves the equilibrium where it is, and then changed along the load path as
    /// [`Self::set_force`] does, warm from the last equilibrium. The new force is the last of
    /// the rod's `forces`. If the change does not converge the force is taken away again and
    /// the equilibrium kept (the report says so). Errors (nothing changed): an unknown rod,
    /// `at` off the rod, a non-finite or absurd value.
    pub fn add_force(
        &mut self,
        rod: usize,
        at: f64,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let base = self.file_vertex_at(rod, at, "forces")?;
        let k = self.spec.rods[rod].forces.len();
        check_force_value(&|| format!("rods[{rod}].forces[{k}]"), value)?;
        let mut spec = self.spec.clone();
        spec.rods[rod].forces.push(PointForceSpec {
            vertex: VertexRef::Index(base),
            force: [0.0; 3],
            follower: false,
        });
        // The whole session as it was, to go back to exactly: the rebuild re-solves every
        // structure from its current shape, which in contact can move it by the solver's
        // tolerance, so taking the zero force away again would not give it back.
        let before = self.clone();
        let added = self.rebuild(spec)?;
        if value == [0.0; 3] {
            return Ok(added);
        }
        let report = match self.set_force(rod, k, value) {
            Ok(r) => r,
            Err(e) => {
                *self = before;
                return Err(e);
            }
        };
        if !report.converged {
            *self = before;
        }
        Ok(report)
    }

    /// The vertex of the file's mesh of rod `rod` nearest rest arc length `at` (m), where a
    /// new load of the rod's `list` (`forces`, `moments`) goes (loads name vertices of the
    /// file's mesh). Errors: an unknown rod, `at` off the rod.
    fn file_vertex_at(&self, rod: usize, at: f64, list: &str) -> Result<usize, SceneError> {
        let Some(compiled) = self.scene.rods.get(rod) else {
            return Err(SceneError::new(
                format!("rods[{rod}]"),
                format!("no such rod (the scene has {})", self.scene.rods.len()),
            ));
        };
        let arc = &compiled.node_arclengths;
        let length = arc.last().copied().unwrap_or(0.0);
        if !(at.is_finite() && (0.0..=length).contains(&at)) {
            return Err(SceneError::new(
                format!("rods[{rod}].{list}.at"),
                format!(
                    "{at} m: off the rod (its rest length is {length} m; valid: 0 ≤ at ≤ {length})"
                ),
            ));
        }
        Ok((0..compiled.base_vertices.len())
            .min_by(|&a, &b| {
                let d = |v: usize| (arc[compiled.base_vertices[v]] - at).abs();
                d(a).total_cmp(&d(b))
            })
            .expect("a rod has vertices"))
    }

    /// Adds a dead point moment to rod `rod` at the vertex of the file's mesh nearest to rest
    /// arc length `at` (m) and sets it to `value` (N m), as [`Self::add_force`] adds a force:
    /// at zero first (the equilibrium stays where it is), then changed along the moment's load
    /// path as [`Self::set_moment`] does. The new moment is the last of the rod's `moments`. If
    /// the change does not converge the moment is taken away again and the equilibrium kept
    /// (the report says so). Errors (nothing changed): an unknown rod, `at` off the rod, a
    /// non-finite or absurd value.
    pub fn add_moment(
        &mut self,
        rod: usize,
        at: f64,
        value: [f64; 3],
    ) -> Result<EditReport, SceneError> {
        let base = self.file_vertex_at(rod, at, "moments")?;
        let k = self.spec.rods[rod].moments.len();
        check_moment_value(&|| format!("rods[{rod}].moments[{k}]"), value)?;
        let mut spec = self.spec.clone();
        spec.rods[rod].moments.push(PointMomentSpec {
            vertex: VertexRef::Index(base),
            moment: [0.0; 3],
            follower: false,
        });
        // The whole session as it was, to go back to exactly (see `add_force`).
        let before = self.clone();
        let added = self.rebuild(spec)?;
        if value == [0.0; 3] {
            return Ok(added);
        }
        let report = match self.set_moment(rod, k, value) {
            Ok(r) => r,
            Err(e) => {
                *self = before;
                return Err(e);
            }
        };
        if !report.converged {
            *self = before;
        }
        Ok(report)
    }

    /// Removes point moment `moment` of rod `rod`: the moment (dead or follower) is first
    /// brought to zero along its load path, warm from the last equilibrium (as
    /// [`Self::set_moment`] does), then taken out of the scene. A change that does not converge
    /// keeps the moment and the equilibrium (the report says so). Errors (nothing changed): an
    /// unknown rod or moment.
    pub fn remove_moment(&mut self, rod: usize, moment: usize) -> Result<EditReport, SceneError> {
        let Some(spec) = self.spec.rods.get(rod).and_then(|r| r.moments.get(moment)) else {
            return Err(no_moment(&self.spec, rod, moment));
        };
        let before = self.clone();
        if spec.moment != [0.0; 3] {
            let report = self.set_moment(rod, moment, [0.0; 3])?;
            if !report.converged {
                return Ok(report);
            }
        }
        let mut spec = self.spec.clone();
        spec.rods[rod].moments.remove(moment);
        self.rebuild(spec).inspect_err(|_| *self = before)
    }

    /// Removes point force `force` of rod `rod`: the force (dead or follower) is first brought
    /// to zero along the load path, warm from the last equilibrium (as [`Self::set_force`]
    /// does), then taken out of the scene. A change that does not converge keeps the force and the equilibrium (the report
    /// says so). Errors (nothing changed): an unknown rod or force.
    pub fn remove_force(&mut self, rod: usize, force: usize) -> Result<EditReport, SceneError> {
        let spec = self.rod_force(rod, force)?;
        // The session as it was, should the rebuild fail after the force went to zero.
        let before = self.clone();
        if spec.force != [0.0; 3] {
            let report = self.set_force(rod, force, [0.0; 3])?;
            if !report.converged {
                return Ok(report);
            }
        }
        let mut spec = self.spec.clone();
        spec.rods[rod].forces.remove(force);
        self.rebuild(spec).inspect_err(|_| *self = before)
    }

    /// Removes support `support` of rod `rod` and re-solves from the current shape.
    pub fn remove_support(&mut self, rod: usize, support: usize) -> Result<EditReport, SceneError> {
        let mut spec = self.spec.clone();
        let n = spec.rods.get(rod).map_or(0, |r| r.supports.len());
        if support >= n {
            return Err(SceneError::new(
                format!("rods[{rod}].supports[{support}]"),
                format!("no such support (the rod has {n})"),
            ));
        }
        spec.rods[rod].supports.remove(support);
        // Motion stages of that rod's supports are renumbered (the saved scene re-derives
        // them from the poses).
        spec.motion
            .retain(|m| !(m.rod == Some(rod) && m.support == support));
        for m in spec.motion.iter_mut() {
            if m.rod == Some(rod) && m.support > support {
                m.support -= 1;
            }
        }
        self.rebuild_removing(spec, rod, support)
    }

    fn rebuild_removing(
        &mut self,
        spec: Scene,
        rod: usize,
        support: usize,
    ) -> Result<EditReport, SceneError> {
        let mut poses = self.poses.clone();
        let mut rest = self.rest_poses.clone();
        poses[rod].remove(support);
        rest[rod].remove(support);
        self.rebuild_stretched(spec, poses, rest, None, true)
    }

    fn rebuild(&mut self, spec: Scene) -> Result<EditReport, SceneError> {
        let poses = self.poses.clone();
        let rest = self.rest_poses.clone();
        self.rebuild_with(spec, poses, rest)
    }

    /// Recompiles `spec` and carries the current equilibrium over; the new supports hold the
    /// rod where it is.
    fn rebuild_with(
        &mut self,
        spec: Scene,
        poses: Vec<Vec<SupportPose>>,
        rest: Vec<Vec<SupportPose>>,
    ) -> Result<EditReport, SceneError> {
        self.rebuild_stretched(spec, poses, rest, None, false)
    }

    /// As [`Self::rebuild_with`]; with `stretch = Some((rod, factor))` that rod's rest length
    /// was multiplied by `factor` (see [`Self::set_rod_length`]): its shape is carried vertex
    /// by vertex (old rest arc lengths scaled by `factor`), the edges its clamps and clips
    /// hold get their new rest length along their current tangent, and its supports' rest
    /// poses move to where the new rest centerline has them. With `release` (a support
    /// removed) a structure whose Newton solve does not converge in `max_iterations` goes on
    /// minimizing for `snap_iterations`: freed from a support a slack cable may have far to
    /// fall, and no load path splits the change.
    fn rebuild_stretched(
        &mut self,
        spec: Scene,
        mut poses: Vec<Vec<SupportPose>>,
        mut rest: Vec<Vec<SupportPose>>,
        stretch: Option<(usize, f64)>,
        release: bool,
    ) -> Result<EditReport, SceneError> {
        let mut scene = spec.compile()?;
        // Supports keep their current poses: the scene's rest positions are where the file
        // has them, so carry the moved ones by shapes, not by the file.
        let states: Vec<&StructureState> = self.runs.iter().map(|r| &r.state).collect();
        let stitched: Vec<Carried> = (0..self.scene.rods.len())
            .map(|r| match FramedSnapshot::of_rod(&self.scene, &states, r) {
                Some(f) => Carried::Framed(f),
                None => {
                    let (snap, interior) = self.rod_snapshot(r);
                    Carried::Der(snap, interior)
                }
            })
            .collect();
        // Old and new vertices: the new mesh may have more (a vertex inserted for a support
        // given by arc length); map each new vertex to the old shape.
        let mut mapped: Vec<Carried> = scene
            .rods
            .iter()
            .enumerate()
            .map(|(r, rod)| {
                let scaled: Vec<f64>;
                let mut old = &self.scene.rods[r].node_arclengths;
                let new = &rod.node_arclengths;
                if let Some((_, factor)) = stretch.filter(|&(s, _)| s == r) {
                    scaled = old.iter().map(|s| s * factor).collect();
                    old = &scaled;
                }
                match &stitched[r] {
                    Carried::Der(snap, interior) => {
                        Carried::Der(remesh(snap, old, new), interior.clone())
                    }
                    Carried::Framed(f) => Carried::Framed(f.remesh(old, new)),
                }
            })
            .collect();
        // A new clip holds its edge along the current tangent at its *rest* length: that is the
        // edge the saved scene's clip carries from rest by a rigid motion, so that the saved
        // scene re-solves to this very equilibrium (instead of one that differs by the edge's
        // current stretch).
        for (r, rod) in scene.rods.iter().enumerate() {
            // A stretched rod's clamps and clips hold edges of a new rest length too.
            let stretched = stretch.is_some_and(|(s, _)| s == r);
            let first = if stretched { 0 } else { poses[r].len() };
            for s in rod.supports.iter().skip(first) {
                let holds_edge =
                    s.kind == SupportKind::Clip || (stretched && s.kind == SupportKind::Clamp);
                if !holds_edge || rod.n_edges == 0 {
                    continue;
                }
                let (a, b) = if s.vertex == rod.n_edges {
                    (s.vertex - 1, s.vertex)
                } else {
                    (s.vertex, s.vertex + 1)
                };
                let Some(part) = rod.parts.iter().find(|p| p.contains(a) && p.contains(b)) else {
                    continue;
                };
                let member = &scene.structures[part.structure].members()[part.member];
                let rest = member.rest_state();
                let rest_x = rest.positions();
                let rest_len =
                    (rest_x[b - part.first_vertex] - rest_x[a - part.first_vertex]).norm();
                let x = mapped[r].positions_mut();
                let t = (x[b] - x[a]).normalize();
                if s.vertex == a {
                    x[b] = x[a] + t * rest_len;
                } else {
                    x[a] = x[b] - t * rest_len;
                }
            }
        }
        let mut runs = Vec::with_capacity(scene.structures.len());
        for (k, s) in scene.structures.iter().enumerate() {
            let mut state = s.rest_state().clone();
            for (r, rod) in scene.rods.iter().enumerate() {
                for part in rod.parts.iter().filter(|p| p.structure == k) {
                    let a = part.first_vertex;
                    let b = a + part.n_vertices - 1;
                    let member = &s.members()[part.member];
                    state.members[part.member] = match (&mapped[r], &stitched[r]) {
                        (Carried::Der(snap, _), Carried::Der(old, interior)) => {
                            let holds = [
                                clamp_hold_at(old, interior, &self.scene, r, a, true),
                                clamp_hold_at(old, interior, &self.scene, r, b, false),
                            ];
                            let sub = snap.slice(a, b, holds);
                            let rod = member.as_der().expect("a discrete elastic rod");
                            MemberState::Der(rod.state_from_snapshot(&sub))
                        }
                        (Carried::Framed(f), _) => f.state_for(member, a, b),
                        _ => unreachable!("a rod keeps its model"),
                    };
                }
            }
            s.reset_joint_twists(&mut state);
            let solver = new_solver(&scene, k, &state);
            // Contacts keep their stick/slide state when the structure keeps its sites.
            let friction = match self.runs.get(k) {
                Some(old)
                    if contact_problem(&scene, k, &state, &[])
                        .and_then(|p| p.ok())
                        .is_some_and(|p| p.friction_state().len() == old.friction.len()) =>
                {
                    old.friction.clone()
                }
                _ => initial_friction(&scene, k, &state),
            };
            let mut run = Run {
                backup: state.clone(),
                stability: StabilityResult::of(&unsolved(String::new())),
                state,
                solver,
                report: unsolved(String::new()),
                backup_friction: friction.clone(),
                backup_report: unsolved(String::new()),
                friction,
            };
            run.report = solve_structure(&scene, k, &mut run, 1.0, 1.0);
            if release && !run.report.converged() {
                let params = run.solver.params;
                run.solver.params.max_iterations =
                    params.snap_iterations.max(params.max_iterations);
                let first = run.report.iterations;
                run.report = solve_structure(&scene, k, &mut run, 1.0, 1.0);
                run.report.iterations += first;
                run.solver.params = params;
            }
            run.stability = StabilityResult::of(&run.report);
            run.save();
            runs.push(run);
        }
        if let Some((k, r)) = runs.iter().enumerate().find(|(_, r)| !r.report.converged()) {
            return Err(SceneError::new(
                "supports",
                format!("the edited scene does not converge from the current shape (structure {k}: {:?}); nothing was changed", r.report.status),
            ));
        }
        // New supports hold the rod where it is now; their rest pose is where the file's
        // geometry has them, so that the saved scene moves them there from it.
        for (r, rod) in scene.rods.iter().enumerate() {
            while poses[r].len() < rod.supports.len() {
                let s = &rod.supports[poses[r].len()];
                let now = mapped[r].positions_mut();
                let part = rod
                    .parts
                    .iter()
                    .find(|p| p.contains(s.vertex))
                    .expect("part");
                let member_rest =
                    scene.structures[part.structure].members()[part.member].rest_state();
                let rest_x = member_rest.positions();
                let lv = s.vertex - part.first_vertex;
                let mut rotation = Rotation3::identity();
                if s.kind == SupportKind::Clip {
                    let (a, b) = if s.vertex == rod.n_edges {
                        (s.vertex - 1, s.vertex)
                    } else {
                        (s.vertex, s.vertex + 1)
                    };
                    let (la, lb) = (
                        a - part.first_vertex,
                        b.min(part.first_vertex + part.n_vertices - 1) - part.first_vertex,
                    );
                    let t0 = (rest_x[lb] - rest_x[la]).normalize();
                    let t1 = (now[b] - now[a]).normalize();
                    rotation =
                        Rotation3::rotation_between(&t0, &t1).unwrap_or_else(Rotation3::identity);
                }
                poses[r].push(SupportPose {
                    position: now[s.vertex],
                    rotation,
                });
                rest[r].push(SupportPose {
                    position: rest_x[lv],
                    rotation: Rotation3::identity(),
                });
            }
        }
        if let Some((r, _)) = stretch {
            // The saved scene moves the supports from where the new rest centerline has them.
            let rod = &scene.rods[r];
            for (pose, s) in rest[r].iter_mut().zip(&rod.supports) {
                let part = rod
                    .parts
                    .iter()
                    .find(|p| p.contains(s.vertex))
                    .expect("part");
                let member_rest =
                    scene.structures[part.structure].members()[part.member].rest_state();
                pose.position = member_rest.positions()[s.vertex - part.first_vertex];
            }
        }
        std::mem::swap(&mut self.scene, &mut scene);
        self.spec = spec;
        self.runs = runs;
        self.poses = poses;
        self.rest_poses = rest;
        let ks: Vec<usize> = (0..self.runs.len()).collect();
        let mut followed = false;
        for &k in &ks {
            followed |= self.stabilize(k);
        }
        let mut r = self.summary(&ks, None);
        r.followed_unstable_mode = followed;
        Ok(r)
    }

    /// The whole rod `r` as one snapshot, stitched from its parts, with the holds of its
    /// interior clamps.
    fn rod_snapshot(&self, r: usize) -> (RodSnapshot, Vec<InteriorClamp>) {
        let rod = &self.scene.rods[r];
        let n = rod.n_edges;
        let mut snap = RodSnapshot {
            positions: vec![Vec3::zeros(); n + 1],
            m1: vec![Vec3::zeros(); n],
            twists: vec![0.0; n.saturating_sub(1)],
            clamps: [None, None],
            load_angles: Vec::new(),
        };
        let mut boundary: Vec<(usize, f64)> = Vec::new();
        let mut interior: Vec<InteriorClamp> = Vec::new();
        for (pi, part) in rod.parts.iter().enumerate() {
            let s = &self.scene.structures[part.structure];
            let member = s.members()[part.member].as_der().expect("rod");
            let rs = self.runs[part.structure].state.members[part.member]
                .as_der()
                .expect("a discrete elastic rod's state");
            let ps = member.snapshot(rs);
            let a = part.first_vertex;
            for (k, p) in ps.positions.iter().enumerate() {
                snap.positions[a + k] = *p;
            }
            for (k, m) in ps.m1.iter().enumerate() {
                snap.m1[a + k] = *m;
            }
            for (k, t) in ps.twists.iter().enumerate() {
                snap.twists[a + k] = *t;
            }
            // Clamp hinges at interior clamps: the two halves' twists add up to the hinge
            // across the clamp, should the clamp go.
            if pi > 0 {
                if let Some(c) = ps.clamps[0] {
                    boundary.push((a, c.twist));
                    interior.push(InteriorClamp {
                        vertex: a,
                        starts: Some(c),
                        ends: None,
                    });
                }
            } else {
                snap.clamps[0] = ps.clamps[0];
            }
            if pi + 1 < rod.parts.len() {
                if let Some(c) = ps.clamps[1] {
                    let v = a + part.n_vertices - 1;
                    boundary.push((v, c.twist));
                    interior.push(InteriorClamp {
                        vertex: v,
                        starts: None,
                        ends: Some(c),
                    });
                }
            } else {
                snap.clamps[1] = ps.clamps[1];
            }
        }
        for (v, t) in boundary {
            if v >= 1 && v < n {
                snap.twists[v - 1] += t;
            }
        }
        (snap, interior)
    }

    /// Number of motion steps over all stages of the scene file.
    pub fn motion_steps(&self) -> usize {
        self.scene.motion.iter().map(|m| m.steps).sum()
    }

    /// Runs step `step` (1-based over all stages) of the scene file's prescribed motion: the
    /// support is moved to where the stage puts it at this step (from where the stage found
    /// it), so a step that failed is made up by the next. Returns the step's results.
    pub fn run_motion_step(&mut self, step: usize) -> SceneStep {
        let (stage_index, k) = self.locate(step);
        let stage: MotionStage = self.scene.motion[stage_index].clone();
        if k == 0 {
            self.stage_start = match (stage.rod, stage.shell, stage.obstacle) {
                (Some(r), _, _) => self.pose(r, stage.support),
                (None, Some(s), _) => self.shell_pose(s, stage.support),
                (None, None, Some(o)) => self.obstacle_moves.get(o).map(|&(r, t)| SupportPose {
                    position: t,
                    rotation: r,
                }),
                (None, None, None) => None,
            };
        }
        let start = self.stage_start.expect("stage start");
        let f = (k + 1) as f64 / stage.steps as f64;
        if let Some(o) = stage.obstacle {
            // The stage turns the obstacle about its reference point where the stage found
            // it, and shifts it: from the motion at the stage's start to this step's.
            let rotation = Rotation3::new(Vec3::from(stage.rotate) * f) * start.rotation;
            let translation = start.position + Vec3::from(stage.translate) * f;
            let pieces = match self.move_obstacle_to(o, rotation, translation) {
                Ok(r) => r.load_steps,
                Err(_) => 0,
            };
            return self.results(step, Some(stage_index), f, pieces);
        }
        let target = SupportPose {
            position: start.position + Vec3::from(stage.translate) * f,
            rotation: Rotation3::new(Vec3::from(stage.rotate) * f) * start.rotation,
        };
        let edit = match (stage.rod, stage.shell) {
            (Some(r), _) => self.move_support(r, stage.support, target),
            (None, Some(s)) => self.move_shell_clamp(s, stage.support, target),
            (None, None) => unreachable!("compiled stages name a rod, a shell or an obstacle"),
        };
        let pieces = match edit {
            Ok(r) => r.load_steps,
            Err(_) => 0,
        };
        self.results(step, Some(stage_index), f, pieces)
    }

    /// (stage, step within the stage) of global motion step `step` ≥ 1.
    fn locate(&self, step: usize) -> (usize, usize) {
        let mut left = step - 1;
        for (i, m) in self.scene.motion.iter().enumerate() {
            if left < m.steps {
                return (i, left);
            }
            left -= m.steps;
        }
        panic!("motion step {step} is past the last stage");
    }

    /// The edited scene as a file: the supports as edited, gravity as set, and one motion
    /// stage per moved support taking it from its rest pose to where it is now. Loading it
    /// solves to the same equilibrium (for a structure with one stable equilibrium per pose).
    pub fn saved(&self) -> Scene {
        let mut spec = self.spec.clone();
        spec.motion.clear();
        for (r, poses) in self.poses.iter().enumerate() {
            for (s, pose) in poses.iter().enumerate() {
                let rest = self.rest_poses[r][s];
                let rotation = rotation_vector(&(pose.rotation * rest.rotation.inverse()));
                let translation = pose.position - rest.position;
                if rotation.norm() == 0.0 && translation.norm() == 0.0 {
                    continue;
                }
                let length = self.scene.rods[r]
                    .node_arclengths
                    .last()
                    .copied()
                    .unwrap_or(1.0);
                let steps = (rotation.norm() / MAX_STEP_ROTATION)
                    .max(translation.norm() / (MAX_STEP_TRANSLATION * length))
                    .ceil()
                    .max(1.0) as usize;
                spec.motion.push(MotionStage {
                    rod: Some(r),
                    shell: None,
                    obstacle: None,
                    support: s,
                    translate: [translation.x, translation.y, translation.z],
                    rotate: [rotation.x, rotation.y, rotation.z],
                    steps,
                });
            }
        }
        // A moved obstacle stays where the file has it (the rest cable is built around it)
        // and a stage moves it where it is now, carrying the cable as the edit did.
        let shortest = self.shortest_member();
        for (o, (r, t)) in self.obstacle_moves.iter().enumerate() {
            let rotation = rotation_vector(r);
            if rotation.norm() == 0.0 && t.norm() == 0.0 {
                continue;
            }
            spec.motion.push(MotionStage {
                rod: None,
                shell: None,
                obstacle: Some(o),
                support: 0,
                translate: [t.x, t.y, t.z],
                rotate: [rotation.x, rotation.y, rotation.z],
                steps: obstacle::stage_steps(&rotation, t, shortest),
            });
        }
        // A strip's clamps are saved at their poses (the file's `clamps`), which the initial
        // solve reaches from rest.
        for (i, (run, c)) in self.shells.iter().zip(&self.scene.shells).enumerate() {
            let moved = c.clamps.iter().enumerate().any(|(k, clamp)| {
                run.pose(c, k).is_some_and(|p| {
                    p.position != clamp.pose.position(&clamp.centre)
                        || p.rotation != clamp.pose.rotation
                })
            });
            if !moved {
                continue;
            }
            let clamps = c
                .clamps
                .iter()
                .enumerate()
                .map(|(k, clamp)| {
                    let p = run.pose(c, k).expect("a clamp of this strip");
                    let offset = p.position - clamp.centre;
                    let rotate = rotation_vector(&p.rotation);
                    ShellClampSpec {
                        edge: match clamp.end {
                            StripEnd::Start => RodEnd::Start,
                            StripEnd::End => RodEnd::End,
                        },
                        offset: offset.into(),
                        rotate: rotate.into(),
                    }
                })
                .collect();
            spec.shells[i].support = None;
            spec.shells[i].clamps = Some(clamps);
        }
        spec
    }

    /// Where clamp `clamp` (index into the strip's `clamps`; 0 for a strip without them: its
    /// start clamp) of strip `shell` is now: the centre of its clamped edge (m) and its
    /// rotation from rest.
    pub fn shell_pose(&self, shell: usize, clamp: usize) -> Option<SupportPose> {
        self.shells
            .get(shell)?
            .pose(&self.scene.shells[shell], clamp)
    }

    /// The strips being solved (in the order of the scene's `shells`).
    pub fn shell_runs(&self) -> &[ShellRun] {
        &self.shells
    }

    /// Moves clamp `clamp` of strip `shell` to `target` (the centre of its edge and its
    /// rotation from rest) and re-solves the strip warm from its last equilibrium: only the
    /// clamped DOFs are moved before Newton (see the strips' `impose_load`), and a move too
    /// large for one Newton solve is split by the continuation. A move that does not converge
    /// leaves the clamp and the equilibrium where they were and says so. Errors (nothing
    /// changed): an unknown strip or clamp, a non-finite pose, a move too large.
    pub fn move_shell_clamp(
        &mut self,
        shell: usize,
        clamp: usize,
        target: SupportPose,
    ) -> Result<EditReport, SceneError> {
        // Named only on an error: a drag allocates nothing.
        let path = || format!("shells[{shell}].clamps[{clamp}]");
        let Some(cur) = self.shell_pose(shell, clamp) else {
            return Err(SceneError::new(
                path(),
                format!(
                    "no such clamp (shells: {}, clamps of this strip: {})",
                    self.scene.shells.len(),
                    self.scene.shells.get(shell).map_or(0, |s| s.clamps.len())
                ),
            ));
        };
        if target.position.iter().any(|c| !c.is_finite())
            || target.rotation.matrix().iter().any(|c| !c.is_finite())
        {
            return Err(SceneError::new(path(), "the target pose must be finite"));
        }
        let (rotation, translation) = pose_change(&cur, &target);
        let c = &mut self.scene.shells[shell];
        let length = c.length();
        let steps = move_steps(&rotation, &translation, length);
        if !(steps <= MAX_MOVE_STEPS) {
            return Err(SceneError::new(
                path(),
                format!(
                    "the move ({:.3e} m, {:.3e} rad) is too large for one edit (at most {} m and {} rad)",
                    translation.norm(),
                    rotation.norm(),
                    MAX_MOVE_STEPS * MAX_STEP_TRANSLATION * length,
                    MAX_MOVE_STEPS * MAX_STEP_ROTATION
                ),
            ));
        }
        let report = self.shells[shell].move_clamp(c, clamp, rotation, translation, steps);
        Ok(self.strip_summary(&report, "the move"))
    }

    /// Moves clamp `clamp` of strip `shell` by a rotation vector (rad, about the centre of
    /// its edge) and a translation (m).
    pub fn move_shell_clamp_by(
        &mut self,
        shell: usize,
        clamp: usize,
        rotation: Vec3,
        translation: Vec3,
    ) -> Result<EditReport, SceneError> {
        let Some(cur) = self.shell_pose(shell, clamp) else {
            return self.move_shell_clamp(
                shell,
                clamp,
                SupportPose {
                    position: Vec3::zeros(),
                    rotation: Rotation3::identity(),
                },
            );
        };
        self.move_shell_clamp(
            shell,
            clamp,
            SupportPose {
                position: cur.position + translation,
                rotation: Rotation3::new(rotation) * cur.rotation,
            },
        )
    }
}

/// Errors (naming `path()`.force) unless every component of a point force is finite and of
/// sensible magnitude (N).
fn check_force_value(path: &impl Fn() -> String, value: [f64; 3]) -> Result<(), SceneError> {
    if value
        .iter()
        .any(|c| !c.is_finite() || c.abs() > super::magnitudes::MAGNITUDE_LIMIT)
    {
        return Err(SceneError::new(
            format!("{}.force", path()),
            format!("{value:?}: must be finite and of sensible magnitude"),
        ));
    }
    Ok(())
}

/// Errors for a moment value that is not finite or absurdly large, naming `path()`.moment.
fn check_moment_value(path: &impl Fn() -> String, value: [f64; 3]) -> Result<(), SceneError> {
    if value
        .iter()
        .any(|c| !c.is_finite() || c.abs() > super::magnitudes::MAGNITUDE_LIMIT)
    {
        return Err(SceneError::new(
            format!("{}.moment", path()),
            format!("{value:?}: must be finite and of sensible magnitude"),
        ));
    }
    Ok(())
}

/// The error for a point moment `moment` of rod `rod` that `spec` does not have.
fn no_moment(spec: &Scene, rod: usize, moment: usize) -> SceneError {
    SceneError::new(
        format!("rods[{rod}].moments[{moment}]"),
        format!(
            "no such moment (rods: {}, point moments of this rod: {})",
            spec.rods.len(),
            spec.rods.get(rod).map_or(0, |r| r.moments.len())
        ),
    )
}

/// The rotation vector (rad) of `r`, through its quaternion: `Rotation3::scaled_axis` can
/// return NaN for a rotation within round-off of the identity (what a page sends when it keeps
/// the orientation), and a NaN move would never converge.
pub(crate) fn rotation_vector(r: &Rotation3<f64>) -> Vec3 {
    nalgebra::UnitQuaternion::from_rotation_matrix(r).scaled_axis()
}

/// The rest poses of every support (vertex positions of the solved loaded scene are where
/// supports hold them; orientation identity).
fn rest_poses(scene: &CompiledScene, runs: &[Run]) -> Vec<Vec<SupportPose>> {
    scene
        .rods
        .iter()
        .map(|rod| {
            rod.supports
                .iter()
                .map(|s| {
                    let part = rod
                        .parts
                        .iter()
                        .find(|p| p.contains(s.vertex))
                        .expect("vertex on a part");
                    let st = &runs[part.structure].state.members[part.member];
                    SupportPose {
                        position: st.positions()[s.vertex - part.first_vertex],
                        rotation: Rotation3::identity(),
                    }
                })
                .collect()
        })
        .collect()
}

/// A rod's shape carried over to a recompiled scene.
enum Carried {
    /// A discrete elastic rod's snapshot and the holds of its interior clamps.
    Der(RodSnapshot, Vec<InteriorClamp>),
    /// A framed rod's shape.
    Framed(FramedSnapshot),
}

impl Carried {
    fn positions_mut(&mut self) -> &mut Vec<Vec3> {
        match self {
            Self::Der(s, _) => &mut s.positions,
            Self::Framed(f) => &mut f.positions,
        }
    }
}

/// The holds of an interior clamp on the parts that end (`ends`) and start (`starts`) there.
#[derive(Clone, Copy, Debug)]
struct InteriorClamp {
    vertex: usize,
    starts: Option<ClampHold>,
    ends: Option<ClampHold>,
}

/// The clamp hold of the old rod `r` at whole-rod vertex `v` (for the part that starts at it
/// if `start`, else the one that ends there), if a clamp held it: at the rod's ends, or an
/// interior clamp (either side's hold: both are the same clamp).
fn clamp_hold_at(
    snap: &RodSnapshot,
    interior: &[InteriorClamp],
    scene: &CompiledScene,
    r: usize,
    v: usize,
    start: bool,
) -> Option<ClampHold> {
    let n = scene.rods[r].n_edges;
    if start && v == 0 {
        return snap.clamps[0];
    }
    if !start && v == n {
        return snap.clamps[1];
    }
    let at: Vec<&InteriorClamp> = interior.iter().filter(|c| c.vertex == v).collect();
    let own = at
        .iter()
        .find_map(|c| if start { c.starts } else { c.ends });
    own.or_else(|| at.iter().find_map(|c| c.starts.or(c.ends)))
}

/// The snapshot on a mesh with nodes `new` (rest arc lengths) from one on nodes `old`; new
/// nodes inside an old edge are placed on that edge (positions interpolated, the edge's
/// material frame and no twist at the new hinge).
fn remesh(snap: &RodSnapshot, old: &[f64], new: &[f64]) -> RodSnapshot {
    if old.len() == new.len() {
        return snap.clone();
    }
    let n = new.len() - 1;
    let mut out = RodSnapshot {
        positions: Vec::with_capacity(n + 1),
        m1: Vec::with_capacity(n),
        twists: Vec::with_capacity(n.saturating_sub(1)),
        clamps: snap.clamps,
        load_angles: snap.load_angles.clone(),
    };
    let edge_of = |s: f64| -> usize {
        old.partition_point(|&x| x <= s)
            .saturating_sub(1)
            .min(old.len() - 2)
    };
    for &s in new {
        let j = edge_of(s);
        let u = (s - old[j]) / (old[j + 1] - old[j]);
        out.positions
            .push(snap.positions[j] * (1.0 - u) + snap.positions[j + 1] * u);
    }
    for w in new.windows(2) {
        out.m1.push(snap.m1[edge_of(0.5 * (w[0] + w[1]))]);
    }
    for &s in &new[1..n] {
        match old.iter().position(|&x| x == s) {
            Some(v) if v >= 1 && v < old.len() - 1 => out.twists.push(snap.twists[v - 1]),
            _ => out.twists.push(0.0),
        }
    }
    out
}
