//! Time stepping of a scene with a `[time]` table: every structure of rods integrated by its
//! own [`TimeStepper`] from the rest state at rest, with gravity and the loads acting from
//! t = 0. No I/O: the caller (`slender solve`) writes the frames.
//!
//! In a scene with contact (obstacles or self-contact) each structure is stepped as a
//! [`ContactProblem`](crate::contact::ContactProblem) built around it for each step (as the
//! [`Session`](super::Session) builds one per solve), with Coulomb friction by
//! [`step_with_friction`]: a step is solved with the current stick/slide set and re-solved
//! while a contact changes, so every accepted step satisfies Coulomb's law at its end. The
//! barrier and the time-of-impact step caps (which bound the stepper's first guess too) keep
//! every gap positive. Contacts within the activation distance of a rough surface at the
//! start stick where they are.
//!
//! Supports stay at their rest pose, so a time-stepped scene has no prescribed motion (it is
//! refused when compiling), and shells are refused too (see
//! [`compile::time`](super::compile::time)). Cosserat rods and SE(3) beams are stepped like
//! discrete elastic rods, with contact or without: the stepper takes their frames' rotary
//! inertia from the structure, through the contact problem when there is one.

use crate::contact::{step_with_friction, Friction};
use crate::dynamics::{FlatDofs, LumpedMass, StepReport, TimeStepper};
use crate::solver::{EquilibriumProblem, SolveReport, SolveStatus};
use crate::structure::{Structure, StructureState};

use super::compile::{CompiledScene, CompiledTime};
use super::contact_report::{contact_problem, contact_report};
use super::error::SceneError;
use super::result::{scene_results_with, FrameEnergy, SceneStep, StabilityResult, TimeFrame};

/// The outcome of one time step of the whole scene.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeStepOutcome {
    /// True if every structure's step converged.
    pub converged: bool,
    /// Newton iterations over the structures.
    pub iterations: usize,
    /// Largest residual force (N) of the structures' last iterates.
    pub residual: f64,
    /// Time (s) after the step; on failure, the time the step tried to reach.
    pub time: f64,
    /// Why the step failed (naming the structure and its rods), if it did.
    pub failure: Option<String>,
}

/// How one structure moves.
enum Motion<'a> {
    /// Without contact: its stepper, kept from step to step (boxed: it holds the Newton
    /// workspace, far larger than the other variant).
    Free(Box<TimeStepper<'a, Structure>>),
    /// With contact: its state, velocity (per free DOF, m/s and rad/s) and friction state;
    /// the contact problem and its stepper are built around them for each step (a stepper
    /// borrows its problem, which borrows the structure).
    Contact {
        state: StructureState,
        velocity: Vec<f64>,
        friction: Vec<Friction>,
        mass: LumpedMass,
    },
}

impl Motion<'_> {
    fn state(&self) -> &StructureState {
        match self {
            Motion::Free(s) => s.state(),
            Motion::Contact { state, .. } => state,
        }
    }

    fn friction(&self) -> &[Friction] {
        match self {
            Motion::Free(_) => &[],
            Motion::Contact { friction, .. } => friction,
        }
    }

    /// Kinetic energy (J) and the structure's potential energy at load `load` (J): elastic
    /// and loads, without the contact barrier and friction terms.
    fn energy(&self, s: &Structure, load: f64) -> (f64, f64) {
        match self {
            Motion::Free(st) => {
                let m = st.energy();
                (m.kinetic, m.potential)
            }
            Motion::Contact {
                state,
                velocity,
                mass,
                ..
            } => {
                // The frames' rotary kinetic energy ½ ωᵀ I ω turns with them: it needs their
                // orientations (none for discrete elastic rods).
                let mut orientations = Vec::new();
                s.frame_orientations(state, &mut orientations);
                let kinetic = mass
                    .kinetic_energy_at(velocity, &orientations)
                    .unwrap_or(f64::NAN);
                (kinetic, s.energy(state, load))
            }
        }
    }
}

/// A scene being stepped in time (see the module docs).
pub struct TimeRun<'a> {
    scene: &'a CompiledScene,
    time: CompiledTime,
    motions: Vec<Motion<'a>>,
    /// Per structure: the report of its last step.
    reports: Vec<SolveReport>,
    step: usize,
    iterations: usize,
    failed: bool,
}

fn report(status: SolveStatus, iterations: usize, residual: f64, energy: f64) -> SolveReport {
    SolveReport {
        status,
        load_reached: 1.0,
        iterations,
        load_steps: 1,
        rejected_steps: 0,
        snaps: 0,
        branch_switches: 0,
        residual,
        relative_residual: f64::NAN,
        force_scale: f64::NAN,
        residual_floor: f64::NAN,
        energy_decrement: f64::NAN,
        energy,
        inertia: None,
        lambda_min: None,
        lambda_min_normalized: None,
        modes: None,
    }
}

impl<'a> TimeRun<'a> {
    /// Starts the run of `scene` (which must have a `[time]` table) at t = 0, every structure
    /// at its rest state with velocity 0. Errors name the field (`time`, or what a stepper
    /// refuses).
    pub fn new(scene: &'a CompiledScene) -> Result<Self, SceneError> {
        let Some(time) = scene.time else {
            return Err(SceneError::new(
                "time",
                "the scene has no [time] table: nothing to step",
            ));
        };
        let mut motions = Vec::with_capacity(scene.structures.len());
        let mut reports = Vec::with_capacity(scene.structures.len());
        for (k, s) in scene.structures.iter().enumerate() {
            let rest = s.rest_state();
            let motion = match contact_problem(scene, k, rest, &[]) {
                None => Motion::Free(Box::new(
                    TimeStepper::at_rest(s, rest.clone(), time.params)
                        .map_err(|e| SceneError::model("time", e))?,
                )),
                Some(Err(e)) => return Err(SceneError::new("contact", e)),
                Some(Ok(problem)) => {
                    // Checks what a stepper refuses, once.
                    TimeStepper::at_rest(&problem, rest.clone(), time.params)
                        .map_err(|e| SceneError::model("time", e))?;
                    problem.update_friction(rest, None);
                    Motion::Contact {
                        state: rest.clone(),
                        velocity: vec![0.0; s.n_free()],
                        friction: problem.friction_state(),
                        mass: LumpedMass::of(s).map_err(|e| SceneError::model("time", e))?,
                    }
                }
            };
            reports.push(report(
                SolveStatus::Converged,
                0,
                f64::NAN,
                motion.energy(s, time.params.load).1,
            ));
            motions.push(motion);
        }
        Ok(Self {
            scene,
            time,
            motions,
            reports,
            step: 0,
            iterations: 0,
            failed: false,
        })
    }

    /// The validated `[time]` table.
    pub fn time_params(&self) -> &CompiledTime {
        &self.time
    }

    /// Time steps taken.
    pub fn steps_taken(&self) -> usize {
        self.step
    }

    /// True when every step has been taken (or one failed: the run stops there).
    pub fn finished(&self) -> bool {
        self.failed || self.step >= self.time.steps
    }

    /// The current time (s): steps taken times `dt`.
    pub fn time(&self) -> f64 {
        self.step as f64 * self.time.params.dt
    }

    /// The state of structure `k`.
    pub fn state(&self, k: usize) -> &StructureState {
        self.motions[k].state()
    }

    /// Energies of the current state (J), summed over the structures. With contact, the
    /// barrier's and the friction terms' energies are not included (friction dissipates).
    pub fn energy(&self) -> FrameEnergy {
        let mut e = FrameEnergy::default();
        for (s, m) in self.scene.structures.iter().zip(&self.motions) {
            let (kinetic, potential) = m.energy(s, self.time.params.load);
            let elastic = s.energy(m.state(), 0.0);
            e.kinetic += kinetic;
            e.elastic += elastic;
            e.gravity_and_loads += potential - elastic;
            e.potential += potential;
        }
        e.total = e.kinetic + e.potential;
        e
    }

    /// Takes one time step of every structure. After a failed step the run is finished: the
    /// structures stay where they were (those stepped before the failing one have advanced,
    /// so the scene's state is no longer one time) and no frame should be written.
    ///
    /// # Panics
    /// If the run is already finished.
    pub fn step(&mut self) -> TimeStepOutcome {
        assert!(!self.finished(), "the time run is finished");
        let target = (self.step + 1) as f64 * self.time.params.dt;
        let now = self.time();
        let mut out = TimeStepOutcome {
            converged: true,
            iterations: 0,
            residual: 0.0,
            time: target,
            failure: None,
        };
        for k in 0..self.motions.len() {
            let r = step_structure(self.scene, k, &mut self.motions[k], &self.time);
            out.iterations += r.iterations;
            out.residual = out.residual.max(r.residual);
            let status = if r.converged {
                SolveStatus::Converged
            } else {
                let rods: Vec<&str> = self
                    .scene
                    .rods
                    .iter()
                    .filter(|rod| rod.parts.iter().any(|p| p.structure == k))
                    .map(|rod| rod.name.as_str())
                    .collect();
                let why = r.failure.clone().unwrap_or_else(|| "no convergence".into());
                let reason = format!(
                    "time step {} (t = {} s -> {target} s) of the structure of rods {} did \
                     not converge after {} Newton iterations (residual {:.3e} N): {why}; a \
                     smaller time.dt or the backward_euler scheme may help",
                    self.step + 1,
                    now,
                    rods.join(", "),
                    r.iterations,
                    r.residual,
                );
                out.converged = false;
                out.failure = Some(reason.clone());
                SolveStatus::NotConverged { reason }
            };
            let potential = self.motions[k]
                .energy(&self.scene.structures[k], self.time.params.load)
                .1;
            self.reports[k] = report(status, r.iterations, r.residual, potential);
            if !r.converged {
                self.failed = true;
                return out;
            }
        }
        self.step += 1;
        self.iterations = out.iterations;
        out
    }

    /// The current state as a frame (allocates: for output). `frame` numbers it.
    pub fn frame(&self, frame: usize) -> SceneStep {
        let states: Vec<StructureState> = self.motions.iter().map(|m| m.state().clone()).collect();
        let stability: Vec<StabilityResult> = self
            .reports
            .iter()
            .map(|_| StabilityResult {
                stable: true,
                unstable_modes: 0,
                null_modes: 0,
                followed_unstable_mode: false,
                left_unstable_modes: 0,
                energy_drop: 0.0,
            })
            .collect();
        let friction: Vec<&[Friction]> = self.motions.iter().map(|m| m.friction()).collect();
        let contacts = contact_report(self.scene, &states, &friction);
        let (rods, structures) = scene_results_with(
            self.scene,
            &states,
            &self.reports,
            &stability,
            &contacts.external,
        );
        let converged = !self.failed;
        let t = self.time();
        SceneStep {
            step: frame,
            stage: None,
            stage_fraction: t / (self.time.steps as f64 * self.time.params.dt),
            seconds: 0.0,
            pieces: 1,
            rods,
            structures,
            shells: Vec::new(),
            converged,
            stable: true,
            obstacles: contacts.obstacles,
            min_gap: contacts.min_gap,
            segment_contacts: contacts.segment_contacts,
            min_segment_gap: contacts.min_segment_gap,
            edges_through_obstacles: contacts.edges_through_obstacles,
            time: Some(TimeFrame {
                t,
                frame,
                time_step: self.step,
                energy: self.energy(),
                iterations: if self.step == 0 { 0 } else { self.iterations },
                converged,
            }),
        }
    }
}

/// Newton iterations allowed per time step of a structure in contact. An impact's steps are
/// capped by the time of impact (a tenth of each closing gap kept, for every DOF at once),
/// so the step that lands needs more iterations than a free motion's.
pub const CONTACT_STEP_ITERATIONS: usize = 300;

/// The time parameters of a structure in contact: [`CONTACT_STEP_ITERATIONS`] at least.
fn contact_params(time: &CompiledTime) -> crate::dynamics::DynamicsParams {
    let mut p = time.params;
    p.solver.max_iterations = p.solver.max_iterations.max(CONTACT_STEP_ITERATIONS);
    p
}

/// One time step of structure `k` in `motion` (left unchanged if the step fails).
fn step_structure(
    scene: &CompiledScene,
    k: usize,
    motion: &mut Motion<'_>,
    time: &CompiledTime,
) -> StepReport {
    let failed = |why: String| StepReport {
        converged: false,
        iterations: 0,
        residual: f64::NAN,
        time: 0.0,
        failure: Some(why),
    };
    match motion {
        Motion::Free(stepper) => stepper.step(),
        Motion::Contact {
            state,
            velocity,
            friction,
            ..
        } => {
            let problem = match contact_problem(scene, k, state, friction) {
                Some(Ok(p)) => p,
                Some(Err(e)) => return failed(e),
                None => return failed("contact: the scene has no contact".into()),
            };
            let mut stepper = match TimeStepper::new(
                &problem,
                state.clone(),
                velocity.clone(),
                contact_params(time),
            ) {
                Ok(s) => s,
                Err(e) => return failed(format!("time: {e}")),
            };
            let r = step_with_friction(&mut stepper, &problem);
            if r.converged {
                velocity.copy_from_slice(stepper.velocity());
                state.clone_from(stepper.state());
                *friction = problem.friction_state();
            }
            r
        }
    }
}
