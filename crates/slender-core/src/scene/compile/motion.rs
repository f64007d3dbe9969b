//! Validation of prescribed support motion.

use crate::geometry::Vec3;

use super::super::error::SceneError;
use super::super::spec::{MotionStage, SupportKind};
use super::rod::CompiledRod;
use crate::scene::shells::CompiledShell;

/// Largest rotation (rad) of a support per load step of a motion step.
pub const MAX_STEP_ROTATION: f64 = 0.2;
/// Largest translation per load step, as a fraction of the moving part's length.
pub const MAX_STEP_TRANSLATION: f64 = 0.05;
/// Largest number of load steps one motion step may need.
const MAX_PIECES_PER_STEP: f64 = 1000.0;

fn finite3(path: &str, v: [f64; 3]) -> Result<Vec3, SceneError> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(Vec3::from(v))
    } else {
        Err(SceneError::new(
            path,
            format!("{v:?}: every component must be a finite number"),
        ))
    }
}

/// Checks motion stage `k` against the compiled rods (`shortest[r]`: the shortest part of rod
/// r, which sets the largest translation per load step).
pub(super) fn check_stage(
    k: usize,
    stage: &MotionStage,
    rods: &[CompiledRod],
    shortest: &[f64],
    shells: &[CompiledShell],
    obstacles: usize,
) -> Result<(), SceneError> {
    let path = format!("motion[{k}]");
    let rod_index = match (stage.rod, stage.shell, stage.obstacle) {
        (Some(r), None, None) => r,
        (None, Some(s), None) => return check_shell_stage(&path, stage, s, shells),
        (None, None, Some(o)) => {
            return check_obstacle_stage(&path, stage, o, obstacles, shortest, shells)
        }
        (None, None, None) => {
            return Err(SceneError::new(
                format!("{path}.rod"),
                "missing: give `rod` (a rod's support), `shell` (a strip's clamp) or \
                 `obstacle`",
            ))
        }
        (Some(_), Some(_), _) => {
            return Err(SceneError::new(
                format!("{path}.shell"),
                "give either `rod` (a rod's support) or `shell` (a strip's clamp), not both",
            ))
        }
        _ => {
            return Err(SceneError::new(
                format!("{path}.obstacle"),
                "an obstacle stage moves the obstacle alone: give no `rod` or `shell` with it",
            ))
        }
    };
    let Some(rod) = rods.get(rod_index) else {
        return Err(SceneError::new(
            format!("{path}.rod"),
            format!("{rod_index}: must be < {} (number of rods)", rods.len()),
        ));
    };
    let Some(support) = rod.supports.get(stage.support) else {
        return Err(SceneError::new(
            format!("{path}.support"),
            format!(
                "{}: must be < {} (supports of rod {})",
                stage.support,
                rod.supports.len(),
                rod_index
            ),
        ));
    };
    let t = finite3(&format!("{path}.translate"), stage.translate)?;
    let rot = finite3(&format!("{path}.rotate"), stage.rotate)?;
    match support.kind {
        SupportKind::Pin | SupportKind::Slider if rot.norm() > 0.0 => {
            return Err(SceneError::new(
                format!("{path}.rotate"),
                "a pin or slider has no orientation to rotate; rotate clamps or clips, translate pins and sliders",
            ));
        }
        SupportKind::TwistHold if t.norm() > 0.0 => {
            return Err(SceneError::new(
                format!("{path}.translate"),
                "a twist hold has no position to translate; rotate it about its edge",
            ));
        }
        _ => {}
    }
    check_steps(&path, stage)?;
    check_pieces(&path, stage, t, rot, shortest[rod_index])
}

fn check_steps(path: &str, stage: &MotionStage) -> Result<(), SceneError> {
    if stage.steps == 0 || stage.steps > 10_000 {
        return Err(SceneError::new(
            format!("{path}.steps"),
            format!("{}: must be in 1..=10000", stage.steps),
        ));
    }
    Ok(())
}

/// A stage moving obstacle `obstacle` (of `count`), in a scene whose rods' shortest parts
/// are `shortest` long, with the strips `shells`.
fn check_obstacle_stage(
    path: &str,
    stage: &MotionStage,
    obstacle: usize,
    count: usize,
    shortest: &[f64],
    shells: &[CompiledShell],
) -> Result<(), SceneError> {
    if obstacle >= count {
        return Err(SceneError::new(
            format!("{path}.obstacle"),
            format!("{obstacle}: must be < {count} (number of obstacles)"),
        ));
    }
    let t = finite3(&format!("{path}.translate"), stage.translate)?;
    let rot = finite3(&format!("{path}.rotate"), stage.rotate)?;
    check_steps(path, stage)?;
    let length = shortest
        .iter()
        .copied()
        .chain(shells.iter().map(|c| c.length()))
        .fold(f64::INFINITY, f64::min);
    check_pieces(
        path,
        stage,
        t,
        rot,
        if length.is_finite() { length } else { 1.0 },
    )
}

/// A stage moving clamp `stage.support` of strip `shell`.
fn check_shell_stage(
    path: &str,
    stage: &MotionStage,
    shell: usize,
    shells: &[CompiledShell],
) -> Result<(), SceneError> {
    let Some(c) = shells.get(shell) else {
        return Err(SceneError::new(
            format!("{path}.shell"),
            format!("{shell}: must be < {} (number of shells)", shells.len()),
        ));
    };
    if stage.support >= c.clamps.len() {
        return Err(SceneError::new(
            format!("{path}.support"),
            format!(
                "{}: must be < {} (clamps of shell {shell})",
                stage.support,
                c.clamps.len()
            ),
        ));
    }
    let t = finite3(&format!("{path}.translate"), stage.translate)?;
    let rot = finite3(&format!("{path}.rotate"), stage.rotate)?;
    check_steps(path, stage)?;
    check_pieces(path, stage, t, rot, c.length())
}

/// Each step is solved in load steps small enough for Newton; bound their number so that an
/// absurd motion is an error, not an endless run (`length`: of the moving part, m).
fn check_pieces(
    path: &str,
    stage: &MotionStage,
    t: Vec3,
    rot: Vec3,
    length: f64,
) -> Result<(), SceneError> {
    // Each step is solved in load steps small enough for Newton; bound their number so that
    // an absurd motion is an error, not an endless run.
    let per_step = |v: Vec3| v.norm() / stage.steps as f64;
    let pieces =
        (per_step(rot) / MAX_STEP_ROTATION).max(per_step(t) / (MAX_STEP_TRANSLATION * length));
    if !(pieces <= MAX_PIECES_PER_STEP) {
        return Err(SceneError::new(
            path,
            format!(
                "the motion per step is too large ({:.3e} rad, {:.3e} m per step would need {pieces:.3e} solves); at most {} rad and {} m per step here: use more steps",
                per_step(rot),
                per_step(t),
                MAX_PIECES_PER_STEP * MAX_STEP_ROTATION,
                MAX_PIECES_PER_STEP * MAX_STEP_TRANSLATION * length
            ),
        ));
    }
    Ok(())
}
