//! Reading scene files (TOML, or JSON by extension) into [`Scene`], with errors that give
//! the file, line and column; and the JSON Schema of the format.

use std::path::Path;

use anyhow::{bail, Context, Result};
use slender_core::scene::Scene;

/// Scene file syntax.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Syntax {
    /// TOML (`.toml`, the default).
    Toml,
    /// JSON (`.json`).
    Json,
}

impl Syntax {
    /// From the file extension: `.json` is JSON, anything else TOML.
    pub fn of(path: &Path) -> Self {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("json") => Self::Json,
            _ => Self::Toml,
        }
    }
}

/// 1-based (line, column) of byte offset `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Parses scene text; `name` is used in messages (the file path).
pub fn parse_scene(text: &str, syntax: Syntax, name: &str) -> Result<Scene> {
    match syntax {
        Syntax::Toml => toml::from_str::<Scene>(text).map_err(|e| {
            let place = match e.span() {
                Some(span) => {
                    let (l, c) = line_col(text, span.start);
                    format!("{name}:{l}:{c}")
                }
                None => name.to_string(),
            };
            anyhow::anyhow!("{place}: {}", e.message().trim_end())
        }),
        Syntax::Json => serde_json::from_str::<Scene>(text)
            .map_err(|e| anyhow::anyhow!("{name}:{}:{}: {e}", e.line(), e.column())),
    }
}

/// Reads and parses a scene file.
pub fn read_scene(path: &Path) -> Result<Scene> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    let Ok(text) = String::from_utf8(bytes) else {
        bail!("{}: not UTF-8 text", path.display());
    };
    parse_scene(&text, Syntax::of(path), &path.display().to_string())
}

/// The JSON Schema of the scene format, generated from the Rust types.
pub fn scene_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Scene)).expect("a schema serializes")
}
