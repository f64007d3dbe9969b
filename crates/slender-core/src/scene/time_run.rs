//! Time stepping of a scene with a `[time]` table: every structure of rods integrated by its
//! own [`TimeStepper`] from the rest state at rest, with gravity and the loads acting from
//! t = 0. No I/O: the caller (`slender solve`) writes the frames.
//!
//! Supports stay at their rest pose, so a time-stepped scene has no prescribed motion (it is
//! refused when compiling), and shells are refused too (see
//! [`compile::time`](super::compile::time)). Cosserat rods and SE(3) beams are stepped like
//! discrete elastic rods: the stepper takes their frames' rotary inertia from the structure.

use crate::dynamics::TimeStepper;
use crate::solver::{EquilibriumProblem, SolveReport, SolveStatus};
use crate::structure::{Structure, StructureState};

use super::compile::{CompiledScene, CompiledTime};
use super::error::SceneError;
use super::result::{scene_results, FrameEnergy, SceneStep, StabilityResult, TimeFrame};

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

/// A scene being stepped in time (see the module docs).
pub struct TimeRun<'a> {
    scene: &'a CompiledScene,
    time: CompiledTime,
    steppers: Vec<TimeStepper<'a, Structure>>,
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
        let mut steppers = Vec::with_capacity(scene.structures.len());
        let mut reports = Vec::with_capacity(scene.structures.len());
        for s in &scene.structures {
            let stepper = TimeStepper::at_rest(s, s.rest_state().clone(), time.params)
                .map_err(|e| SceneError::model("time", e))?;
            reports.push(report(
                SolveStatus::Converged,
                0,
                f64::NAN,
                stepper.energy().potential,
            ));
            steppers.push(stepper);
        }
        Ok(Self {
            scene,
            time,
            steppers,
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
        self.steppers[k].state()
    }

    /// Energies of the current state (J), summed over the structures.
    pub fn energy(&self) -> FrameEnergy {
        let mut e = FrameEnergy::default();
        for (s, st) in self.scene.structures.iter().zip(&self.steppers) {
            let m = st.energy();
            let elastic = s.energy(st.state(), 0.0);
            e.kinetic += m.kinetic;
            e.elastic += elastic;
            e.gravity_and_loads += m.potential - elastic;
            e.potential += m.potential;
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
        for (k, stepper) in self.steppers.iter_mut().enumerate() {
            let r = stepper.step();
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
            self.reports[k] = report(status, r.iterations, r.residual, stepper.energy().potential);
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
        let states: Vec<StructureState> = self.steppers.iter().map(|s| s.state().clone()).collect();
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
        let (rods, structures) = scene_results(self.scene, &states, &self.reports, &stability);
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
            obstacles: Vec::new(),
            min_gap: None,
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
