//! A rigid triangle mesh (a vehicle panel, a housing read from STL or OBJ by the binary): its
//! surface seen from a point, through a bounding-volume hierarchy of its triangles.
//!
//! The mesh is a surface, not a solid: the distance is unsigned, so a cable stays on the side
//! of the surface it starts on (an open panel works as well as a closed housing).

use nalgebra::{Matrix3, Vector3};

use super::edge_penetration::segment_through_triangle;
use super::obstacle::{Obstacle, SurfacePoint};
use crate::ModelError;

/// Triangles per leaf of the hierarchy.
const LEAF: usize = 4;
/// Conservative-advancement iterations of a step that leaves a face's region.
const ADVANCE_ITERATIONS: usize = 64;

/// Where on a triangle the closest point lies.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Feature {
    /// Inside the face.
    Face,
    /// On the edge from corner `0` to corner `1` (its unit direction).
    Edge(Vector3<f64>),
    /// At a corner.
    Vertex,
}

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection §5.1.5).
fn closest_on_triangle(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> (Vector3<f64>, Feature) {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (*a, Feature::Vertex);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (*b, Feature::Vertex);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + ab * v, Feature::Edge(ab.normalize()));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (*c, Feature::Vertex);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + ac * w, Feature::Edge(ac.normalize()));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + (c - b) * w, Feature::Edge((c - b).normalize()));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (a + ab * v + ac * w, Feature::Face)
}

/// A node of the hierarchy: a box and either two children or a range of triangles.
#[derive(Clone, Debug, PartialEq)]
struct Node {
    lo: Vector3<f64>,
    hi: Vector3<f64>,
    /// Children (internal node) or `order[start..end]` (leaf, `children` = None).
    children: Option<(usize, usize)>,
    start: usize,
    end: usize,
}

/// A rigid triangle mesh.
#[derive(Clone, Debug, PartialEq)]
pub struct TriangleMesh {
    vertices: Vec<Vector3<f64>>,
    triangles: Vec<[usize; 3]>,
    friction: f64,
    nodes: Vec<Node>,
    /// Triangle indices in hierarchy order.
    order: Vec<usize>,
}

impl TriangleMesh {
    /// A mesh of `vertices` (m) and `triangles` (vertex index triples), Coulomb coefficient
    /// `friction` (≥ 0). Errors name the triangle: an index out of range, or a degenerate
    /// triangle (area below 10⁻¹² of its longest edge squared).
    pub fn new(
        vertices: Vec<Vector3<f64>>,
        triangles: Vec<[usize; 3]>,
        friction: f64,
    ) -> Result<Self, ModelError> {
        crate::error::require_non_negative("friction", friction)?;
        if triangles.is_empty() {
            return Err(ModelError::structure(
                "triangles",
                "the mesh has no triangle",
            ));
        }
        if let Some(k) = vertices
            .iter()
            .position(|v| v.iter().any(|c| !c.is_finite()))
        {
            return Err(ModelError::structure(
                format!("vertices[{k}]"),
                "must be finite",
            ));
        }
        for (t, tri) in triangles.iter().enumerate() {
            if tri.iter().any(|&i| i >= vertices.len()) {
                return Err(ModelError::structure(
                    format!("triangles[{t}]"),
                    format!("a vertex index is beyond the {} vertices", vertices.len()),
                ));
            }
            let [a, b, c] = tri.map(|i| vertices[i]);
            let longest = (b - a).norm().max((c - b).norm()).max((a - c).norm());
            let area2 = (b - a).cross(&(c - a)).norm();
            if !(area2 > 1e-12 * longest * longest) {
                return Err(ModelError::structure(
                    format!("triangles[{t}]"),
                    "is degenerate (zero area): remove it or fix its vertices",
                ));
            }
        }
        let mut mesh = Self {
            vertices,
            triangles,
            friction,
            nodes: Vec::new(),
            order: Vec::new(),
        };
        mesh.order = (0..mesh.triangles.len()).collect();
        mesh.build(0, mesh.triangles.len());
        Ok(mesh)
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    fn corners(&self, t: usize) -> [Vector3<f64>; 3] {
        self.triangles[t].map(|i| self.vertices[i])
    }

    /// Builds the node over `order[start..end]`; returns its index.
    fn build(&mut self, start: usize, end: usize) -> usize {
        let mut lo = Vector3::repeat(f64::INFINITY);
        let mut hi = Vector3::repeat(f64::NEG_INFINITY);
        for &t in &self.order[start..end] {
            for c in self.corners(t) {
                lo = lo.inf(&c);
                hi = hi.sup(&c);
            }
        }
        let index = self.nodes.len();
        self.nodes.push(Node {
            lo,
            hi,
            children: None,
            start,
            end,
        });
        if end - start > LEAF {
            // Split at the median centroid along the longest axis.
            let axis = (hi - lo).imax();
            let centroid = |t: usize| self.corners(t).iter().map(|c| c[axis]).sum::<f64>();
            let mut slice = self.order[start..end].to_vec();
            slice.sort_by(|&a, &b| centroid(a).total_cmp(&centroid(b)).then(a.cmp(&b)));
            self.order[start..end].copy_from_slice(&slice);
            let mid = start + (end - start) / 2;
            let left = self.build(start, mid);
            let right = self.build(mid, end);
            self.nodes[index].children = Some((left, right));
        }
        index
    }

    /// The closest triangle feature to `p`: (closest point, feature, squared distance).
    fn closest(&self, p: &Vector3<f64>) -> (Vector3<f64>, Feature, f64) {
        let mut best = (Vector3::zeros(), Feature::Face, f64::INFINITY);
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            let outside = (node.lo - p).sup(&(p - node.hi)).sup(&Vector3::zeros());
            if outside.norm_squared() >= best.2 {
                continue;
            }
            match node.children {
                Some((l, r)) => {
                    stack.push(l);
                    stack.push(r);
                }
                None => {
                    for &t in &self.order[node.start..node.end] {
                        let [a, b, c] = self.corners(t);
                        let (q, f) = closest_on_triangle(p, &a, &b, &c);
                        let d2 = (p - q).norm_squared();
                        if d2 < best.2 {
                            best = (q, f, d2);
                        }
                    }
                }
            }
        }
        best
    }
}

impl Obstacle for TriangleMesh {
    fn surface(&self, p: &Vector3<f64>) -> SurfacePoint {
        let (q, feature, d2) = self.closest(p);
        let distance = d2.sqrt();
        if distance == 0.0 {
            return SurfacePoint {
                distance,
                normal: Vector3::z(),
                normal_derivative: Matrix3::zeros(),
            };
        }
        let n = (p - q) / distance;
        // Flat over a face, a cylinder about an edge, a sphere about a corner.
        let normal_derivative = match feature {
            Feature::Face => Matrix3::zeros(),
            Feature::Edge(t) => {
                (Matrix3::identity() - n * n.transpose() - t * t.transpose()) / distance
            }
            Feature::Vertex => (Matrix3::identity() - n * n.transpose()) / distance,
        };
        SurfacePoint {
            distance,
            normal: n,
            normal_derivative,
        }
    }

    fn signed(&self) -> bool {
        false
    }

    fn time_of_impact(&self, p: &Vector3<f64>, dp: &Vector3<f64>, clearance: f64) -> f64 {
        let length = dp.norm();
        if length == 0.0 {
            return 1.0;
        }
        // Conservative advancement: the distance is 1-Lipschitz, so a move of the current
        // distance minus the clearance never reaches the inflated surface. Over a face the
        // distance is linear along the step, and the move is taken in one go.
        let mut alpha = 0.0;
        let mut room0: Option<f64> = None;
        for _ in 0..ADVANCE_ITERATIONS {
            let x = p + dp * alpha;
            let s = self.surface(&x);
            let room = s.distance - clearance;
            // Stop once the room left is a small fraction of the room at the start (it is
            // positive at the start: the point keeps at least its clearance).
            let start = *room0.get_or_insert(room);
            if room <= 1e-3 * start {
                return alpha;
            }
            let (_, feature, _) = self.closest(&x);
            let approach = -dp.dot(&s.normal);
            let step = if feature == Feature::Face && approach > 0.0 {
                // Distance to the face's plane falls at the rate `approach` (and no faster
                // to any other feature than |dp|).
                (room / approach).min(1.0 - alpha).max(room / length)
            } else if feature == Feature::Face {
                1.0 - alpha
            } else {
                room / length
            };
            let next = (alpha + step).min(1.0);
            // Keep only a move whose end is still clear (the face step assumed its plane).
            if self.surface(&(p + dp * next)).distance - clearance < 0.0 {
                alpha += room / length;
            } else {
                alpha = next;
            }
            if alpha >= 1.0 {
                return 1.0;
            }
        }
        alpha
    }

    fn edge_through_triangle(&self, corners: &[Vector3<f64>; 3]) -> Option<Vector3<f64>> {
        let [a, b, c] = corners;
        let (lo, hi) = (a.inf(b).inf(c), a.sup(b).sup(c));
        // Depth first over the nodes whose boxes overlap the triangle's, left child first: the
        // same answer for the same input.
        let mut stack = vec![0usize];
        while let Some(k) = stack.pop() {
            let node = &self.nodes[k];
            if (0..3).any(|i| node.lo[i] > hi[i] || node.hi[i] < lo[i]) {
                continue;
            }
            match node.children {
                Some((l, r)) => {
                    stack.push(r);
                    stack.push(l);
                }
                None => {
                    for &t in &self.order[node.start..node.end] {
                        let [p, q, r] = self.corners(t);
                        for (s, e) in [(p, q), (q, r), (r, p)] {
                            if let Some(x) = segment_through_triangle(&s, &e, corners) {
                                return Some(x);
                            }
                        }
                    }
                }
            }
        }
        None
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn bounds(&self) -> (Vector3<f64>, Vector3<f64>) {
        (self.nodes[0].lo, self.nodes[0].hi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square in z = 0 as two triangles, and a tetrahedron's surface.
    fn square() -> TriangleMesh {
        TriangleMesh::new(
            vec![
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(1.0, 0.0, 0.0),
                Vector3::new(1.0, 1.0, 0.0),
                Vector3::new(0.0, 1.0, 0.0),
            ],
            vec![[0, 1, 2], [0, 2, 3]],
            0.4,
        )
        .unwrap()
    }

    #[test]
    fn distance_and_derivatives_over_faces_edges_and_corners() {
        let m = square();
        assert!((m.surface(&Vector3::new(0.3, 0.6, 0.25)).distance - 0.25).abs() < 1e-15);
        assert!((m.surface(&Vector3::new(0.3, -0.3, 0.4)).distance - 0.5).abs() < 1e-15);
        assert!(
            (m.surface(&Vector3::new(-0.3, -0.4, 0.0)).distance - 0.5).abs() < 1e-15,
            "corner"
        );
        for p in [
            Vector3::new(0.3, 0.6, 0.25),
            Vector3::new(0.3, -0.3, 0.4),
            Vector3::new(1.2, 0.7, -0.3),
            Vector3::new(-0.3, -0.4, 0.2),
        ] {
            let s = m.surface(&p);
            let h = 1e-6;
            for k in 0..3 {
                let mut e = Vector3::zeros();
                e[k] = h;
                let (sp, sm) = (m.surface(&(p + e)), m.surface(&(p - e)));
                assert!(((sp.distance - sm.distance) / (2.0 * h) - s.normal[k]).abs() < 1e-8);
                let fd_n = (sp.normal - sm.normal) / (2.0 * h);
                for i in 0..3 {
                    assert!(
                        (fd_n[i] - s.normal_derivative[(i, k)]).abs() < 1e-6,
                        "{p:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn hierarchy_finds_the_same_closest_point_as_brute_force() {
        // A wavy sheet of 2 × 20 × 20 triangles.
        let n = 20;
        let mut vertices = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                vertices.push(Vector3::new(x, y, 0.1 * (6.0 * x).sin() * (4.0 * y).cos()));
            }
        }
        let mut triangles = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let v = |a: usize, b: usize| a * (n + 1) + b;
                triangles.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
                triangles.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
            }
        }
        let mesh = TriangleMesh::new(vertices, triangles, 0.0).unwrap();
        let mut seed = 0.123_f64;
        for _ in 0..200 {
            let mut r = || {
                seed = (seed * 997.0 + 0.31).fract();
                seed
            };
            let p = Vector3::new(1.4 * r() - 0.2, 1.4 * r() - 0.2, 0.6 * r() - 0.3);
            let fast = mesh.surface(&p).distance;
            let slow = (0..mesh.triangle_count())
                .map(|t| {
                    let [a, b, c] = mesh.corners(t);
                    (p - closest_on_triangle(&p, &a, &b, &c).0).norm()
                })
                .fold(f64::INFINITY, f64::min);
            assert!((fast - slow).abs() < 1e-14, "{fast} vs {slow}");
        }
    }

    #[test]
    fn degenerate_or_out_of_range_triangles_are_named() {
        let v = vec![Vector3::zeros(), Vector3::x(), Vector3::x() * 2.0];
        let e = TriangleMesh::new(v.clone(), vec![[0, 1, 2]], 0.1).unwrap_err();
        assert!(e.to_string().contains("triangles[0]") && e.to_string().contains("degenerate"));
        let e = TriangleMesh::new(v, vec![[0, 1, 7]], 0.1).unwrap_err();
        assert!(e.to_string().contains("triangles[0]"));
    }

    #[test]
    fn a_panel_corner_poking_through_a_face_is_found_and_one_below_it_is_not() {
        // A thin vertical blade (a mesh triangle in the plane y = 0.2) whose tip pokes 1 cm up
        // through a face in z = 0; none of the face's edges meets the blade.
        let face = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
        ];
        let blade = |tip: f64| {
            TriangleMesh::new(
                vec![
                    Vector3::new(0.19, 0.2, -0.1),
                    Vector3::new(0.21, 0.2, -0.1),
                    Vector3::new(0.2, 0.2, tip),
                ],
                vec![[0, 1, 2]],
                0.0,
            )
            .unwrap()
        };
        let poking = blade(0.01);
        for (p, q) in [(0, 1), (1, 2), (2, 0)] {
            assert_eq!(
                poking.time_of_impact(&face[p], &(face[q] - face[p]), 0.0),
                1.0
            );
        }
        let x = poking
            .edge_through_triangle(&face)
            .expect("the tip crosses");
        assert!(x.z.abs() < 1e-15 && (x.y - 0.2).abs() < 1e-15, "{x:?}");
        // On one of the blade's slanted edges: 1 cm below the tip, 0.91 mm beside its x.
        assert!(
            ((x.x - 0.2).abs() - 0.01 * 0.01 / 0.11).abs() < 1e-15,
            "{x:?}"
        );
        assert_eq!(blade(-0.01).edge_through_triangle(&face), None);
        // A face beside the blade.
        let beside = face.map(|v| v + Vector3::new(0.5, 0.5, 0.0));
        assert_eq!(poking.edge_through_triangle(&beside), None);
    }

    #[test]
    fn steps_stop_short_of_the_surface_and_slide_over_it() {
        let m = square();
        let p = Vector3::new(0.5, 0.5, 0.3);
        let t = m.time_of_impact(&p, &Vector3::new(0.0, 0.0, -0.5), 0.1);
        assert!((t - 0.4).abs() < 1e-12, "{t}");
        assert_eq!(m.time_of_impact(&p, &Vector3::new(0.3, 0.1, 0.0), 0.1), 1.0);
    }
}
