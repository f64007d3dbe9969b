//! Building a shell strip from validated parameters.

use nalgebra::Vector3;

use crate::error::{require_finite, require_positive, ModelError};
use crate::geometry::Vec3;
use crate::linalg::SparseSymmetricMatrix;
use crate::rod::Grading;

use super::bending::{edge_curvature_value, second_fundamental_form, EdgeDirector, FACE_VARS};
use super::clamp::Clamp;
use super::dofs::ShellDofs;
use super::gravity::lumped_vertex_masses;
use super::membrane::FaceRest;
use super::mesh::StripMesh;
use crate::assembly::FIXED;
use crate::bspline_shell::StripEnd;

use super::model::FaceTerm;
use super::model::{Shell, ShellProperties};

/// Builds a [`Shell`]: a flat rectangular strip (length along x, width along z, rest normal
/// +y) clamped along its edge x = 0 (by default), its edge x = L, or both.
#[derive(Clone, Debug)]
pub struct ShellBuilder {
    properties: ShellProperties,
    n_length: usize,
    n_width: usize,
    grading: Grading,
    gravity: Vec3,
    clamped: [bool; 2],
    /// (station, column, force at load factor 1 in N).
    point_forces: Vec<(usize, usize, Vec3)>,
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
            clamped: [true, false],
            point_forces: Vec::new(),
        }
    }

    /// Clamps `end` (at its rest pose: a state's clamp poses move it, see
    /// [`Shell::set_clamp_at`]).
    pub fn clamp(mut self, end: StripEnd) -> Self {
        self.clamped[end.index()] = true;
        self
    }

    /// Leaves `end` free.
    pub fn free(mut self, end: StripEnd) -> Self {
        self.clamped[end.index()] = false;
        self
    }

    /// Adds a dead force (N at load factor 1, scaled with gravity) at vertex (`station`,
    /// `column`) of the structured mesh (station 0 … n_L along x, column 0 … n_W along z).
    pub fn point_force(mut self, station: usize, column: usize, force: Vec3) -> Self {
        // Checked in `build`, where the mesh is known.
        self.point_forces.push((station, column, force));
        self
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
        if !self.clamped[0] && !self.clamped[1] {
            return Err(ModelError::structure(
                "clamps",
                "neither end is clamped; a free strip has rigid-body modes and no equilibrium",
            ));
        }
        if self.clamped[0] && self.clamped[1] && self.n_length < 2 {
            return Err(ModelError::structure(
                "n_length",
                format!(
                    "got {}; with both ends clamped the strip needs at least 2 elements along its length",
                    self.n_length
                ),
            ));
        }
        let mut point_forces = Vec::with_capacity(self.point_forces.len());
        for &(i, j, f) in &self.point_forces {
            if i > self.n_length || j > self.n_width {
                return Err(ModelError::structure(
                    "point_force",
                    format!(
                        "vertex (station {i}, column {j}) is off the strip; valid: station 0..={}, column 0..={}",
                        self.n_length, self.n_width
                    ),
                ));
            }
            for (c, x) in ["point_force.x", "point_force.y", "point_force.z"]
                .iter()
                .zip(f.iter())
            {
                require_finite(c, *x)?;
            }
            point_forces.push((i * (self.n_width + 1) + j, f));
        }
        let stations = self.grading.node_arclengths(self.n_length, p.length)?;
        let mut mesh = StripMesh::new(&stations, p.width, self.n_width);
        mesh.clamp_vertices = StripEnd::BOTH
            .iter()
            .filter(|e| self.clamped[e.index()])
            .flat_map(|e| mesh.end_vertices[e.index()].clone())
            .collect();
        mesh.clamp_edges = StripEnd::BOTH
            .iter()
            .filter(|e| self.clamped[e.index()])
            .flat_map(|e| mesh.end_edges[e.index()].clone())
            .collect();
        let mut edge_clamp = vec![None; mesh.edges.len()];
        for end in StripEnd::BOTH {
            if self.clamped[end.index()] {
                for &e in &mesh.end_edges[end.index()] {
                    edge_clamp[e] = Some(end.index());
                }
            }
        }
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
                    let d = if edge_clamp[fe.edge].is_some() {
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
                    edge_curvature_value(q, i, &d)
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
            clamped: self.clamped,
            edge_clamp,
            point_forces,
            // Set below, once the face terms exist.
            scatter: SparseSymmetricMatrix::from_pattern(0, Vec::new())
                .scatter_plan(std::iter::empty::<&[usize; FACE_VARS]>()),
            guess: Default::default(),
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
        shell.scatter = Shell::hessian_plan(&shell.faces, shell.dofs.n_free());
        Ok(shell)
    }
}
