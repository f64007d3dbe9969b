//! Obstacle meshes from files: STL (ASCII or binary, `stl_io`) and Wavefront OBJ (`tobj`,
//! polygons triangulated), as the vertex and triangle lists of the scene's inline mesh.

use std::path::Path;

use anyhow::{bail, Context as _, Result};

/// A triangle mesh: vertices (m, as written in the file) and vertex index triples.
pub type MeshData = (Vec<[f64; 3]>, Vec<[usize; 3]>);

/// Reads the mesh in `path`, by its extension (`.stl` or `.obj`, any case).
pub fn read_mesh(path: &Path) -> Result<MeshData> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let mesh = match extension.as_deref() {
        Some("stl") => read_stl(path),
        Some("obj") => read_obj(path),
        _ => bail!(
            "{}: unknown mesh format (expected a .stl or .obj file)",
            path.display()
        ),
    }
    .with_context(|| format!("reading the obstacle mesh {}", path.display()))?;
    if mesh.1.is_empty() {
        bail!("{}: the mesh has no triangle", path.display());
    }
    Ok(mesh)
}

fn read_stl(path: &Path) -> Result<MeshData> {
    let mut file = std::fs::File::open(path)?;
    let mesh = stl_io::read_stl(&mut file)?;
    let vertices = mesh
        .vertices
        .iter()
        .map(|v| [f64::from(v[0]), f64::from(v[1]), f64::from(v[2])])
        .collect();
    let triangles = mesh.faces.iter().map(|f| f.vertices).collect();
    Ok((vertices, triangles))
}

fn read_obj(path: &Path) -> Result<MeshData> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(path, &options)?;
    let mut vertices = Vec::new();
    let mut triangles = Vec::new();
    for model in models {
        let m = &model.mesh;
        let base = vertices.len();
        vertices.extend(
            m.positions
                .chunks_exact(3)
                .map(|p| [f64::from(p[0]), f64::from(p[1]), f64::from(p[2])]),
        );
        triangles.extend(m.indices.chunks_exact(3).map(|t| {
            [
                base + t[0] as usize,
                base + t[1] as usize,
                base + t[2] as usize,
            ]
        }));
    }
    Ok((vertices, triangles))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir() -> std::path::PathBuf {
        let d = std::env::temp_dir().join(format!("slender-mesh-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    /// A unit square in z = 0 as two triangles.
    const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";

    #[test]
    fn reads_obj_quads_as_triangles() {
        let path = dir().join("square.obj");
        std::fs::write(&path, OBJ).unwrap();
        let (v, t) = read_mesh(&path).unwrap();
        assert_eq!(v.len(), 4);
        assert_eq!(t.len(), 2);
        assert!(t.iter().flatten().all(|&i| i < 4));
    }

    #[test]
    fn reads_ascii_and_binary_stl() {
        let ascii = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
        let path = dir().join("square.stl");
        std::fs::write(&path, ascii).unwrap();
        let (v, t) = read_mesh(&path).unwrap();
        assert_eq!((v.len(), t.len()), (4, 2), "shared vertices are merged");
        // The same triangles written in binary.
        let tris: Vec<stl_io::Triangle> = t
            .iter()
            .map(|tri| stl_io::Triangle {
                normal: stl_io::Normal::new([0.0, 0.0, 1.0]),
                vertices: tri.map(|i| stl_io::Vertex::new(v[i].map(|c| c as f32))),
            })
            .collect();
        let bin = dir().join("square_bin.STL");
        let mut f = std::fs::File::create(&bin).unwrap();
        stl_io::write_stl(&mut f, tris.iter()).unwrap();
        drop(f);
        let (vb, tb) = read_mesh(&bin).unwrap();
        assert_eq!((vb.len(), tb.len()), (4, 2));
    }

    #[test]
    fn unknown_formats_and_missing_files_say_which_file() {
        let e = read_mesh(Path::new("bracket.ply")).unwrap_err().to_string();
        assert!(e.contains("bracket.ply") && e.contains(".stl"), "{e}");
        let e = format!(
            "{:#}",
            read_mesh(Path::new("/nonexistent/x.obj")).unwrap_err()
        );
        assert!(e.contains("/nonexistent/x.obj"), "{e}");
    }
}
