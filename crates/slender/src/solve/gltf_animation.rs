//! The frames of a time-stepped scene as one animated glTF 2.0 file (`frames.gltf`, buffer
//! embedded as a base64 data URI): per rod the tube mesh and the centerline of frame 0, each
//! with one morph target per later frame (its vertices' displacement from frame 0, and the
//! tube's normals'), and an animation whose keyframes, at the frames' times in seconds, set
//! the weight of frame k's target to 1 and all others to 0, linearly interpolated — so a
//! viewer shows every frame exactly at its time and blends the vertices linearly between
//! frames. The scene's "up" is turned onto glTF's +y by a root node, as in the static
//! `shape.gltf` ([`super::gltf`]).

use serde_json::{json, Value};
use slender_core::geometry::Vec3;
use slender_core::scene::{CompiledRod, SceneStep};

use super::gltf::{f32x3, tube_indices, tube_vertices, up_to_y, Builder, LINE_STRIP, TRIANGLES};

/// Displacements (m) of `points` from `base`, as f32 (computed in f64: the displacement
/// carries the frame's position to f32 round-off of its coordinates).
fn displacements(points: &[Vec3], base: &[Vec3]) -> Vec<[f32; 3]> {
    points.iter().zip(base).map(|(p, b)| f32x3(p - b)).collect()
}

fn centerline(frame: &SceneStep, rod: usize) -> Vec<Vec3> {
    frame.rods[rod]
        .positions
        .iter()
        .map(|p| Vec3::from(*p))
        .collect()
}

/// The animated glTF JSON of `frames` (every frame of a time run, frame 0 first, each with its
/// `time`); `up` is the scene direction shown upward. One frame gives a still mesh.
pub fn frames_to_gltf(rods: &[CompiledRod], frames: &[SceneStep], up: Vec3) -> Value {
    let mut b = Builder::new();
    let mut meshes = Vec::new();
    let mut nodes = Vec::new();
    let targets = frames.len().saturating_sub(1);
    let target_names: Vec<String> = frames
        .iter()
        .skip(1)
        .map(|f| format!("t = {} s", f.time.as_ref().map_or(0.0, |t| t.t)))
        .collect();
    for (ri, rod) in rods.iter().enumerate() {
        let Some(first) = frames.first() else { break };
        let name = &first.rods[ri].name;
        let (tube0, normals0) = tube_vertices(rod, &first.rods[ri]);
        let line0 = centerline(first, ri);
        let mut tube_targets = Vec::with_capacity(targets);
        let mut line_targets = Vec::with_capacity(targets);
        for f in frames.iter().skip(1) {
            let (tube, normals) = tube_vertices(rod, &f.rods[ri]);
            let p = b.vec3(&displacements(&tube, &tube0));
            let n = b.vec3(&displacements(&normals, &normals0));
            tube_targets.push(json!({"POSITION": p, "NORMAL": n}));
            let l = b.vec3(&displacements(&centerline(f, ri), &line0));
            line_targets.push(json!({"POSITION": l}));
        }
        let tube_pos = b.vec3(&tube0.iter().map(|p| f32x3(*p)).collect::<Vec<_>>());
        let tube_nrm = b.vec3(&normals0.iter().map(|p| f32x3(*p)).collect::<Vec<_>>());
        let tube_idx = b.indices(&tube_indices(line0.len()));
        let line = b.vec3(&line0.iter().map(|p| f32x3(*p)).collect::<Vec<_>>());
        let weights = vec![0.0; targets];
        meshes.push(json!({
            "name": format!("{name} tube"),
            "primitives": [{
                "attributes": {"POSITION": tube_pos, "NORMAL": tube_nrm},
                "indices": tube_idx, "mode": TRIANGLES, "targets": tube_targets
            }],
            "weights": weights,
            "extras": {"targetNames": target_names}
        }));
        nodes.push(json!({"name": name, "mesh": meshes.len() - 1}));
        meshes.push(json!({
            "name": format!("{name} centerline"),
            "primitives": [{
                "attributes": {"POSITION": line}, "mode": LINE_STRIP, "targets": line_targets
            }],
            "weights": weights,
            "extras": {"targetNames": target_names}
        }));
        nodes.push(json!({"name": format!("{name}-centerline"), "mesh": meshes.len() - 1}));
    }
    let mut gltf = json!({
        "asset": {"version": "2.0", "generator": "slender solve (time stepping)"},
        "scene": 0,
        "scenes": [{"nodes": [nodes.len()]}],
        "meshes": meshes,
    });
    if targets > 0 {
        // Keyframe k (k ≥ 1) is target k − 1 at weight 1; keyframe 0 is the base mesh.
        let times: Vec<f32> = frames
            .iter()
            .map(|f| f.time.as_ref().map_or(0.0, |t| t.t) as f32)
            .collect();
        let mut w = vec![0.0f32; frames.len() * targets];
        for k in 1..frames.len() {
            w[k * targets + k - 1] = 1.0;
        }
        let input = b.scalars(&times, true);
        let output = b.scalars(&w, false);
        let samplers: Vec<Value> = (0..nodes.len())
            .map(|_| json!({"input": input, "output": output, "interpolation": "LINEAR"}))
            .collect();
        let channels: Vec<Value> = (0..nodes.len())
            .map(|n| json!({"sampler": n, "target": {"node": n, "path": "weights"}}))
            .collect();
        gltf["animations"] = json!([{
            "name": "motion", "samplers": samplers, "channels": channels
        }]);
    }
    let root = json!({
        "name": "slender scene (up = against gravity)",
        "rotation": up_to_y(up),
        "children": (0..nodes.len()).collect::<Vec<_>>()
    });
    nodes.push(root);
    gltf["nodes"] = json!(nodes);
    gltf["buffers"] = json!([{"byteLength": b.bin.len(), "uri": b.uri()}]);
    gltf["bufferViews"] = json!(b.views);
    gltf["accessors"] = json!(b.accessors);
    gltf
}
