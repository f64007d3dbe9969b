//! Undo and redo for `slender view`: whole-session snapshots around the protocol's handler.
//!
//! A snapshot is a clone of the [`Session`] (its equilibria, supports, loads and solver
//! workspaces), so an undo puts back exactly the equilibrium that was shown, branch included —
//! no re-solve, which for a bistable cable could land on the other branch. Discrete edits
//! (adding or removing a support or force, gravity, a cable's length, a force's value, a typed pose (`place`), a
//! `move_by`, snapping to the stable branch) take a snapshot before they run and keep it when they change the
//! session. A drag is many `move` messages: the page sends `checkpoint` when it starts, so the
//! whole drag is one step back. At most [`MAX_UNDO`] steps are kept.

use serde::Deserialize;
use serde_json::{json, Value};
use slender_core::scene::Session;

use super::protocol::{handle, state_reply};

/// Steps kept for undo (the oldest are dropped): each is a whole session.
pub const MAX_UNDO: usize = 30;

/// The sessions to go back and forth to.
#[derive(Default)]
pub struct History {
    undo: Vec<Session>,
    redo: Vec<Session>,
}

/// The operation of a message, read without the rest of it.
#[derive(Deserialize)]
struct Op {
    op: String,
}

/// Operations that change the session in one step and are undone one by one.
const DISCRETE: [&str; 14] = [
    "place",
    "obstacle",
    "move_by",
    "add_support",
    "remove_support",
    "gravity",
    "length",
    "force",
    "add_force",
    "remove_force",
    "moment",
    "add_moment",
    "remove_moment",
    "follow_stable",
];

impl History {
    /// Handles one message of the protocol, plus `undo`, `redo` and `checkpoint` (their
    /// replies give the number of steps each way in `history`); never panics on any input, and
    /// on an error the session is unchanged.
    pub fn handle(&mut self, session: &mut Session, message: &str) -> String {
        let op = serde_json::from_str::<Op>(message).map(|o| o.op);
        match op.as_deref() {
            Ok("undo") => self.step(session, true),
            Ok("redo") => self.step(session, false),
            Ok("checkpoint") => {
                self.push(session.clone());
                self.depths(json!({"ok": true, "op": "checkpoint"}))
            }
            Ok(op) if DISCRETE.contains(&op) => {
                let before = session.clone();
                let reply = handle(session, message);
                if changed(&reply) {
                    self.push(before);
                }
                reply
            }
            // Moves (a drag after its checkpoint), state, save, glTF, bad messages.
            _ => handle(session, message),
        }
    }

    /// A new step back to `s`; the steps forward are gone.
    fn push(&mut self, s: Session) {
        if self.undo.len() == MAX_UNDO {
            self.undo.remove(0);
        }
        self.undo.push(s);
        self.redo.clear();
    }

    /// One step back (`back`) or forward: the session swapped with the stored one; the reply is
    /// the new state's, as the `state` message gives it.
    fn step(&mut self, session: &mut Session, back: bool) -> String {
        let name = if back { "undo" } else { "redo" };
        let (from, to) = if back {
            (&mut self.undo, &mut self.redo)
        } else {
            (&mut self.redo, &mut self.undo)
        };
        let Some(mut other) = from.pop() else {
            return json!({"ok": false, "op": name, "error": {"field": name, "message": format!("nothing to {name}")}})
                .to_string();
        };
        std::mem::swap(session, &mut other);
        to.push(other);
        let depths = json!({"undo": self.undo.len(), "redo": self.redo.len()});
        state_reply(session, name, depths)
    }

    /// `reply` (a small object) with the number of steps back and forward.
    fn depths(&self, mut reply: Value) -> String {
        reply["history"] = json!({"undo": self.undo.len(), "redo": self.redo.len()});
        reply.to_string()
    }
}

/// True if a reply reports a change of the session: ok, and its edit (if any) converged (an
/// edit that does not converge keeps the last equilibrium).
fn changed(reply: &str) -> bool {
    #[derive(Deserialize)]
    struct Edit {
        converged: bool,
    }
    #[derive(Deserialize)]
    struct Reply {
        ok: bool,
        edit: Option<Edit>,
    }
    serde_json::from_str::<Reply>(reply).is_ok_and(|r| r.ok && r.edit.is_none_or(|e| e.converged))
}
