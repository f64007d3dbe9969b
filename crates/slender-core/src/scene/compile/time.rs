//! The `[time]` table: validated into the parameters of a time integration, and the scene
//! checked for what time stepping covers (rods of every model, conservative loads, fixed
//! supports; obstacles, self-contact and friction, with rods of every model).

use crate::dynamics::DynamicsParams;

use super::super::error::SceneError;
use super::super::spec::{Scene, TimeSchemeSpec, TimeSpec};

/// Largest number of time steps a scene may ask for.
pub const MAX_TIME_STEPS: usize = 10_000_000;
/// Frames written by default (at most about this many).
pub const DEFAULT_FRAMES: usize = 200;

/// A validated `[time]` table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompiledTime {
    /// Time step, scheme, damping and Newton tolerances of each step.
    pub params: DynamicsParams,
    /// Number of time steps: ⌈duration/dt⌉ (within 1e-9 of an integer rounds to it).
    pub steps: usize,
    /// Steps between written frames (frame 0 and the last step are always written).
    pub output_every: usize,
}

impl CompiledTime {
    /// True if the state after time step `step` (0 = the start) is written as a frame.
    pub fn is_frame(&self, step: usize) -> bool {
        step.is_multiple_of(self.output_every) || step == self.steps
    }

    /// Number of frames written by a complete run.
    pub fn frames(&self) -> usize {
        (0..=self.steps).filter(|&k| self.is_frame(k)).count()
    }
}

fn finite_positive(path: &str, v: f64, unit: &str) -> Result<(), SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SceneError::new(
            path,
            format!("{v}: must be finite and > 0 ({unit})"),
        ))
    }
}

fn finite_non_negative(path: &str, v: f64, unit: &str) -> Result<(), SceneError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(SceneError::new(
            path,
            format!("{v}: must be finite and >= 0 ({unit})"),
        ))
    }
}

/// Validates `time` and checks that `scene` can be stepped in time. Errors name the field and
/// its valid range.
pub(crate) fn check_time(scene: &Scene, time: &TimeSpec) -> Result<CompiledTime, SceneError> {
    finite_positive("time.dt", time.dt, "s")?;
    finite_positive("time.duration", time.duration, "s")?;
    if time.duration < time.dt {
        return Err(SceneError::new(
            "time.duration",
            format!(
                "{}: must be >= time.dt = {} (at least one step)",
                time.duration, time.dt
            ),
        ));
    }
    finite_non_negative("time.rayleigh_mass", time.rayleigh_mass, "1/s")?;
    finite_non_negative("time.rayleigh_stiffness", time.rayleigh_stiffness, "s")?;
    let ratio = time.duration / time.dt;
    let steps_f = if (ratio - ratio.round()).abs() <= 1e-9 * ratio {
        ratio.round()
    } else {
        ratio.ceil()
    };
    if !(steps_f <= MAX_TIME_STEPS as f64) {
        return Err(SceneError::new(
            "time.duration",
            format!(
                "{} s in steps of {} s is {steps_f:.3e} steps; at most {MAX_TIME_STEPS} \
                 (raise time.dt or shorten time.duration)",
                time.duration, time.dt
            ),
        ));
    }
    let steps = steps_f as usize;
    let output_every = match time.output_every {
        Some(0) => {
            return Err(SceneError::new(
                "time.output_every",
                "0: must be an integer >= 1 (time steps between written frames)",
            ))
        }
        Some(k) => k,
        None => steps.div_ceil(DEFAULT_FRAMES).max(1),
    };
    // Every rod model is stepped, with contact or without: the Cosserat rod's and the SE(3)
    // beam's frames carry their rotary inertia (dynamics::IncrementalProblem), which the
    // contact problem forwards from the structure it wraps.
    for (i, rod) in scene.rods.iter().enumerate() {
        for (k, f) in rod.forces.iter().enumerate() {
            if f.follower {
                return Err(SceneError::new(
                    format!("rods[{i}].forces[{k}].follower"),
                    "a follower load is not conservative and cannot be stepped in time \
                     ([time]); use a dead load (follower = false) or remove [time]",
                ));
            }
        }
        for (k, m) in rod.moments.iter().enumerate() {
            if m.follower {
                return Err(SceneError::new(
                    format!("rods[{i}].moments[{k}].follower"),
                    "a follower moment is not conservative and cannot be stepped in time \
                     ([time]); use a dead moment (follower = false) or remove [time]",
                ));
            }
        }
    }
    if !scene.shells.is_empty() {
        return Err(SceneError::new(
            "shells",
            "time stepping ([time]) covers rods only; a scene with [[shells]] cannot have \
             [time] (remove one of them)",
        ));
    }
    let contact =
        !scene.obstacles.is_empty() || scene.contact.as_ref().is_some_and(|c| c.self_contact);
    if contact && time.scheme == TimeSchemeSpec::Midpoint {
        // The solve's unknown is the midpoint y, kept outside every obstacle by the barrier
        // and the step caps; x_{n+1} = 2y − xₙ is extrapolated past it and, at an impact,
        // ends inside the obstacle.
        return Err(SceneError::new(
            "time.scheme",
            "\"midpoint\" cannot step a scene with contact (obstacles or self-contact): its \
             new state 2y − xₙ is extrapolated past the solved midpoint y and can end inside \
             an obstacle; use \"backward_euler\" (dissipative, robust at impacts) or \
             \"energy_conserving\"",
        ));
    }
    if !scene.motion.is_empty() {
        return Err(SceneError::new(
            "motion",
            "prescribed motion ([[motion]]) is not supported with [time]: supports stay at \
             their rest pose during time stepping (remove one of them)",
        ));
    }
    if scene.rods.is_empty() {
        return Err(SceneError::new(
            "rods",
            "[time] needs at least one rod to step",
        ));
    }
    let params = DynamicsParams::new(time.dt)
        .with_scheme(time.scheme.scheme())
        .with_rayleigh(time.rayleigh_mass, time.rayleigh_stiffness);
    params
        .validate()
        .map_err(|e| SceneError::model("time", e))?;
    Ok(CompiledTime {
        params,
        steps,
        output_every,
    })
}
