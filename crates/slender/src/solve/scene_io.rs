//! Reading scene files (TOML, or JSON by extension) into [`Scene`], with errors that give
//! the file, line and column; and the JSON Schema of the format.

use std::path::Path;

use anyhow::{bail, Context, Result};
use slender_core::scene::spec::ObstacleShapeSpec;
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

/// Reads and parses a scene file, and the obstacle meshes it names (`file`, relative to the
/// scene file's folder).
pub fn read_scene(path: &Path) -> Result<Scene> {
    let bytes = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    let Ok(text) = String::from_utf8(bytes) else {
        bail!("{}: not UTF-8 text", path.display());
    };
    let mut scene = parse_scene(&text, Syntax::of(path), &path.display().to_string())?;
    load_mesh_files(&mut scene, path.parent().unwrap_or(Path::new(".")))?;
    Ok(scene)
}

/// Replaces the vertices and triangles of every mesh obstacle that names a `file` by the
/// file's (relative paths from `folder`); errors name the obstacle.
pub fn load_mesh_files(scene: &mut Scene, folder: &Path) -> Result<()> {
    for (i, o) in scene.obstacles.iter_mut().enumerate() {
        if let ObstacleShapeSpec::Mesh {
            file: Some(file),
            vertices,
            triangles,
        } = &mut o.shape
        {
            let (v, t) = super::mesh_file::read_mesh(&folder.join(&*file))
                .with_context(|| format!("obstacles[{i}].shape.file"))?;
            *vertices = v;
            *triangles = t;
        }
    }
    Ok(())
}

/// The JSON Schema of the scene format, generated from the Rust types.
pub fn scene_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Scene)).expect("a schema serializes")
}

#[cfg(test)]
mod tests {
    use super::*;
    use slender_core::scene::Session;

    /// A cable clamped 5 mm above a floor given as an OBJ file next to the scene: the file is
    /// read, and the cable rests on it.
    #[test]
    fn a_mesh_obstacle_is_read_from_its_file_and_carries_the_cable() {
        let dir = std::env::temp_dir().join(format!("slender-scene-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("floor.obj"),
            "v -1 -1 0\nv 2 -1 0\nv 2 1 0\nv -1 1 0\nf 1 2 3 4\n",
        )
        .unwrap();
        let scene = r#"
gravity = [0.0, 0.0, -9.81]
[[rods]]
elements = 40
centerline = { kind = "straight", start = [0.0, 0.0, 0.008], direction = [1.0, 0.0, 0.0], length = 1.0 }
section = { shape = "circle", diameter = 0.006 }
material = { young = 1.0e8, poisson = 0.4, density = 1400.0 }
supports = [ { kind = "clamp", vertex = "start" } ]
[[obstacles]]
shape = { kind = "mesh", file = "floor.obj" }
"#;
        let path = dir.join("scene.toml");
        std::fs::write(&path, scene).unwrap();
        let spec = read_scene(&path).unwrap();
        let session = Session::new(spec).unwrap();
        assert!(session.report(0).converged(), "{:?}", session.report(0));
        let step = session.results(0, None, 1.0, 1);
        let obstacles = &step.obstacles;
        assert!(
            !obstacles[0].contacts.is_empty(),
            "the cable does not touch the mesh floor"
        );
        let gap = step.min_gap.expect("a min gap");
        assert!(gap > 0.0 && gap < 1e-5, "min gap {gap}");
        // A missing file is named with its obstacle.
        std::fs::write(&path, scene.replace("floor.obj", "nowhere.stl")).unwrap();
        let e = format!("{:#}", read_scene(&path).unwrap_err());
        assert!(
            e.contains("obstacles[0].shape.file") && e.contains("nowhere.stl"),
            "{e}"
        );
    }
}
