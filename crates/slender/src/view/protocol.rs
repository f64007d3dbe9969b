//! The messages between the page and `slender view`: one JSON request per HTTP POST, one JSON
//! reply. [`handle`] is the whole protocol, without a socket (the fuzz test drives it
//! directly): it parses a request, applies it to the [`Session`] and answers with what
//! changed. A request that cannot be applied (bad JSON, unknown support, non-finite pose, a
//! clip beyond the cable, a move too large) gets `{"ok": false, "error": {...}}` naming the
//! problem, and the session keeps its last equilibrium; a move that does not converge is
//! `ok` with `edit.converged = false` (the last equilibrium is kept and shown).

use std::time::Instant;

use nalgebra::Rotation3;
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use slender_core::geometry::Vec3;
use slender_core::scene::spec::{SupportKind, SupportSpec, UnstablePolicy};
use slender_core::scene::{EditReport, SceneError, Session, SupportPose};

use super::state::{scene_geometry, view_state, SceneGeometry, ViewState};
use crate::solve::gltf;

/// Largest request the server reads (bytes).
pub const MAX_REQUEST_BYTES: usize = 1 << 20;

/// A request from the page. Indices are 0-based: `rod` in the scene's `rods`, `support` in
/// that rod's supports as the last [`ViewState`] lists them; a move addresses a strip's clamp
/// with `shell` (index in `shells`) instead of `rod`, and `support` is then the clamp's index
/// in that strip's `clamps`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
// Field-less operations are empty struct variants (`State {}`), not unit variants: serde's
// internally tagged unit variants ignore unknown keys even with `deny_unknown_fields`.
#[serde(tag = "op", rename_all = "snake_case", deny_unknown_fields)]
pub enum Request {
    /// The current equilibria (no change), and the obstacles' shapes (`geometry`): what the
    /// page asks first.
    State {},
    /// Move a support to an absolute pose (what a drag sends).
    Move {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// Support index (a strip's clamp index with `shell`).
        support: usize,
        /// Target position of the support's vertex (m; a strip's clamp: the centre of its
        /// edge).
        position: [f64; 3],
        /// Target orientation relative to rest, as a rotation vector (rad); absent: keep the
        /// current orientation.
        #[serde(default)]
        rotation: Option<[f64; 3]>,
    },
    /// Move a support to a typed pose: as `move`, but one step of undo by itself (a `move` is
    /// a piece of a drag, undone with the drag from its `checkpoint`).
    Place {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// Support index (a strip's clamp index with `shell`).
        support: usize,
        /// Target position of the support's vertex (m; a strip's clamp: the centre of its
        /// edge).
        position: [f64; 3],
        /// Target orientation relative to rest, as a rotation vector (rad); absent: keep the
        /// current orientation.
        #[serde(default)]
        rotation: Option<[f64; 3]>,
    },
    /// Move a support by a translation (m) and a rotation vector (rad, about its vertex).
    MoveBy {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// Support index (a strip's clamp index with `shell`).
        support: usize,
        /// Translation (m).
        #[serde(default)]
        translation: [f64; 3],
        /// Rotation vector (rad).
        #[serde(default)]
        rotation: [f64; 3],
    },
    /// Add a clip, pin, slider or twist hold at rest arc length `at` (m) of a rod, holding
    /// the rod where it is now.
    AddSupport {
        /// Rod index.
        rod: usize,
        /// Kind (not a clamp: clamps are added in the scene file).
        kind: SupportKind,
        /// Rest arc length from vertex 0 (m).
        at: f64,
    },
    /// Remove a support.
    RemoveSupport {
        /// Rod index.
        rod: usize,
        /// Support index.
        support: usize,
    },
    /// Set gravity (m/s²).
    Gravity {
        /// Acceleration (m/s²).
        gravity: [f64; 3],
    },
    /// Set a rod's rest length (m): cable paid out or pulled in between its supports, which
    /// stay where they are (`Session::set_rod_length`).
    Length {
        /// Rod index.
        rod: usize,
        /// New rest length (m).
        length: f64,
    },
    /// Move obstacle `obstacle` (index in the scene's `obstacles`) rigidly: turned by
    /// `rotation` (a rotation vector, rad) about its reference point, then shifted by
    /// `translation` (m); the cables it sweeps are carried along and every structure
    /// re-solves (`Session::move_obstacle_by`). The reply carries the moved shapes
    /// (`geometry`). As `drag_obstacle` it is a piece of a gizmo drag: the same move, undone
    /// with the whole drag from its `checkpoint` (an `obstacle` is one step of undo by itself).
    #[serde(alias = "drag_obstacle")]
    Obstacle {
        /// Obstacle index.
        obstacle: usize,
        /// Translation (m).
        #[serde(default)]
        translation: [f64; 3],
        /// Rotation vector (rad) about the obstacle's reference point, or about `pivot`.
        #[serde(default)]
        rotation: [f64; 3],
        /// The point (m) the rotation turns about, if not the obstacle's reference point (the
        /// page's gizmo turns an obstacle about the centre of its drawn shape).
        #[serde(default)]
        pivot: Option<[f64; 3]>,
    },
    /// Set a dead point force of a rod (the scene's `rods[rod].forces[force]`) or of a shell
    /// strip (`shells[shell].forces[force]`) to `value` (N).
    Force {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// Index in the rod's or strip's `forces`.
        force: usize,
        /// Force (N).
        value: [f64; 3],
    },
    /// Set a point moment of a rod (the scene's `rods[rod].moments[moment]`) to `value` (N m;
    /// a follower moment's as it acts at rest).
    Moment {
        /// Rod index.
        rod: usize,
        /// Index in the rod's `moments`.
        moment: usize,
        /// Moment (N m).
        value: [f64; 3],
    },
    /// Add a dead point moment, set to `value` (N m; default zero), as the last of the rod's
    /// `moments`, at the file's vertex nearest rest arc length `at` (m).
    AddMoment {
        /// Rod index.
        rod: usize,
        /// Rest arc length from vertex 0 (m).
        at: f64,
        /// Moment (N m).
        #[serde(default)]
        value: [f64; 3],
    },
    /// Remove point moment `moment` of a rod (first brought to zero warm).
    RemoveMoment {
        /// Rod index.
        rod: usize,
        /// Index in the rod's `moments`.
        moment: usize,
    },
    /// Add a dead point force, set to `value` (N; default zero), as the last of the rod's or
    /// strip's `forces`: on a rod at the file's vertex nearest rest arc length `at` (m), on a
    /// shell strip at grid vertex (`station`, `column`).
    AddForce {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// A rod's: rest arc length from vertex 0 (m).
        #[serde(default)]
        at: Option<f64>,
        /// A strip's: station along the length, 0 … elements.
        #[serde(default)]
        station: Option<usize>,
        /// A strip's: column across the width, 0 … width_elements.
        #[serde(default)]
        column: Option<usize>,
        /// Force (N).
        #[serde(default)]
        value: [f64; 3],
    },
    /// Remove point force `force` of a rod or a shell strip (a dead force is first brought to
    /// zero warm).
    RemoveForce {
        /// Rod index (or give `shell`).
        #[serde(default)]
        rod: Option<usize>,
        /// Shell strip index (or give `rod`).
        #[serde(default)]
        shell: Option<usize>,
        /// Index in the rod's or strip's `forces`.
        force: usize,
    },
    /// Follow every unstable equilibrium to a stable one now.
    FollowStable {},
    /// What to do with unstable equilibria from now on.
    UnstablePolicy {
        /// `follow` or `keep`.
        policy: UnstablePolicy,
    },
    /// The edited scene as TOML (its solve gives the current equilibrium).
    Save {},
    /// The current shapes as glTF 2.0 (JSON with an embedded buffer).
    Gltf {},
}

/// The error part of a reply: where and what.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ErrorReply {
    /// The offending field (e.g. `rods[0].supports[3]`, `request`).
    pub field: String,
    /// What is wrong and what would be valid.
    pub message: String,
}

impl From<SceneError> for ErrorReply {
    fn from(e: SceneError) -> Self {
        Self {
            field: e.path,
            message: e.message,
        }
    }
}

/// The outcome of an edit as the page shows it.
#[derive(Clone, Debug, Serialize)]
pub struct EditView {
    /// True if every re-solved structure converged (else the last equilibrium was kept).
    pub converged: bool,
    /// Why not.
    pub reason: Option<String>,
    /// Newton iterations.
    pub iterations: usize,
    /// Load steps.
    pub load_steps: usize,
    /// Largest relative residual of the re-solved structures.
    pub relative_residual: f64,
    /// True if every equilibrium is stable.
    pub stable: bool,
    /// True if an unstable equilibrium was followed to a stable one.
    pub followed_unstable_mode: bool,
}

impl From<EditReport> for EditView {
    fn from(r: EditReport) -> Self {
        Self {
            converged: r.converged,
            reason: r.reason,
            iterations: r.iterations,
            load_steps: r.load_steps,
            relative_residual: r.relative_residual,
            stable: r.stable,
            followed_unstable_mode: r.followed_unstable_mode,
        }
    }
}

/// A successful reply.
#[derive(Clone, Debug, Serialize)]
pub struct OkReply {
    /// Always true.
    pub ok: bool,
    /// The request's `op`.
    pub op: &'static str,
    /// The edit's outcome (absent for `state`, `save`, `gltf`).
    pub edit: Option<EditView>,
    /// Wall time of the solve (s), measured here.
    pub solve_seconds: f64,
    /// The equilibria now.
    pub view: ViewState,
    /// `state` and `obstacle`: the obstacles' shapes (only these replies carry them: the
    /// other edits leave the obstacles where they are).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub geometry: Option<SceneGeometry>,
    /// `save`: the scene as TOML.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub toml: Option<String>,
    /// `gltf`: the shapes as glTF.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gltf: Option<Value>,
    /// `undo`, `redo`: the steps left each way (see `history.rs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub history: Option<Value>,
}

/// The reply to `state`, named `op` and carrying `history` (the undo and redo steps left): what
/// an undo or redo answers. Serialized once, so that the view's numbers are those of `state`
/// to the bit (a parse and re-serialization of the text could move a float by an ulp).
pub fn state_reply(session: &mut Session, op: &'static str, history: Value) -> String {
    match apply(session, &Request::State {}) {
        Ok(mut reply) => {
            reply.op = op;
            reply.history = Some(history);
            serde_json::to_string(&reply).unwrap_or_else(|e| {
                error_reply("reply", format!("the reply could not be encoded: {e}"))
            })
        }
        Err(e) => json!({"ok": false, "op": op, "error": e}).to_string(),
    }
}

fn error_reply(field: impl Into<String>, message: impl Into<String>) -> String {
    json!({"ok": false, "error": ErrorReply { field: field.into(), message: message.into() }})
        .to_string()
}

fn op_name(r: &Request) -> &'static str {
    match r {
        Request::State {} => "state",
        Request::Move { .. } => "move",
        Request::Place { .. } => "place",
        Request::MoveBy { .. } => "move_by",
        Request::AddSupport { .. } => "add_support",
        Request::RemoveSupport { .. } => "remove_support",
        Request::Gravity { .. } => "gravity",
        Request::Length { .. } => "length",
        Request::Obstacle { .. } => "obstacle",
        Request::Force { .. } => "force",
        Request::Moment { .. } => "moment",
        Request::AddMoment { .. } => "add_moment",
        Request::RemoveMoment { .. } => "remove_moment",
        Request::AddForce { .. } => "add_force",
        Request::RemoveForce { .. } => "remove_force",
        Request::FollowStable {} => "follow_stable",
        Request::UnstablePolicy { .. } => "unstable_policy",
        Request::Save {} => "save",
        Request::Gltf {} => "gltf",
    }
}

fn finite(field: &str, v: &[f64]) -> Result<(), ErrorReply> {
    if v.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(ErrorReply {
            field: field.into(),
            message: format!("{v:?}: every component must be a finite number"),
        })
    }
}

/// Applies one request to the session; the reply as JSON text. Never panics on any input
/// text; on an error the session is unchanged.
pub fn handle(session: &mut Session, message: &str) -> String {
    if message.len() > MAX_REQUEST_BYTES {
        return error_reply(
            "request",
            format!("{} bytes: at most {MAX_REQUEST_BYTES}", message.len()),
        );
    }
    let request: Request = match serde_json::from_str(message) {
        Ok(r) => r,
        Err(e) => {
            // JSON has no non-finite numbers: say so rather than "expected value".
            let hint = if ["NaN", "Infinity", "inf"]
                .iter()
                .any(|w| message.contains(w))
            {
                " (NaN and Infinity are not numbers in JSON: every coordinate must be finite)"
            } else {
                ""
            };
            return error_reply(
                "request",
                format!(
                    "{e}{hint} (expected a JSON object with \"op\": state, move, place, move_by, add_support, remove_support, gravity, force, add_force, remove_force, follow_stable, unstable_policy, save or gltf)"
                ),
            );
        }
    };
    match apply(session, &request) {
        Ok(reply) => serde_json::to_string(&reply).unwrap_or_else(|e| {
            error_reply("reply", format!("the reply could not be encoded: {e}"))
        }),
        Err(e) => json!({"ok": false, "op": op_name(&request), "error": e}).to_string(),
    }
}

fn apply(session: &mut Session, request: &Request) -> Result<OkReply, ErrorReply> {
    let clock = Instant::now();
    let mut toml_text = None;
    let mut gltf_value = None;
    let edit: Option<EditReport> = match request {
        Request::State {} => None,
        Request::Move {
            rod,
            shell,
            support,
            position,
            rotation,
        }
        | Request::Place {
            rod,
            shell,
            support,
            position,
            rotation,
        } => {
            finite("position", position)?;
            if let Some(r) = rotation {
                finite("rotation", r)?;
            }
            let target = |current: SupportPose| SupportPose {
                position: Vec3::from(*position),
                rotation: rotation.map_or(current.rotation, |r| Rotation3::new(Vec3::from(r))),
            };
            match target_of(*rod, *shell)? {
                Target::Rod(rod) => {
                    let current = session
                        .pose(rod, *support)
                        .ok_or_else(|| no_support(session, rod, *support))?;
                    Some(session.move_support(rod, *support, target(current))?)
                }
                Target::Shell(shell) => {
                    let current = session
                        .shell_pose(shell, *support)
                        .ok_or_else(|| no_clamp(session, shell, *support))?;
                    Some(session.move_shell_clamp(shell, *support, target(current))?)
                }
            }
        }
        Request::MoveBy {
            rod,
            shell,
            support,
            translation,
            rotation,
        } => {
            finite("translation", translation)?;
            finite("rotation", rotation)?;
            match target_of(*rod, *shell)? {
                Target::Rod(rod) => {
                    if session.pose(rod, *support).is_none() {
                        return Err(no_support(session, rod, *support));
                    }
                    Some(session.move_support_by(
                        rod,
                        *support,
                        Vec3::from(*rotation),
                        Vec3::from(*translation),
                    )?)
                }
                Target::Shell(shell) => {
                    if session.shell_pose(shell, *support).is_none() {
                        return Err(no_clamp(session, shell, *support));
                    }
                    Some(session.move_shell_clamp_by(
                        shell,
                        *support,
                        Vec3::from(*rotation),
                        Vec3::from(*translation),
                    )?)
                }
            }
        }
        Request::AddSupport { rod, kind, at } => {
            finite("at", &[*at])?;
            let length = session
                .compiled()
                .rods
                .get(*rod)
                .and_then(|r| r.node_arclengths.last().copied())
                .ok_or_else(|| no_rod(session, *rod))?;
            if !(0.0..=length).contains(at) {
                return Err(ErrorReply {
                    field: format!("rods[{rod}].supports.at"),
                    message: format!("{at} m: beyond the cable (its rest length is {length} m; valid: 0 ≤ at ≤ {length})"),
                });
            }
            Some(session.add_support(
                *rod,
                SupportSpec {
                    kind: *kind,
                    vertex: None,
                    at: Some(*at),
                    axis: None,
                },
            )?)
        }
        Request::RemoveSupport { rod, support } => {
            if session.pose(*rod, *support).is_none() {
                return Err(no_support(session, *rod, *support));
            }
            Some(session.remove_support(*rod, *support)?)
        }
        Request::Gravity { gravity } => {
            finite("gravity", gravity)?;
            Some(session.set_gravity(*gravity)?)
        }
        Request::Length { rod, length } => Some(session.set_rod_length(*rod, *length)?),
        Request::Obstacle {
            obstacle,
            translation,
            rotation,
            pivot,
        } => {
            finite("translation", translation)?;
            finite("rotation", rotation)?;
            let mut shift = Vec3::from(*translation);
            if let Some(pivot) = pivot {
                finite("pivot", pivot)?;
                // Turning by R about c, then shifting by t, is turning about the reference
                // point p and shifting by t + (I − R)(c − p).
                if let Some(p) = session.obstacle_reference(*obstacle) {
                    let c = Vec3::from(*pivot);
                    let r = nalgebra::Rotation3::new(Vec3::from(*rotation));
                    shift += (c - p) - r * (c - p);
                }
            }
            Some(session.move_obstacle_by(*obstacle, Vec3::from(*rotation), shift)?)
        }
        Request::Force {
            rod,
            shell,
            force,
            value,
        } => {
            finite("value", value)?;
            match target_of(*rod, *shell)? {
                Target::Rod(rod) => Some(session.set_force(rod, *force, *value)?),
                Target::Shell(shell) => Some(session.set_shell_force(shell, *force, *value)?),
            }
        }
        Request::Moment { rod, moment, value } => {
            finite("value", value)?;
            Some(session.set_moment(*rod, *moment, *value)?)
        }
        Request::AddMoment { rod, at, value } => {
            finite("value", value)?;
            finite("at", &[*at])?;
            Some(session.add_moment(*rod, *at, *value)?)
        }
        Request::RemoveMoment { rod, moment } => Some(session.remove_moment(*rod, *moment)?),
        Request::AddForce {
            rod,
            shell,
            at,
            station,
            column,
            value,
        } => {
            finite("value", value)?;
            let missing = |field: &str, what: &str| ErrorReply {
                field: field.into(),
                message: format!("missing: {what}"),
            };
            match target_of(*rod, *shell)? {
                Target::Rod(rod) => {
                    let at = at.ok_or_else(|| {
                        missing(
                            "at",
                            "a rod's force is placed by its rest arc length `at` (m)",
                        )
                    })?;
                    finite("at", &[at])?;
                    Some(session.add_force(rod, at, *value)?)
                }
                Target::Shell(shell) => {
                    let grid = "a strip's force is placed at grid vertex `station` (0 … elements) and `column` (0 … width_elements)";
                    let station = station.ok_or_else(|| missing("station", grid))?;
                    let column = column.ok_or_else(|| missing("column", grid))?;
                    Some(session.add_shell_force(shell, station, column, *value)?)
                }
            }
        }
        Request::RemoveForce { rod, shell, force } => match target_of(*rod, *shell)? {
            Target::Rod(rod) => Some(session.remove_force(rod, *force)?),
            Target::Shell(shell) => Some(session.remove_shell_force(shell, *force)?),
        },
        Request::FollowStable {} => Some(session.follow_stable()),
        Request::UnstablePolicy { policy } => {
            session.set_unstable_policy(*policy);
            None
        }
        Request::Save {} => {
            let text = toml::to_string(&session.saved()).map_err(|e| ErrorReply {
                field: "save".into(),
                message: format!("the scene could not be written as TOML: {e}"),
            })?;
            toml_text = Some(format!(
                "# Saved by `slender view`: the edited scene. Moved supports and obstacles are moved\n# from their rest pose by the [[motion]] stages; its solve gives the equilibrium shown.\n\n{text}"
            ));
            None
        }
        Request::Gltf {} => None,
    };
    let solve_seconds = clock.elapsed().as_secs_f64();
    let pieces = edit.as_ref().map_or(1, |e| e.load_steps);
    let step = session.results(0, None, 1.0, pieces);
    if matches!(request, Request::Gltf {}) {
        let scene = session.compiled();
        gltf_value = Some(gltf::rods_to_gltf(
            &scene.rods,
            &step.rods,
            &step.shells,
            gltf::scene_up(scene.gravity),
        ));
    }
    // The obstacles' shapes go with `state` and with every move of an obstacle.
    let geometry = matches!(request, Request::State {} | Request::Obstacle { .. })
        .then(|| scene_geometry(session, &step));
    Ok(OkReply {
        ok: true,
        op: op_name(request),
        edit: edit.map(EditView::from),
        solve_seconds,
        view: view_state(session, &step),
        geometry,
        toml: toml_text,
        gltf: gltf_value,
        history: None,
    })
}

/// What a move addresses.
enum Target {
    Rod(usize),
    Shell(usize),
}

fn target_of(rod: Option<usize>, shell: Option<usize>) -> Result<Target, ErrorReply> {
    match (rod, shell) {
        (Some(r), None) => Ok(Target::Rod(r)),
        (None, Some(s)) => Ok(Target::Shell(s)),
        (Some(_), Some(_)) => Err(ErrorReply {
            field: "shell".into(),
            message: "give either `rod` (a rod: its supports, its forces) or `shell` (a shell strip: its clamps, its forces), not both".into(),
        }),
        (None, None) => Err(ErrorReply {
            field: "rod".into(),
            message: "missing: give `rod` (a rod: its supports, its forces) or `shell` (a shell strip: its clamps, its forces)".into(),
        }),
    }
}

fn no_clamp(session: &Session, shell: usize, clamp: usize) -> ErrorReply {
    match session.compiled().shells.get(shell) {
        None => ErrorReply {
            field: format!("shells[{shell}]"),
            message: format!(
                "no such shell strip (the scene has {})",
                session.compiled().shells.len()
            ),
        },
        Some(s) => ErrorReply {
            field: format!("shells[{shell}].clamps[{clamp}]"),
            message: format!("no such clamp (the strip has {})", s.clamps.len()),
        },
    }
}

fn no_rod(session: &Session, rod: usize) -> ErrorReply {
    ErrorReply {
        field: format!("rods[{rod}]"),
        message: format!(
            "no such rod (the scene has {})",
            session.compiled().rods.len()
        ),
    }
}

fn no_support(session: &Session, rod: usize, support: usize) -> ErrorReply {
    match session.compiled().rods.get(rod) {
        None => no_rod(session, rod),
        Some(r) => ErrorReply {
            field: format!("rods[{rod}].supports[{support}]"),
            message: format!("no such support (the rod has {})", r.supports.len()),
        },
    }
}
