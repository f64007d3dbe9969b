//! A shell strip in a [`Session`](super::Session): its last equilibrium, a backup, its solver
//! workspace, and the moves of its clamps (drags in `slender view`, prescribed motion stages,
//! the poses of the file) as load paths of the one continuation (`solver::continuation`): a
//! move too large for one Newton solve is split into load steps, and a move that does not
//! converge restores the last equilibrium.

use crate::bspline_shell::{BsplineLoadPath, BsplineShell, BsplineState, ClampMotion};
use crate::geometry::Vec3;
use crate::shell::{Clamp, LoadPath, Shell, ShellState};
use crate::solver::{EquilibriumProblem, EquilibriumSolver, SolveReport, SolverParams};

use super::compile::{MAX_STEP_ROTATION, MAX_STEP_TRANSLATION};
use super::session::{rotation_vector, SupportPose};
use super::shell_contact_run::{ContactStripRun, StripContact, StripContacts};
use super::shells::{
    bspline_result, midedge_result, solve_midedge_loaded, CompiledShell, ShellResult, StripModel,
};

/// Largest number of load steps one clamp move may need before it is refused as too large.
pub(crate) const MAX_MOVE_STEPS: f64 = 1000.0;

/// A dead load of a strip that a session edits: gravity, or one of its point forces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum StripLoad {
    /// Gravity (m/s²).
    Gravity(Vec3),
    /// Point force `k` (in the order of the spec's `forces`) at load factor 1 (N).
    PointForce(usize, Vec3),
}

/// A strip model whose clamps a load path can move.
pub(crate) trait StripProblem: EquilibriumProblem {
    /// From now on the load factor moves the clamps by `motions` (loads at full scale).
    fn set_motions(&mut self, motions: &[ClampMotion]);
    /// Back to the default load path (the loads ramped, the clamps where the state has them).
    fn clear_motions(&mut self);
    /// Sets gravity or a point force at load factor 1 (assigned, not incremented: setting
    /// the old value back restores the model bit for bit).
    fn set_load(&mut self, load: StripLoad);
}

impl StripProblem for Shell {
    fn set_motions(&mut self, motions: &[ClampMotion]) {
        let mut by_end = [None; 2];
        for m in motions {
            by_end[m.end.index()] = Some(*m);
        }
        self.set_load_path(LoadPath::ClampMotion(by_end));
    }

    fn clear_motions(&mut self) {
        self.set_load_path(LoadPath::Gravity);
    }

    fn set_load(&mut self, load: StripLoad) {
        match load {
            StripLoad::Gravity(g) => self.set_gravity(g),
            StripLoad::PointForce(k, f) => self.set_point_force(k, f),
        }
    }
}

impl StripProblem for BsplineShell {
    fn set_motions(&mut self, motions: &[ClampMotion]) {
        // The path's list of motions is refilled, not replaced: a drag allocates nothing.
        let mut path = std::mem::take(&mut self.load_path);
        path.loads = BsplineLoadPath::clamp_motion(Vec::new()).loads;
        path.motions.clear();
        path.motions.extend_from_slice(motions);
        // The session checks the ends and the finiteness of the motions before.
        self.set_load_path(path)
            .expect("motions of clamped ends, finite");
    }

    fn clear_motions(&mut self) {
        // The default path, keeping the capacity of the list of motions.
        let mut path = std::mem::take(&mut self.load_path);
        path.loads = BsplineLoadPath::default().loads;
        path.motions.clear();
        self.set_load_path(path).expect("the default path is valid");
    }

    fn set_load(&mut self, load: StripLoad) {
        match load {
            StripLoad::Gravity(g) => self.set_gravity(g),
            StripLoad::PointForce(k, f) => self.set_point_force(k, f),
        }
    }
}

/// One model's strip: state, backup, solver, last report.
#[derive(Clone)]
pub(crate) struct StripRun<P: EquilibriumProblem> {
    pub(crate) state: P::State,
    backup: P::State,
    solver: EquilibriumSolver<P::State, P::Hessian>,
    pub(crate) report: SolveReport,
}

impl<P: StripProblem> StripRun<P> {
    /// Moves the clamps by `motions` in at least `steps` load steps, warm from the current
    /// state; if the solve does not converge, the state goes back to where it was.
    fn move_clamps(&mut self, model: &mut P, motions: &[ClampMotion], steps: f64) -> SolveReport {
        self.backup.clone_from(&self.state);
        model.set_motions(motions);
        let user = self.solver.params;
        let piece = 1.0 / steps;
        self.solver.params.initial_load_step = user.initial_load_step.min(piece);
        self.solver.params.max_load_step = user.max_load_step.min(piece);
        let report = self.solver.solve_in_place(model, &mut self.state, 0.0, 1.0);
        self.solver.params = user;
        model.clear_motions();
        if !report.converged() {
            self.state.clone_from(&self.backup);
        }
        report
    }

    /// A load changed from `old` to `new`: one Newton solve warm from the current state (the
    /// strip's loads are at full scale); if it does not converge, the load and the state go
    /// back.
    fn change_load(&mut self, model: &mut P, old: StripLoad, new: StripLoad) -> SolveReport {
        self.backup.clone_from(&self.state);
        model.set_load(new);
        let report = self.solver.solve_in_place(model, &mut self.state, 1.0, 1.0);
        if !report.converged() {
            model.set_load(old);
            self.state.clone_from(&self.backup);
        }
        report
    }

    /// Undoes the last [`Self::change_load`] that converged.
    fn undo_load(&mut self, model: &mut P, old: StripLoad) {
        model.set_load(old);
        self.state.clone_from(&self.backup);
    }
}

#[derive(Clone)]
enum Runs {
    Midedge(StripRun<Shell>),
    Bspline(StripRun<BsplineShell>),
    /// A mid-edge strip in a scene with obstacles.
    MidedgeContact(ContactStripRun),
}

/// A strip being solved and edited.
#[derive(Clone)]
pub struct ShellRun {
    runs: Runs,
    rod_predictor_used: bool,
}

/// Load steps a rigid move of a clamp by `rotation` (rad) and `translation` (m) needs on a
/// strip of length `length` (m), as for rods' supports.
pub(crate) fn move_steps(rotation: &Vec3, translation: &Vec3, length: f64) -> f64 {
    (rotation.norm() / MAX_STEP_ROTATION)
        .max(translation.norm() / (MAX_STEP_TRANSLATION * length))
        .ceil()
        .max(1.0)
}

impl ShellRun {
    /// Solves the strip `c` loaded at its clamps' rest poses, then moves the clamps to the
    /// poses of the file (one load path for all of them).
    pub fn new(c: &mut CompiledShell, params: &SolverParams) -> Self {
        Self::with_contact(c, params, None)
    }

    /// As [`Self::new`], in contact with obstacles when `contact` is given (a mid-edge strip:
    /// the scene's compilation refuses B-spline strips with obstacles).
    pub(crate) fn with_contact(
        c: &mut CompiledShell,
        params: &SolverParams,
        contact: Option<StripContact>,
    ) -> Self {
        let (runs, rod_predictor_used) = match (&c.model, contact) {
            (StripModel::Midedge(shell), Some(contact)) => (
                Runs::MidedgeContact(ContactStripRun::new(shell, contact, params)),
                false,
            ),
            (StripModel::Midedge(shell), None) => {
                let flat = shell.rest_state();
                let mut solver = EquilibriumSolver::new(shell, &flat, *params);
                let (solution, rod) = solve_midedge_loaded(shell, &mut solver, params);
                (
                    Runs::Midedge(StripRun {
                        backup: solution.state.clone(),
                        state: solution.state,
                        solver,
                        report: solution.report,
                    }),
                    rod,
                )
            }
            (StripModel::Bspline(shell), _) => {
                let flat = shell.rest_state();
                let mut solver = EquilibriumSolver::new(shell, &flat, *params);
                let solution = solver.solve(shell, &flat, 0.0, 1.0);
                (
                    Runs::Bspline(StripRun {
                        backup: solution.state.clone(),
                        state: solution.state,
                        solver,
                        report: solution.report,
                    }),
                    false,
                )
            }
        };
        let mut run = Self {
            runs,
            rod_predictor_used,
        };
        if !run.report().converged() {
            return run;
        }
        let length = c.length();
        let mut motions = Vec::new();
        let mut steps: f64 = 1.0;
        for k in &c.clamps {
            let rotation = rotation_vector(&k.pose.rotation);
            let translation = k.pose.position(&k.centre) - k.centre;
            if rotation.norm() == 0.0 && translation.norm() == 0.0 {
                continue;
            }
            steps = steps.max(move_steps(&rotation, &translation, length));
            motions.push(ClampMotion {
                end: k.end,
                pivot: k.centre.into(),
                rotation: rotation.into(),
                translation: translation.into(),
            });
        }
        if !motions.is_empty() {
            run.solve_motions(c, &motions, steps);
        }
        run
    }

    /// The last solve report.
    pub fn report(&self) -> &SolveReport {
        match &self.runs {
            Runs::Midedge(r) => &r.report,
            Runs::Bspline(r) => &r.report,
            Runs::MidedgeContact(r) => &r.report,
        }
    }

    fn solve_motions(
        &mut self,
        c: &mut CompiledShell,
        motions: &[ClampMotion],
        steps: f64,
    ) -> SolveReport {
        let report = match (&mut self.runs, &mut c.model) {
            (Runs::Midedge(r), StripModel::Midedge(m)) => r.move_clamps(m, motions, steps),
            (Runs::Bspline(r), StripModel::Bspline(m)) => r.move_clamps(m, motions, steps),
            (Runs::MidedgeContact(r), StripModel::Midedge(m)) => r.move_clamps(m, motions, steps),
            _ => unreachable!("a run is built from its own model"),
        };
        match &mut self.runs {
            Runs::Midedge(r) => r.report = report.clone(),
            Runs::Bspline(r) => r.report = report.clone(),
            Runs::MidedgeContact(r) => r.report = report.clone(),
        }
        report
    }

    /// Changes a load of the strip (gravity or a point force) from `old` to `new` and
    /// re-solves warm; a change that does not converge is undone (the report says so).
    pub(crate) fn set_load(
        &mut self,
        c: &mut CompiledShell,
        old: StripLoad,
        new: StripLoad,
    ) -> SolveReport {
        let report = match (&mut self.runs, &mut c.model) {
            (Runs::Midedge(r), StripModel::Midedge(m)) => r.change_load(m, old, new),
            (Runs::Bspline(r), StripModel::Bspline(m)) => r.change_load(m, old, new),
            (Runs::MidedgeContact(r), StripModel::Midedge(m)) => r.change_load(m, old, new),
            _ => unreachable!("a run is built from its own model"),
        };
        if report.converged() {
            match &mut self.runs {
                Runs::Midedge(r) => r.report = report.clone(),
                Runs::Bspline(r) => r.report = report.clone(),
                Runs::MidedgeContact(r) => r.report = report.clone(),
            }
        }
        report
    }

    /// Undoes a converged [`Self::set_load`] (another structure of the edit failed).
    pub(crate) fn undo_load(&mut self, c: &mut CompiledShell, old: StripLoad) {
        match (&mut self.runs, &mut c.model) {
            (Runs::Midedge(r), StripModel::Midedge(m)) => r.undo_load(m, old),
            (Runs::Bspline(r), StripModel::Bspline(m)) => r.undo_load(m, old),
            (Runs::MidedgeContact(r), StripModel::Midedge(m)) => r.undo_load(m, old),
            _ => unreachable!("a run is built from its own model"),
        }
    }

    /// The last solve of the strip's run in contact with the scene's obstacles (`None`
    /// without obstacles).
    pub(crate) fn contact_report(&self) -> Option<&SolveReport> {
        match &self.runs {
            Runs::MidedgeContact(r) => Some(&r.report),
            _ => None,
        }
    }

    /// The strip's run in contact with the scene's obstacles (`None` without obstacles).
    pub(crate) fn contact_run_mut(&mut self) -> Option<&mut ContactStripRun> {
        match &mut self.runs {
            Runs::MidedgeContact(r) => Some(r),
            _ => None,
        }
    }

    /// The pose of clamp `k` (in the order of the spec's `clamps`): the position of its
    /// edge's centre (m) and its rotation from rest.
    pub fn pose(&self, c: &CompiledShell, k: usize) -> Option<SupportPose> {
        let clamp = c.clamps.get(k)?;
        let pose: Clamp = match &self.runs {
            Runs::Midedge(r) => r.state.clamps[clamp.end.index()],
            Runs::Bspline(r) => r.state.clamps[clamp.end.index()],
            Runs::MidedgeContact(r) => r.state.clamps[clamp.end.index()],
        };
        Some(SupportPose {
            position: pose.position(&clamp.centre),
            rotation: pose.rotation,
        })
    }

    /// Moves clamp `k` by `rotation` (rotation vector, rad, about its edge's centre) and
    /// `translation` (m) in `steps` load steps or more, warm from the last equilibrium; a move
    /// that does not converge keeps the last equilibrium (the report says so).
    pub(crate) fn move_clamp(
        &mut self,
        c: &mut CompiledShell,
        k: usize,
        rotation: Vec3,
        translation: Vec3,
        steps: f64,
    ) -> SolveReport {
        let pivot = self.pose(c, k).expect("a clamp of this strip").position;
        let motion = ClampMotion {
            end: c.clamps[k].end,
            pivot: pivot.into(),
            rotation: rotation.into(),
            translation: translation.into(),
        };
        self.solve_motions(c, &[motion], steps)
    }

    /// The strip's results at its current equilibrium (allocates; the clamp force is
    /// differentiated numerically: for output, not per Newton step).
    pub fn result(&self, c: &CompiledShell) -> ShellResult {
        match (&self.runs, &c.model) {
            (Runs::Midedge(r), StripModel::Midedge(m)) => midedge_result(
                &c.name,
                m,
                &r.state,
                &r.report,
                self.rod_predictor_used,
                None,
            ),
            (Runs::MidedgeContact(r), StripModel::Midedge(m)) => midedge_result(
                &c.name,
                m,
                &r.state,
                &r.report,
                false,
                Some(&r.contacts(m).unwrap_or(StripContacts {
                    contacts: Vec::new(),
                    min_gap: f64::NAN,
                    through: Vec::new(),
                })),
            ),
            (Runs::Bspline(r), StripModel::Bspline(m)) => {
                bspline_result(&c.name, m, &r.state, &r.report)
            }
            _ => unreachable!("a run is built from its own model"),
        }
    }

    /// The mid-edge state, if the strip is a mid-edge shell.
    pub fn midedge_state(&self) -> Option<&ShellState> {
        match &self.runs {
            Runs::Midedge(r) => Some(&r.state),
            Runs::MidedgeContact(r) => Some(&r.state),
            Runs::Bspline(_) => None,
        }
    }

    /// The strip's contacts with the obstacles at its current equilibrium (`None` without
    /// obstacles).
    pub(crate) fn contacts(&self, c: &CompiledShell) -> Option<StripContacts> {
        match (&self.runs, &c.model) {
            (Runs::MidedgeContact(r), StripModel::Midedge(m)) => r.contacts(m),
            _ => None,
        }
    }

    /// The B-spline state, if the strip is a B-spline shell.
    pub fn bspline_state(&self) -> Option<&BsplineState> {
        match &self.runs {
            Runs::Bspline(r) => Some(&r.state),
            Runs::Midedge(_) | Runs::MidedgeContact(_) => None,
        }
    }
}

/// The rotation vector (rad) and translation (m) that take `from` to `to` about the centre of
/// `from` (a clamp's current pose to its target).
pub(crate) fn pose_change(from: &SupportPose, to: &SupportPose) -> (Vec3, Vec3) {
    (
        rotation_vector(&(to.rotation * from.rotation.inverse())),
        to.position - from.position,
    )
}
