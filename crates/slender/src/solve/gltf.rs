//! Rod shapes as glTF 2.0 (a `.gltf` JSON file with its binary buffer embedded as a base64
//! data URI) for Blender and the web: per rod a tube mesh (triangles, ring frames from the
//! material frames) and its centerline as a line strip; per shell strip its triangle mesh
//! (double-sided material, no normals: viewers compute flat ones). Vertex data are in the scene's
//! coordinates; a root node rotates the scene's "up" (against gravity, +z without gravity)
//! onto glTF's +y, so that viewers show cables hanging down.

use base64::Engine;
use serde_json::{json, Value};
use slender_core::geometry::Vec3;
use slender_core::scene::{CompiledRod, RodResult, ShellResult};

/// Sides of the tube around each rod.
pub(super) const TUBE_SIDES: usize = 12;

pub(super) const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
pub(super) const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
pub(super) const TRIANGLES: u32 = 4;
pub(super) const LINE_STRIP: u32 = 3;

/// Collects the binary buffer, its views and accessors.
pub(super) struct Builder {
    pub(super) bin: Vec<u8>,
    pub(super) views: Vec<Value>,
    pub(super) accessors: Vec<Value>,
}

impl Builder {
    pub(super) fn new() -> Self {
        Self {
            bin: Vec::new(),
            views: Vec::new(),
            accessors: Vec::new(),
        }
    }

    /// The buffer as a base64 data URI.
    pub(super) fn uri(&self) -> String {
        format!(
            "data:application/octet-stream;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&self.bin)
        )
    }

    /// A buffer view of `bytes`; `target` None for data that is not vertex or index data
    /// (animation keyframes).
    fn push_view_for(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.views.push(view);
        self.views.len() - 1
    }

    /// A SCALAR float accessor (animation times with their min/max, or keyframe values).
    pub(super) fn scalars(&mut self, v: &[f32], bounds: bool) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|c| c.to_le_bytes()).collect();
        let view = self.push_view_for(&bytes, None);
        let mut a = json!({
            "bufferView": view, "componentType": FLOAT, "count": v.len(), "type": "SCALAR"
        });
        if bounds {
            let min = v.iter().copied().fold(f32::INFINITY, f32::min);
            let max = v.iter().copied().fold(f32::NEG_INFINITY, f32::max);
            a["min"] = json!([min]);
            a["max"] = json!([max]);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn push_view(&mut self, bytes: &[u8], target: u32) -> usize {
        self.push_view_for(bytes, Some(target))
    }

    /// A VEC3 float accessor with min/max (required for POSITION).
    pub(super) fn vec3(&mut self, v: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = v.iter().flatten().flat_map(|c| c.to_le_bytes()).collect();
        let view = self.push_view(&bytes, ARRAY_BUFFER);
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in v {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        self.accessors.push(json!({
            "bufferView": view, "componentType": FLOAT, "count": v.len(), "type": "VEC3",
            "min": min, "max": max
        }));
        self.accessors.len() - 1
    }

    pub(super) fn indices(&mut self, idx: &[u32]) -> usize {
        let bytes: Vec<u8> = idx.iter().flat_map(|c| c.to_le_bytes()).collect();
        let view = self.push_view(&bytes, ELEMENT_ARRAY_BUFFER);
        self.accessors.push(json!({
            "bufferView": view, "componentType": UNSIGNED_INT, "count": idx.len(), "type": "SCALAR"
        }));
        self.accessors.len() - 1
    }
}

pub(super) fn f32x3(v: Vec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// Unit normal frame (n1, n2) of the tube ring at vertex `i`, from the adjacent edges'
/// material frames.
fn ring_frame(r: &RodResult, i: usize) -> (Vec3, Vec3) {
    let n_edges = r.frames.len();
    let edges: Vec<usize> = [i.checked_sub(1), (i < n_edges).then_some(i)]
        .into_iter()
        .flatten()
        .collect();
    let mut t = Vec3::zeros();
    let mut m1 = Vec3::zeros();
    for &j in &edges {
        m1 += Vec3::from(r.frames[j][0]);
        t += Vec3::from(r.frames[j][2]);
    }
    // Two edges folded back onto each other have no mean tangent: use the first one's.
    let t = if t.norm() > 1e-9 {
        t.normalize()
    } else {
        Vec3::from(r.frames[edges[0]][2])
    };
    let mut n1 = m1 - t * t.dot(&m1);
    if n1.norm() < 1e-9 {
        n1 = Vec3::from(r.frames[edges[0]][1]);
    }
    let n1 = n1.normalize();
    (n1, t.cross(&n1))
}

/// The tube around rod result `r` (of `rod`): its vertices and unit normals (m), ring after
/// ring ([`TUBE_SIDES`] per centerline vertex).
pub(super) fn tube_vertices(rod: &CompiledRod, r: &RodResult) -> (Vec<Vec3>, Vec<Vec3>) {
    let nv = r.positions.len();
    let mut pos = Vec::with_capacity(nv * TUBE_SIDES);
    let mut nrm = Vec::with_capacity(nv * TUBE_SIDES);
    for i in 0..nv {
        let (n1, n2) = ring_frame(r, i);
        let c = Vec3::from(r.positions[i]);
        for k in 0..TUBE_SIDES {
            let a = 2.0 * std::f64::consts::PI * k as f64 / TUBE_SIDES as f64;
            let n = n1 * a.cos() + n2 * a.sin();
            pos.push(c + n * rod.display_radius);
            nrm.push(n);
        }
    }
    (pos, nrm)
}

/// The triangles of a tube of `nv` rings.
pub(super) fn tube_indices(nv: usize) -> Vec<u32> {
    let mut idx = Vec::with_capacity(nv.saturating_sub(1) * TUBE_SIDES * 6);
    for i in 0..nv.saturating_sub(1) {
        for k in 0..TUBE_SIDES {
            let a = (i * TUBE_SIDES + k) as u32;
            let b2 = (i * TUBE_SIDES + (k + 1) % TUBE_SIDES) as u32;
            let c = a + TUBE_SIDES as u32;
            let d = b2 + TUBE_SIDES as u32;
            idx.extend_from_slice(&[a, b2, d, a, d, c]);
        }
    }
    idx
}

/// Unit quaternion [x, y, z, w] of the rotation that takes `up` (unit) onto +y.
pub(super) fn up_to_y(up: Vec3) -> [f64; 4] {
    let y = Vec3::y();
    let c = up.dot(&y);
    if c < -1.0 + 1e-12 {
        return [1.0, 0.0, 0.0, 0.0]; // half turn about x
    }
    let axis = up.cross(&y);
    // q = (axis, 1 + c) normalized: the half-angle formula.
    let q = [axis.x, axis.y, axis.z, 1.0 + c];
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    q.map(|v| v / n)
}

/// The scene's up direction: against gravity, +z without it.
pub fn scene_up(gravity: [f64; 3]) -> Vec3 {
    let g = Vec3::from(gravity);
    if g.norm() > 0.0 {
        -g.normalize()
    } else {
        Vec3::z()
    }
}

/// The glTF JSON of one step; `up` is the scene direction shown upward.
pub fn rods_to_gltf(
    rods: &[CompiledRod],
    results: &[RodResult],
    shells: &[ShellResult],
    up: Vec3,
) -> Value {
    let mut b = Builder::new();
    let mut meshes = Vec::new();
    let mut nodes = Vec::new();
    for (rod, r) in rods.iter().zip(results) {
        let nv = r.positions.len();
        let centerline: Vec<[f32; 3]> = r.positions.iter().map(|p| f32x3(Vec3::from(*p))).collect();
        let line = b.vec3(&centerline);
        let (ring_pos, ring_nrm) = tube_vertices(rod, r);
        let ring_pos: Vec<[f32; 3]> = ring_pos.into_iter().map(f32x3).collect();
        let ring_nrm: Vec<[f32; 3]> = ring_nrm.into_iter().map(f32x3).collect();
        let idx = tube_indices(nv);
        let tube_pos = b.vec3(&ring_pos);
        let tube_nrm = b.vec3(&ring_nrm);
        let tube_idx = b.indices(&idx);
        meshes.push(json!({
            "name": format!("{} tube", r.name),
            "primitives": [{
                "attributes": {"POSITION": tube_pos, "NORMAL": tube_nrm},
                "indices": tube_idx, "mode": TRIANGLES
            }]
        }));
        nodes.push(json!({"name": r.name.clone(), "mesh": meshes.len() - 1}));
        meshes.push(json!({
            "name": format!("{} centerline", r.name),
            "primitives": [{"attributes": {"POSITION": line}, "mode": LINE_STRIP}]
        }));
        nodes.push(json!({"name": format!("{}-centerline", r.name), "mesh": meshes.len() - 1}));
    }
    for sh in shells {
        let pos: Vec<[f32; 3]> = sh.positions.iter().map(|p| f32x3(Vec3::from(*p))).collect();
        let idx: Vec<u32> = sh.faces.iter().flatten().map(|&v| v as u32).collect();
        let p = b.vec3(&pos);
        let i = b.indices(&idx);
        meshes.push(json!({
            "name": format!("{} surface", sh.name),
            "primitives": [{
                "attributes": {"POSITION": p}, "indices": i, "mode": TRIANGLES, "material": 0
            }]
        }));
        nodes.push(json!({"name": sh.name.clone(), "mesh": meshes.len() - 1}));
    }
    let uri = b.uri();
    json!({
        "asset": {"version": "2.0", "generator": "slender solve"},
        "scene": 0,
        "scenes": [{"nodes": [nodes.len()]}],
        "nodes": nodes.iter().cloned().chain(std::iter::once(json!({
            "name": "slender scene (up = against gravity)",
            "rotation": up_to_y(up),
            "children": (0..nodes.len()).collect::<Vec<_>>()
        }))).collect::<Vec<_>>(),
        "meshes": meshes,
        "materials": [{"name": "shell (both sides)", "doubleSided": true}],
        "buffers": [{"byteLength": b.bin.len(), "uri": uri}],
        "bufferViews": b.views,
        "accessors": b.accessors
    })
}
