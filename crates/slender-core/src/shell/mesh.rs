//! Structured triangle mesh of a rectangular strip: length along x (graded toward the clamp at
//! x = 0), width along z, rest mid-surface in the xz-plane with normal +y, quads split by
//! alternating diagonals (so that the mesh has no preferred shear direction), and the
//! edge/face adjacency the mid-edge bending term needs.

use std::collections::HashMap;

use crate::geometry::Vec3;

/// Face `f`'s view of one of its edges.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceEdge {
    /// Global edge index.
    pub edge: usize,
    /// +1 if the face runs along the edge from its first to its second vertex, −1 otherwise
    /// (the sign of the edge's director angle as seen from this face).
    pub orientation: f64,
    /// Vertex of the neighbouring face opposite this edge, if the edge is interior.
    pub opposite_vertex: Option<usize>,
}

/// A triangle mesh with adjacency.
#[derive(Clone, Debug, PartialEq)]
pub struct StripMesh {
    /// Rest positions (m).
    pub rest_positions: Vec<Vec3>,
    /// Faces as vertex triples, counter-clockwise about +y.
    pub faces: Vec<[usize; 3]>,
    /// Edges as vertex pairs (smaller index first).
    pub edges: Vec<[usize; 2]>,
    /// For each face and local vertex i, the edge opposite vertex i.
    pub face_edges: Vec<[FaceEdge; 3]>,
    /// Vertices held by the strip's clamps (the clamp lines x = 0 and/or x = L), by end and
    /// increasing z. A new mesh has its start clamped; the builder sets the clamped ends.
    pub clamp_vertices: Vec<usize>,
    /// Edges on the clamp lines.
    pub clamp_edges: Vec<usize>,
    /// Vertices of the end edges x = 0 and x = L at rest (indexed by
    /// [`StripEnd::index`](crate::bspline_shell::StripEnd::index)), by increasing z.
    pub end_vertices: [Vec<usize>; 2],
    /// Mesh edges on the end edges x = 0 and x = L.
    pub end_edges: [Vec<usize>; 2],
    /// Elements along the length.
    pub n_length: usize,
    /// Elements across the width.
    pub n_width: usize,
}

impl StripMesh {
    /// A strip of length `length` and width `width` (m), `stations` = x coordinates of the
    /// vertex columns (increasing, first 0), `n_width` elements across the width.
    pub fn new(stations: &[f64], width: f64, n_width: usize) -> Self {
        let n_length = stations.len() - 1;
        let nw = n_width;
        let vid = |i: usize, j: usize| i * (nw + 1) + j;
        let mut rest_positions = Vec::with_capacity((n_length + 1) * (nw + 1));
        for &x in stations {
            for j in 0..=nw {
                let z = -0.5 * width + width * j as f64 / nw as f64;
                rest_positions.push(Vec3::new(x, 0.0, z));
            }
        }
        let mut faces = Vec::with_capacity(2 * n_length * nw);
        for i in 0..n_length {
            for j in 0..nw {
                let (a, b, c, d) = (vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1));
                // (a, d, c) has normal (d − a) × (c − a) ∝ e_z × e_x = +e_y.
                if (i + j) % 2 == 0 {
                    faces.push([a, d, c]);
                    faces.push([a, c, b]);
                } else {
                    faces.push([a, d, b]);
                    faces.push([b, d, c]);
                }
            }
        }
        let mut edge_index: HashMap<[usize; 2], usize> = HashMap::new();
        let mut edges = Vec::new();
        let mut edge_faces: Vec<Vec<(usize, usize)>> = Vec::new();
        let mut face_edges = Vec::with_capacity(faces.len());
        for (f, tri) in faces.iter().enumerate() {
            let mut fe = [FaceEdge {
                edge: 0,
                orientation: 1.0,
                opposite_vertex: None,
            }; 3];
            for (k, slot) in fe.iter_mut().enumerate() {
                let (u, v) = (tri[(k + 1) % 3], tri[(k + 2) % 3]);
                let key = [u.min(v), u.max(v)];
                let e = *edge_index.entry(key).or_insert_with(|| {
                    edges.push(key);
                    edge_faces.push(Vec::new());
                    edges.len() - 1
                });
                edge_faces[e].push((f, k));
                *slot = FaceEdge {
                    edge: e,
                    orientation: if u < v { 1.0 } else { -1.0 },
                    opposite_vertex: None,
                };
            }
            face_edges.push(fe);
        }
        for adj in &edge_faces {
            if let [(f, k), (g, l)] = adj[..] {
                face_edges[f][k].opposite_vertex = Some(faces[g][l]);
                face_edges[g][l].opposite_vertex = Some(faces[f][k]);
            }
        }
        let start_vertices: Vec<usize> = (0..=nw).map(|j| vid(0, j)).collect();
        let end_vertices: Vec<usize> = (0..=nw).map(|j| vid(n_length, j)).collect();
        let start_edges: Vec<usize> = edges
            .iter()
            .enumerate()
            .filter(|(_, e)| e[1] <= nw)
            .map(|(i, _)| i)
            .collect();
        let end_edges: Vec<usize> = edges
            .iter()
            .enumerate()
            .filter(|(_, e)| e[0] >= vid(n_length, 0))
            .map(|(i, _)| i)
            .collect();
        Self {
            rest_positions,
            faces,
            edges,
            face_edges,
            clamp_vertices: start_vertices.clone(),
            clamp_edges: start_edges.clone(),
            end_vertices: [start_vertices, end_vertices],
            end_edges: [start_edges, end_edges],
            n_length,
            n_width: nw,
        }
    }

    /// Index of the vertex at station `i` (along x) and row `j` (along z).
    pub fn vertex(&self, i: usize, j: usize) -> usize {
        i * (self.n_width + 1) + j
    }

    /// Station (column along x) of vertex `v`.
    pub fn station(&self, v: usize) -> usize {
        v / (self.n_width + 1)
    }

    /// Largest ratio of the longer to the shorter side of a quad of the structured grid.
    pub fn max_aspect_ratio(&self, width: f64) -> f64 {
        let dz = width / self.n_width as f64;
        (0..self.n_length)
            .map(|i| {
                let dx = self.rest_positions[self.vertex(i + 1, 0)].x
                    - self.rest_positions[self.vertex(i, 0)].x;
                (dx / dz).max(dz / dx)
            })
            .fold(1.0, f64::max)
    }
}
