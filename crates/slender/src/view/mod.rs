//! `slender view SCENE`: the interactive cable-editing page. A local HTTP server owns one
//! [`Session`] (the physics runs natively in this process, every model); the page (plain
//! HTML, ES modules and vendored three.js, embedded in the binary) draws the equilibria, the
//! obstacles and their contacts, and sends edits: drag a support, add a clip, delete a
//! support, change gravity, edit, add and remove point forces, snap to the stable branch,
//! undo and redo, save the scene, export glTF.
//!
//! Layout: [`protocol`] (the messages and their handler, socket-free), [`history`] (undo and
//! redo around it), [`state`] (what the page draws), [`server`] (HTTP), [`socket`] (the page's WebSocket), `page/` (the page and
//! `vendor/three`).

pub mod history;
pub mod protocol;
pub mod server;
pub mod socket;
pub mod state;

#[cfg(test)]
mod fuzz;

use std::path::PathBuf;
use std::time::Instant;

use anyhow::Result;
use slender_core::scene::Session;

use crate::solve::scene_io;

/// Options of `slender view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// Scene file (.toml, or .json).
    pub scene: PathBuf,
    /// Port to listen on (0: any free port; the URL is printed).
    #[arg(long, default_value_t = 8765)]
    pub port: u16,
    /// Interface to listen on. The default serves this machine only; another address (e.g.
    /// 0.0.0.0) lets other machines edit the session.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: String,
}

/// Solves the scene, starts the server and prints the page's URL; serves until stopped.
pub fn run(args: &ViewArgs) -> Result<bool> {
    let scene = scene_io::read_scene(&args.scene)?;
    let clock = Instant::now();
    let session =
        Session::new(scene).map_err(|e| anyhow::anyhow!("{}: {e}", args.scene.display()))?;
    let step = session.results(0, None, 1.0, 1);
    println!(
        "solved {} in {:.3} s: {}{}",
        args.scene.display(),
        clock.elapsed().as_secs_f64(),
        if step.converged {
            "converged"
        } else {
            "NOT converged"
        },
        if step.stable { "" } else { ", unstable" }
    );
    let name = args
        .scene
        .file_name()
        .map_or_else(|| "scene".to_string(), |n| n.to_string_lossy().into_owned());
    let server = server::ViewServer::bind(&args.host, args.port, &name)?;
    println!(
        "slender view: open {}  (Ctrl-C stops the server)",
        server.url()
    );
    let mut session = session;
    server.serve(&mut session)?;
    Ok(true)
}
