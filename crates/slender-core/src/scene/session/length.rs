//! Paying out and pulling in cable: a rod's rest length changed in a session.
//!
//! A harness is routed by its supports *and* by the length of its cables: more cable between
//! two connectors hangs lower and bends tighter, less pulls taut. The edit scales the rod's
//! rest centerline about its start (every rest arc length of the rod with it, so that each
//! support and load stays on the same point of the cable), keeps every support where it is
//! now, and re-solves from the current shape, in steps of at most [`MAX_LENGTH_STEP`] so that
//! each step starts near its equilibrium.

use super::{EditReport, Scene, SceneError, Session};
use crate::geometry::Vec3;
use crate::rod::RestCurve;
use crate::scene::magnitudes::{MAGNITUDE_FLOOR, MAGNITUDE_LIMIT};

/// Largest relative change of the rest length solved in one step (5 %): the carried shape is
/// then strained by at most that much before Newton starts, where a cable held taut between
/// its supports still finds its way to the slack (or taut) equilibrium.
const MAX_LENGTH_STEP: f64 = 0.05;
/// Halvings of a step that did not converge before the edit is given up.
const MAX_LENGTH_HALVINGS: usize = 6;
/// One edit changes the length by at most this factor either way.
const MAX_LENGTH_RATIO: f64 = 10.0;

impl Session {
    /// The rest length (m) of rod `rod`'s centerline.
    pub fn rod_length(&self, rod: usize) -> Option<f64> {
        self.scene
            .rods
            .get(rod)
            .and_then(|r| r.node_arclengths.last().copied())
    }

    /// Sets rod `rod`'s rest length to `length` (m) and re-solves from the current shape:
    /// cable paid out (longer) or pulled in (shorter) between supports that stay where they
    /// are. The rest centerline (straight, or a polyline: its shape kept) is scaled about its
    /// start, and with it every rest arc length of the rod (a support's `at`, a line load's
    /// range), so that supports and loads stay on the same point of the cable, where the
    /// supports stay; the saved scene has the new length and moves the supports from its
    /// rest centerline to their poses. The change is solved in steps of at most 5 %, halved up
    /// to six times where one does not converge, the last try a long minimization (past a
    /// fold the cable snaps to another shape); if that does not converge either, the rod
    /// keeps its length and its equilibrium and the report says so.
    ///
    /// Errors (nothing changed): an unknown rod; a length that is not finite and positive or
    /// changes the rod by more than ×10 either way; an arc or helix (their length goes with a
    /// radius and pitch); a closed loop; a scene the new length makes invalid (a joint whose
    /// rest points no longer meet), with that field's error.
    pub fn set_rod_length(&mut self, rod: usize, length: f64) -> Result<EditReport, SceneError> {
        let path = format!("rods[{rod}].centerline.length");
        let Some(current) = self.rod_length(rod) else {
            return Err(SceneError::new(
                format!("rods[{rod}]"),
                format!("no such rod (the scene has {})", self.scene.rods.len()),
            ));
        };
        if !(length.is_finite() && (MAGNITUDE_FLOOR..=MAGNITUDE_LIMIT).contains(&length)) {
            return Err(SceneError::new(
                path,
                format!("{length:?} m: must be finite and positive"),
            ));
        }
        let (low, high) = (current / MAX_LENGTH_RATIO, current * MAX_LENGTH_RATIO);
        if !(low..=high).contains(&length) {
            return Err(SceneError::new(
                path,
                format!(
                    "{length} m: one edit changes the length by at most ×{MAX_LENGTH_RATIO} \
                     (valid here: {low} m to {high} m)"
                ),
            ));
        }
        if !matches!(
            self.spec.rods[rod].centerline,
            RestCurve::Straight { .. } | RestCurve::Polyline { .. }
        ) {
            return Err(SceneError::new(
                format!("rods[{rod}].centerline"),
                "only a straight or polyline rest centerline has its length edited (an arc's \
                 or helix's length is set with its radius and pitch: edit the scene file)",
            ));
        }
        if self.spec.rods[rod].closed {
            return Err(SceneError::new(
                format!("rods[{rod}].closed"),
                "a closed loop has no ends to pay cable out between",
            ));
        }
        // Every error of the new length shows now, before anything moves.
        with_length(&self.spec, rod, length).compile()?;
        if length == current {
            return Ok(self.summary(&[], None));
        }

        let before = self.clone();
        let mut reached = current;
        let mut ratio_step = (1.0 + MAX_LENGTH_STEP).ln();
        let mut halvings = 0;
        let (mut iterations, mut load_steps, mut followed) = (0, 0, false);
        let mut last: Option<EditReport> = None;
        while reached != length {
            let remaining = (length / reached).ln();
            let next = if remaining.abs() <= ratio_step {
                length
            } else {
                reached * (ratio_step * remaining.signum()).exp()
            };
            // From the scene as it was, so that the arc lengths scale once, not step by step.
            let spec = with_length(&before.spec, rod, next);
            // The scene at `next` compiles if the final one does; should it not, its error
            // names the field.
            spec.compile().inspect_err(|_| *self = before.clone())?;
            let poses = self.poses.clone();
            let rest = self.rest_poses.clone();
            // The last try, with the smallest step, lets the structure settle by a long
            // minimization: past a fold of the length path (a slack loop between two clips
            // flipping over) no nearby equilibrium exists and smaller steps cannot help.
            let snap = halvings == MAX_LENGTH_HALVINGS;
            let stretch = Some((rod, next / reached));
            match self.rebuild_stretched(spec, poses, rest, stretch, snap) {
                Ok(r) => {
                    iterations += r.iterations;
                    load_steps += r.load_steps;
                    followed |= r.followed_unstable_mode;
                    last = Some(r);
                    reached = next;
                }
                Err(e) => {
                    halvings += 1;
                    if halvings > MAX_LENGTH_HALVINGS {
                        *self = before;
                        let mut r = self.summary(
                            &[],
                            Some(format!(
                                "the length change to {length} m did not converge (stuck at \
                                 {reached} m: {}); the last equilibrium is kept",
                                e.message
                            )),
                        );
                        r.iterations = iterations;
                        r.load_steps = load_steps;
                        return Ok(r);
                    }
                    ratio_step *= 0.5;
                }
            }
        }
        let mut r = last.expect("at least one step");
        r.iterations = iterations;
        r.load_steps = load_steps;
        r.followed_unstable_mode = followed;
        Ok(r)
    }
}

/// `spec` with rod `rod`'s rest centerline scaled about its start to length `length` (m): a
/// straight one's `length` set, a polyline's points scaled (its turning angles kept), and
/// every rest arc length of the rod (a support's `at`, a line load's range and table) scaled
/// alike, so that each stays on the same point of the cable.
fn with_length(spec: &Scene, rod: usize, length: f64) -> Scene {
    let mut spec = spec.clone();
    let r = &mut spec.rods[rod];
    let current = match &mut r.centerline {
        RestCurve::Straight { length: l, .. } => std::mem::replace(l, length),
        RestCurve::Polyline { points } => {
            let p0 = Vec3::from(points[0]);
            let current: f64 = points
                .windows(2)
                .map(|w| (Vec3::from(w[1]) - Vec3::from(w[0])).norm())
                .sum();
            let scale = length / current;
            for p in points.iter_mut() {
                *p = (p0 + (Vec3::from(*p) - p0) * scale).into();
            }
            current
        }
        _ => return spec,
    };
    let scale = length / current;
    for s in r.supports.iter_mut() {
        if let Some(at) = &mut s.at {
            *at *= scale;
        }
    }
    for l in r.line_loads.iter_mut() {
        for s in [&mut l.from, &mut l.to].into_iter().flatten() {
            *s *= scale;
        }
        for row in l.table.iter_mut().flatten() {
            row[0] *= scale;
        }
    }
    spec
}
