//! Building a shell strip from validated parameters.

use nalgebra::Vector3;

use crate::error::{require_finite, require_positive, ModelError};
use crate::geometry::Vec3;
use crate::rod::Grading;

use super::bending::{edge_curvature, second_fundamental_form, EdgeDirector};
use super::clamp::Clamp;
use super::dofs::ShellDofs;
use super::gravity::lumped_vertex_masses;
use super::membrane::FaceRest;
use super::mesh::StripMesh;
use crate::assembly::FIXED;

use super::model::FaceTerm;
use super::model::{Shell, ShellProperties};

/// Builds a [`Shell`]: a flat rectangular strip (length along x, width along z, rest normal
/// +y) clamped along its edge x = 0.
#[derive(Clone, Debug)]
pub struct ShellBuilder {
    properties: ShellProperties,
    n_length: usize,
    n_width: usize,
    grading: Grading,
    gravity: Vec3,
}

impl ShellBuilder {
    /// A strip of the given material and geometry (SI units), 8 × 2 elements, graded
    /// s = L(i/n)² toward the clamp, no gravity.
    pub fn new(properties: ShellProperties) -> Self {
        Self {
            properties,
            n_length: 8,
            n_width: 2,
            grading: Grading::default(),
            gravity: Vec3::zeros(),
        }
    }

    /// Elements along the length (≥ 1) and across the width (≥ 1).
    pub fn elements(mut self, n_length: usize, n_width: usize) -> Self {
        self.n_length = n_length;
        self.n_width = n_width;
        self
    }

    /// Distribution of the stations along the length.
    pub fn grading(mut self, grading: Grading) -> Self {
        self.grading = grading;
        self
    }

    /// Gravity (m/s²) at load factor 1.
    pub fn gravity(mut self, g: Vec3) -> Self {
        self.gravity = g;
        self
    }

    /// Validates the input and builds the shell. Errors name the field and its valid range.
    pub fn build(&self) -> Result<Shell, ModelError> {
        let p = self.properties;
        require_positive("length", p.length)?;
        require_positive("width", p.width)?;
        require_positive("thickness", p.thickness)?;
        require_positive("young", p.young)?;
        require_positive("density", p.density)?;
        if !(p.poisson > -1.0 && p.poisson < 0.5) {
            return Err(ModelError::parameter("poisson", p.poisson, "in (-1, 0.5)"));
        }
        for (c, g) in ["gravity.x", "gravity.y", "gravity.z"]
            .iter()
            .zip(self.gravity.iter())
        {
            require_finite(c, *g)?;
        }
        if self.n_length < 1 {
            return Err(ModelError::structure(
                "n_length",
                format!("got {}; need at least 1 element", self.n_length),
            ));
        }
        if self.n_width < 1 {
            return Err(ModelError::structure(
                "n_width",
                format!("got {}; need at least 1 element", self.n_width),
            ));
        }
        let stations = self.grading.node_arclengths(self.n_length, p.length)?;
        let mesh = StripMesh::new(&stations, p.width, self.n_width);
        let rest: Vec<FaceRest> = mesh
            .faces
            .iter()
            .map(|t| {
                FaceRest::new([
                    &mesh.rest_positions[t[0]],
                    &mesh.rest_positions[t[1]],
                    &mesh.rest_positions[t[2]],
                ])
            })
            .collect();
        let clamp = Clamp::default();
        // Rest second fundamental form (zero for the flat strip, computed for generality).
        let bbar = mesh
            .faces
            .iter()
            .enumerate()
            .map(|(f, t)| {
                let q = [
                    &mesh.rest_positions[t[0]],
                    &mesh.rest_positions[t[1]],
                    &mesh.rest_positions[t[2]],
                ];
                let ii = Vector3::from_fn(|i, _| {
                    let fe = mesh.face_edges[f][i];
                    let d = if mesh.clamp_edges.contains(&fe.edge) {
                        EdgeDirector::Clamped {
                            normal: clamp.normal(),
                        }
                    } else if let Some(pv) = fe.opposite_vertex {
                        EdgeDirector::Interior {
                            p: mesh.rest_positions[pv],
                            phi: 0.0,
                            sigma: fe.orientation,
                        }
                    } else {
                        EdgeDirector::Free {
                            phi: 0.0,
                            sigma: fe.orientation,
                        }
                    };
                    edge_curvature(q, i, &d).v
                });
                second_fundamental_form(&ii)
            })
            .collect();
        let nv = mesh.rest_positions.len();
        let ne = mesh.edges.len();
        let mut fixed = vec![false; 3 * nv + ne];
        let mut key = vec![0usize; 3 * nv + ne];
        for v in 0..nv {
            for c in 0..3 {
                fixed[3 * v + c] = mesh.clamp_vertices.contains(&v);
                key[3 * v + c] = 2 * mesh.station(v);
            }
        }
        for (e, ends) in mesh.edges.iter().enumerate() {
            fixed[3 * nv + e] = mesh.clamp_edges.contains(&e);
            key[3 * nv + e] = mesh.station(ends[0]) + mesh.station(ends[1]);
        }
        let dofs = ShellDofs::new(nv, &fixed, &key);
        let areal_density = p.density * p.thickness;
        let vertex_masses = lumped_vertex_masses(nv, &mesh.faces, &rest, areal_density);
        let mut edge_inertia = vec![0.0; ne];
        // Rotational inertia of an edge director: the mass next to it times its length².
        for (fes, r) in mesh.face_edges.iter().zip(&rest) {
            for fe in fes {
                let [a, b] = mesh.edges[fe.edge];
                let len2 = (mesh.rest_positions[b] - mesh.rest_positions[a]).norm_squared();
                edge_inertia[fe.edge] += areal_density * r.area / 3.0 * len2;
            }
        }
        let mut shell = Shell {
            mesh,
            properties: p,
            rest,
            faces: Vec::new(),
            bbar,
            dofs,
            half_bandwidth: 0,
            vertex_masses,
            edge_inertia,
            gravity: self.gravity,
            load_path: Default::default(),
            grading: self.grading,
        };
        shell.faces = (0..shell.mesh.faces.len())
            .map(|f| FaceTerm {
                face: f,
                dofs: shell.face_stencil(f).map(|i| i.unwrap_or(FIXED)),
            })
            .collect();
        let mut bw = 0;
        for f in 0..shell.mesh.faces.len() {
            let idx: Vec<usize> = shell.face_stencil(f).iter().flatten().copied().collect();
            if let (Some(lo), Some(hi)) = (idx.iter().min(), idx.iter().max()) {
                bw = bw.max(hi - lo);
            }
        }
        shell.half_bandwidth = bw;
        Ok(shell)
    }
}
