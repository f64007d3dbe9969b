//! The VTK and glTF shape files read back by independent parsers written here: structure,
//! vertex counts and positions match the result JSON; plus the preview and the JSON Schema.

use std::path::PathBuf;
use std::process::Command;

use base64::Engine;
use serde_json::Value;

/// Two rods in one scene: a clamped cantilever and a cable between a clamp and a pin.
const SCENE: &str = r#"
gravity = [0.0, 0.0, -9.81]

[[rods]]
name = "arm"
elements = 12
centerline = { kind = "straight", start = [0.0, 0.0, 0.0], direction = [1.0, 0.0, 0.0], length = 0.5 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [{ kind = "clamp", vertex = "start" }]

[[rods]]
name = "loop"
elements = 30
centerline = { kind = "arc", start = [0.0, 1.0, 0.0], tangent = [1.0, 0.0, 0.0], normal = [0.0, 1.0, 0.0], radius = 0.2, length = 1.0 }
section = { shape = "rectangle", width = 0.01, height = 0.002 }
material = { young = 2.0e9, shear_modulus = 7.0e8, density = 1400.0 }
supports = [{ kind = "clamp", vertex = "start" }, { kind = "pin", vertex = "end" }]
"#;

fn solve_scene(name: &str) -> (PathBuf, Value) {
    solve_text(name, SCENE)
}

fn solve_text(name: &str, text: &str) -> (PathBuf, Value) {
    let d = std::env::temp_dir().join(format!("slender-shapes-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("scene.toml"), text).unwrap();
    let out = d.join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .arg("solve")
        .arg(d.join("scene.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let result: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("step_000/result.json")).unwrap())
            .unwrap();
    (out, result)
}

fn rod_positions(result: &Value, k: usize) -> Vec<[f64; 3]> {
    result["rods"][k]["positions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let a = p.as_array().unwrap();
            [0, 1, 2].map(|i| a[i].as_f64().unwrap())
        })
        .collect()
}

/// A minimal legacy-VTK PolyData reader: points, polylines and named point scalars.
struct Vtk {
    points: Vec<[f64; 3]>,
    lines: Vec<Vec<usize>>,
    scalars: Vec<(String, Vec<f64>)>,
}

fn read_vtk(text: &str) -> Vtk {
    let mut lines_iter = text.lines();
    assert!(lines_iter
        .next()
        .unwrap()
        .starts_with("# vtk DataFile Version"));
    let _title = lines_iter.next().unwrap();
    assert_eq!(lines_iter.next().unwrap(), "ASCII");
    assert_eq!(lines_iter.next().unwrap(), "DATASET POLYDATA");
    let mut t = lines_iter.flat_map(|l| l.split_whitespace()).peekable();
    let mut next = move || t.next();
    let mut word = || next().expect("truncated VTK file");
    assert_eq!(word(), "POINTS");
    let n: usize = word().parse().unwrap();
    assert_eq!(word(), "double");
    let points: Vec<[f64; 3]> = (0..n)
        .map(|_| [0; 3].map(|_| word().parse::<f64>().unwrap()))
        .collect();
    assert_eq!(word(), "LINES");
    let n_lines: usize = word().parse().unwrap();
    let size: usize = word().parse().unwrap();
    let mut lines = Vec::new();
    let mut count = 0;
    for _ in 0..n_lines {
        let m: usize = word().parse().unwrap();
        lines.push(
            (0..m)
                .map(|_| word().parse().unwrap())
                .collect::<Vec<usize>>(),
        );
        count += m + 1;
    }
    assert_eq!(count, size, "LINES size field");
    assert_eq!(word(), "POINT_DATA");
    assert_eq!(word().parse::<usize>().unwrap(), n);
    let mut scalars = Vec::new();
    // Each block: SCALARS name double 1 / LOOKUP_TABLE default / n values; 4 blocks written.
    for _ in 0..4 {
        assert_eq!(word(), "SCALARS");
        let name = word().to_string();
        assert_eq!(word(), "double");
        assert_eq!(word(), "1");
        assert_eq!(word(), "LOOKUP_TABLE");
        assert_eq!(word(), "default");
        scalars.push((name, (0..n).map(|_| word().parse().unwrap()).collect()));
    }
    Vtk {
        points,
        lines,
        scalars,
    }
}

#[test]
fn vtk_reads_back_with_exact_positions_and_radii() {
    let (out, result) = solve_scene("vtk");
    let vtk = read_vtk(&std::fs::read_to_string(out.join("step_000/shape.vtk")).unwrap());
    let arm = rod_positions(&result, 0);
    let ring = rod_positions(&result, 1);
    assert_eq!(vtk.points.len(), arm.len() + ring.len());
    assert_eq!(vtk.lines.len(), 2);
    assert_eq!(vtk.lines[0], (0..13).collect::<Vec<_>>());
    assert_eq!(vtk.lines[1], (13..44).collect::<Vec<_>>());
    // Shortest round-trip formatting: the positions are those of the result, to the last
    // bit up to serde_json's reader (not correctly rounded by default: allow 1 ulp).
    for (p, q) in vtk.points.iter().zip(arm.iter().chain(ring.iter())) {
        for c in 0..3 {
            assert!(
                (p[c] - q[c]).abs() <= f64::EPSILON * q[c].abs(),
                "{p:?} vs {q:?}"
            );
        }
    }
    let radius = &vtk.scalars.iter().find(|s| s.0 == "radius").unwrap().1;
    assert!(radius[..13].iter().all(|&r| r == 0.002));
    let rect = (0.01f64 * 0.002 / std::f64::consts::PI).sqrt();
    assert!(radius[13..].iter().all(|&r| (r - rect).abs() < 1e-15));
    let names: Vec<&str> = vtk.scalars.iter().map(|s| s.0.as_str()).collect();
    assert_eq!(names, ["radius", "curvature", "twist", "rod"]);
}

/// Decodes accessor `k` of a glTF document as f32 triples (or u32 scalars).
fn accessor_f32(doc: &Value, bin: &[u8], k: usize) -> Vec<[f32; 3]> {
    let acc = &doc["accessors"][k];
    assert_eq!(acc["componentType"], 5126);
    assert_eq!(acc["type"], "VEC3");
    let view = &doc["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let off = view["byteOffset"].as_u64().unwrap() as usize;
    let len = view["byteLength"].as_u64().unwrap() as usize;
    let count = acc["count"].as_u64().unwrap() as usize;
    assert_eq!(len, count * 12);
    (0..count)
        .map(|i| {
            [0, 1, 2].map(|c| {
                let b = off + 12 * i + 4 * c;
                f32::from_le_bytes(bin[b..b + 4].try_into().unwrap())
            })
        })
        .collect()
}

#[test]
fn gltf_reads_back_with_matching_accessors() {
    let (out, result) = solve_scene("gltf");
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("step_000/shape.gltf")).unwrap())
            .unwrap();
    assert_eq!(doc["asset"]["version"], "2.0");
    let uri = doc["buffers"][0]["uri"].as_str().unwrap();
    let b64 = uri
        .strip_prefix("data:application/octet-stream;base64,")
        .unwrap();
    let bin = base64::engine::general_purpose::STANDARD
        .decode(b64)
        .unwrap();
    assert_eq!(
        bin.len() as u64,
        doc["buffers"][0]["byteLength"].as_u64().unwrap()
    );
    let meshes = doc["meshes"].as_array().unwrap();
    assert_eq!(meshes.len(), 4, "a tube and a centerline per rod");
    let nodes = doc["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 5, "a node per mesh and a root");
    assert_eq!(doc["scenes"][0]["nodes"], serde_json::json!([4]));
    assert_eq!(nodes[4]["children"], serde_json::json!([0, 1, 2, 3]));
    // The root turns the scene's up (against gravity −z: +z) onto glTF's +y.
    let q: Vec<f64> = nodes[4]["rotation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let (v, w) = ([q[0], q[1], q[2]], q[3]);
    let rotate = |p: [f64; 3]| {
        // p + 2w (v × p) + 2 v × (v × p)
        let c = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let vp = c(v, p);
        let vvp = c(v, vp);
        [0, 1, 2].map(|i| p[i] + 2.0 * w * vp[i] + 2.0 * vvp[i])
    };
    let up = rotate([0.0, 0.0, 1.0]);
    assert!(
        (up[1] - 1.0).abs() < 1e-12 && up[0].abs() < 1e-12 && up[2].abs() < 1e-12,
        "{up:?}"
    );
    for (k, n_vertices) in [(0usize, 13usize), (1, 31)] {
        let positions = rod_positions(&result, k);
        // Centerline: a line strip through the vertices.
        let line = &meshes[2 * k + 1]["primitives"][0];
        assert_eq!(line["mode"], 3);
        let acc = line["attributes"]["POSITION"].as_u64().unwrap() as usize;
        let pts = accessor_f32(&doc, &bin, acc);
        assert_eq!(pts.len(), n_vertices);
        for (p, q) in pts.iter().zip(&positions) {
            for c in 0..3 {
                assert_eq!(p[c], q[c] as f32);
            }
        }
        let a = &doc["accessors"][acc];
        for c in 0..3 {
            let lo = positions
                .iter()
                .map(|p| p[c] as f32)
                .fold(f32::INFINITY, f32::min);
            let hi = positions
                .iter()
                .map(|p| p[c] as f32)
                .fold(f32::NEG_INFINITY, f32::max);
            assert_eq!(a["min"][c].as_f64().unwrap() as f32, lo);
            assert_eq!(a["max"][c].as_f64().unwrap() as f32, hi);
        }
        // Tube: 12 vertices per ring at the section's radius around each vertex.
        let tube = &meshes[2 * k]["primitives"][0];
        assert_eq!(tube["mode"], 4);
        let ring = accessor_f32(
            &doc,
            &bin,
            tube["attributes"]["POSITION"].as_u64().unwrap() as usize,
        );
        assert_eq!(ring.len(), 12 * n_vertices);
        let radius = if k == 0 {
            0.002
        } else {
            (0.01f64 * 0.002 / std::f64::consts::PI).sqrt()
        };
        for (i, p) in ring.iter().enumerate() {
            let c = positions[i / 12];
            let d = ((p[0] as f64 - c[0]).powi(2)
                + (p[1] as f64 - c[1]).powi(2)
                + (p[2] as f64 - c[2]).powi(2))
            .sqrt();
            assert!((d / radius - 1.0).abs() < 1e-4, "ring vertex {i}: {d}");
        }
        let idx = &doc["accessors"][tube["indices"].as_u64().unwrap() as usize];
        assert_eq!(idx["componentType"], 5125);
        assert_eq!(
            idx["count"].as_u64().unwrap() as usize,
            (n_vertices - 1) * 12 * 6
        );
    }
    assert!(out.join("preview.png").exists() && out.join("preview.svg").exists());
}

#[test]
fn the_json_schema_is_generated_from_the_types_and_matches_the_committed_copy() {
    let o = Command::new(env!("CARGO_BIN_EXE_slender"))
        .arg("scene-schema")
        .output()
        .unwrap();
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    let schema: Value = serde_json::from_str(&text).unwrap();
    for key in ["gravity", "solver", "rods", "shells", "motion"] {
        assert!(schema["properties"].get(key).is_some(), "{key}");
    }
    assert_eq!(schema["additionalProperties"], Value::Bool(false));
    let committed = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/scene.schema.json"),
    )
    .expect("examples/scene.schema.json (regenerate: slender scene-schema --out examples/scene.schema.json)");
    assert_eq!(
        committed, text,
        "examples/scene.schema.json is stale; regenerate it"
    );
}

/// A rod and a shell strip in one scene (they do not interact; each is solved on its own).
const SHELL_SCENE: &str = r#"
gravity = [0.0, -9.81, 0.0]

[[rods]]
name = "arm"
elements = 4
centerline = { kind = "straight", start = [0.0, 0.0, 1.0], direction = [1.0, 0.0, 0.0], length = 0.5 }
section = { shape = "circle", diameter = 0.004 }
material = { young = 1.0e9, poisson = 0.4, density = 1400.0 }
supports = [{ kind = "clamp", vertex = "start" }]

[[shells]]
name = "strip"
length = 0.2
width = 0.04
thickness = 0.0003
material = { young = 5.0e9, poisson = 0.3, density = 1200.0 }
elements = 6
width_elements = 3
"#;

/// The shell as triangles in VTK (POLYGONS after the rod's LINES) and in glTF (an indexed
/// triangle mesh), both matching the result's positions and the structured mesh's counts.
#[test]
fn shell_strips_read_back_as_triangle_meshes() {
    let (out, result) = solve_text("shell", SHELL_SCENE);
    assert_eq!(result["converged"], Value::Bool(true));
    let arm = rod_positions(&result, 0);
    let strip: Vec<[f64; 3]> = result["shells"][0]["positions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| [0, 1, 2].map(|i| p[i].as_f64().unwrap()))
        .collect();
    let (nl, nw) = (6, 3);
    let (n_vertices, n_faces) = ((nl + 1) * (nw + 1), 2 * nl * nw);
    assert_eq!(strip.len(), n_vertices);
    // The strip hangs: its free edge is below the clamp, the clamp edge did not move.
    assert!(strip[nl * (nw + 1)][1] < -1e-3);
    assert!(strip[..=nw].iter().all(|p| p[0] == 0.0 && p[1] == 0.0));
    // The clamp force carries the weight ρ h w L g (computed here from the scene's data).
    let weight = 1200.0 * 0.0003 * 0.04 * 0.2 * 9.81;
    let fy = result["shells"][0]["clamp_force"][1].as_f64().unwrap();
    assert!(
        (fy / weight - 1.0).abs() < 1e-6,
        "clamp force {fy} vs weight {weight}"
    );

    // VTK, read token by token.
    let text = std::fs::read_to_string(out.join("step_000/shape.vtk")).unwrap();
    let words: Vec<&str> = text
        .lines()
        .skip(4)
        .flat_map(|l| l.split_whitespace())
        .collect();
    let mut k = 0;
    let mut word = || {
        k += 1;
        words[k - 1]
    };
    assert_eq!(word(), "POINTS");
    let n: usize = word().parse().unwrap();
    assert_eq!(n, arm.len() + n_vertices);
    word();
    let points: Vec<[f64; 3]> = (0..n)
        .map(|_| [0; 3].map(|_| word().parse::<f64>().unwrap()))
        .collect();
    for (p, q) in points[arm.len()..].iter().zip(&strip) {
        for c in 0..3 {
            assert!(
                (p[c] - q[c]).abs() <= f64::EPSILON * q[c].abs(),
                "{p:?} {q:?}"
            );
        }
    }
    assert_eq!(word(), "LINES");
    assert_eq!(word(), "1");
    let size: usize = word().parse().unwrap();
    for _ in 0..size {
        word();
    }
    assert_eq!(word(), "POLYGONS");
    assert_eq!(word().parse::<usize>().unwrap(), n_faces);
    assert_eq!(word().parse::<usize>().unwrap(), 4 * n_faces);
    let mut area = 0.0;
    let mut used = vec![false; n];
    for _ in 0..n_faces {
        assert_eq!(word(), "3");
        let t = [0; 3].map(|_| word().parse::<usize>().unwrap());
        for &v in &t {
            assert!(
                v >= arm.len() && v < n,
                "triangle vertex {v} is not the strip's"
            );
            used[v] = true;
        }
        let [a, b, c] = t.map(|v| points[v]);
        let (u, w) = (
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        let x = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        area += 0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    }
    assert!(
        used[arm.len()..].iter().all(|&u| u),
        "every strip vertex in a triangle"
    );
    // The membrane is stiff: the deformed surface keeps the rest area L·w.
    assert!((area / (0.2 * 0.04) - 1.0).abs() < 1e-4, "area {area}");
    assert_eq!(word(), "POINT_DATA");
    assert_eq!(word().parse::<usize>().unwrap(), n);

    // glTF: the strip's mesh is the last one, indexed triangles over its vertices.
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("step_000/shape.gltf")).unwrap())
            .unwrap();
    let uri = doc["buffers"][0]["uri"].as_str().unwrap();
    let bin = base64::engine::general_purpose::STANDARD
        .decode(
            uri.strip_prefix("data:application/octet-stream;base64,")
                .unwrap(),
        )
        .unwrap();
    let meshes = doc["meshes"].as_array().unwrap();
    assert_eq!(
        meshes.len(),
        3,
        "tube and centerline of the rod, the strip's surface"
    );
    let prim = &meshes[2]["primitives"][0];
    assert_eq!(prim["mode"], 4);
    assert_eq!(
        doc["materials"][prim["material"].as_u64().unwrap() as usize]["doubleSided"],
        true
    );
    let pts = accessor_f32(
        &doc,
        &bin,
        prim["attributes"]["POSITION"].as_u64().unwrap() as usize,
    );
    assert_eq!(pts.len(), n_vertices);
    for (p, q) in pts.iter().zip(&strip) {
        for c in 0..3 {
            assert_eq!(p[c], q[c] as f32);
        }
    }
    let acc = &doc["accessors"][prim["indices"].as_u64().unwrap() as usize];
    assert_eq!(acc["componentType"], 5125);
    assert_eq!(acc["count"].as_u64().unwrap() as usize, 3 * n_faces);
    let view = &doc["bufferViews"][acc["bufferView"].as_u64().unwrap() as usize];
    let off = view["byteOffset"].as_u64().unwrap() as usize;
    let idx: Vec<u32> = (0..3 * n_faces)
        .map(|i| u32::from_le_bytes(bin[off + 4 * i..off + 4 * i + 4].try_into().unwrap()))
        .collect();
    assert!(idx.iter().all(|&i| (i as usize) < n_vertices));
    let faces = result["shells"][0]["faces"].as_array().unwrap();
    assert_eq!(faces.len(), n_faces);
    for (f, t) in faces.iter().zip(idx.chunks(3)) {
        for c in 0..3 {
            assert_eq!(f[c].as_u64().unwrap(), t[c] as u64);
        }
    }
    // The vertex CSV has one row per strip vertex.
    let csv = std::fs::read_to_string(out.join("step_000/strip_vertices.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + n_vertices);
    assert!(out.join("preview.png").exists());
}
