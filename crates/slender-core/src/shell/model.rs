//! The shell model: mesh, material, clamp, gravity, and assembly of energy, gradient and
//! Hessian over the free DOFs.

use std::borrow::Cow;

use nalgebra::{SMatrix, SVector, Vector3};

use crate::geometry::Vec3;
use crate::linalg::{SparseSymmetricMatrix, SymmetricMatrix};
use crate::rod::Grading;
use crate::solver::AssemblyInfo;

use super::bending::{bending_energy, EdgeDirector, FACE_VARS};
use super::clamp::Clamp;
use super::dofs::ShellDofs;
use super::gravity::gravity_energy;
use super::load_path::LoadPath;
use super::membrane::{membrane_energy, FaceRest};
use super::mesh::StripMesh;
use super::state::ShellState;

/// Which energy terms to include (for tests of single terms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShellTerms {
    /// St-Venant–Kirchhoff membrane.
    pub membrane: bool,
    /// Mid-edge bending (including the clamp's director term).
    pub bending: bool,
    /// Self-weight.
    pub gravity: bool,
}

impl ShellTerms {
    /// Every term.
    pub const ALL: Self = Self {
        membrane: true,
        bending: true,
        gravity: true,
    };
    /// Membrane only.
    pub const MEMBRANE: Self = Self {
        membrane: true,
        bending: false,
        gravity: false,
    };
    /// Bending only.
    pub const BENDING: Self = Self {
        membrane: false,
        bending: true,
        gravity: false,
    };
    /// Gravity only.
    pub const GRAVITY: Self = Self {
        membrane: false,
        bending: false,
        gravity: true,
    };
}

/// Material and geometry of a built shell (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellProperties {
    /// Length along x (m).
    pub length: f64,
    /// Width along z (m).
    pub width: f64,
    /// Thickness h (m).
    pub thickness: f64,
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson ratio ν.
    pub poisson: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
}

impl ShellProperties {
    /// Bending stiffness D = E h³ / (12 (1 − ν²)) (N m).
    pub fn bending_stiffness(&self) -> f64 {
        self.young * self.thickness.powi(3) / (12.0 * (1.0 - self.poisson * self.poisson))
    }

    /// 2-D Lamé constants (λ, μ) = (Eν/(1−ν²), E/(2(1+ν))) (Pa) — the plane-stress values, not
    /// the 3-D ones.
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (e * nu / (1.0 - nu * nu), e / (2.0 * (1.0 + nu)))
    }

    /// Gravito-bending parameter Γ_shell = ρ h g L³ / D at gravity `g` (m/s²).
    pub fn gamma(&self, g: f64) -> f64 {
        self.density * self.thickness * g * self.length.powi(3) / self.bending_stiffness()
    }

    /// Gravity (m/s²) that gives Γ_shell = `gamma`.
    pub fn gravity_for_gamma(&self, gamma: f64) -> f64 {
        gamma * self.bending_stiffness() / (self.density * self.thickness * self.length.powi(3))
    }
}

/// A Kirchhoff–Love shell strip clamped at x = 0 (see the module docs of `shell`).
#[derive(Clone, Debug)]
pub struct Shell {
    pub(crate) mesh: StripMesh,
    pub(crate) properties: ShellProperties,
    pub(crate) rest: Vec<FaceRest>,
    pub(crate) bbar: Vec<Vector3<f64>>,
    pub(crate) dofs: ShellDofs,
    pub(crate) half_bandwidth: usize,
    pub(crate) vertex_masses: Vec<f64>,
    pub(crate) edge_inertia: Vec<f64>,
    pub(crate) gravity: Vec3,
    pub(crate) clamp: Clamp,
    pub(crate) load_path: LoadPath,
    pub(crate) grading: Grading,
}

impl Shell {
    /// The mesh.
    pub fn mesh(&self) -> &StripMesh {
        &self.mesh
    }

    /// Material and geometry.
    pub fn properties(&self) -> &ShellProperties {
        &self.properties
    }

    /// Gravity (m/s²) at load factor 1.
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// Sets gravity (m/s²) at load factor 1.
    pub fn set_gravity(&mut self, g: Vec3) {
        self.gravity = g;
    }

    /// Distribution of the stations along the length.
    pub fn grading(&self) -> Grading {
        self.grading
    }

    /// The clamp.
    pub fn clamp(&self) -> Clamp {
        self.clamp
    }

    /// Rotates the clamp about x to `sigma` (rad) and moves the clamped vertices of `state` with it.
    pub fn set_clamp_rotation(&mut self, sigma: f64, state: &mut ShellState) {
        self.clamp = Clamp { sigma };
        self.apply_clamp(state);
    }

    /// What the load factor drives (gravity by default).
    pub fn load_path(&self) -> LoadPath {
        self.load_path
    }

    /// Sets what the load factor drives. With [`LoadPath::ClampRotation`], call
    /// [`set_clamp_rotation`](Self::set_clamp_rotation) with the final angle afterwards, so that
    /// the shell's clamp and the state's clamped vertices agree again.
    pub fn set_load_path(&mut self, path: LoadPath) {
        self.load_path = path;
    }

    /// Puts the clamped vertices of `state` where the clamp holds them.
    pub fn apply_clamp(&self, state: &mut ShellState) {
        for &v in &self.mesh.clamp_vertices {
            state.positions[v] = self.clamp.position(&self.mesh.rest_positions[v]);
        }
    }

    /// The rest (flat, unloaded) state.
    pub fn rest_state(&self) -> ShellState {
        let mut s = ShellState {
            positions: self.mesh.rest_positions.clone(),
            angles: vec![0.0; self.mesh.edges.len()],
        };
        self.apply_clamp(&mut s);
        s
    }

    /// The DOF numbering.
    pub fn dofs(&self) -> &ShellDofs {
        &self.dofs
    }

    /// Lumped vertex masses (kg).
    pub fn vertex_masses(&self) -> &[f64] {
        &self.vertex_masses
    }

    /// Half-bandwidth of the Hessian in the free ordering (the free DOFs are numbered along
    /// the length, so a banded matrix can hold the Hessian too).
    pub fn half_bandwidth(&self) -> usize {
        self.half_bandwidth
    }

    /// A zero sparse Hessian whose pattern holds every pair of free DOFs sharing a face
    /// stencil (the bending stencil contains the membrane one).
    pub fn sparse_hessian(&self) -> SparseSymmetricMatrix {
        let mut pairs = Vec::new();
        for f in 0..self.mesh.faces.len() {
            let idx: Vec<usize> = self.face_stencil(f).iter().flatten().copied().collect();
            for (a, &i) in idx.iter().enumerate() {
                for &j in &idx[..a] {
                    pairs.push((i, j));
                }
            }
        }
        SparseSymmetricMatrix::from_pattern(self.dofs.n_free(), pairs)
    }

    /// Free DOF indices of face `f`'s 21-variable bending stencil (None: fixed or absent).
    pub(crate) fn face_stencil(&self, f: usize) -> [Option<usize>; FACE_VARS] {
        let tri = self.mesh.faces[f];
        let mut idx = [None; FACE_VARS];
        for k in 0..3 {
            for c in 0..3 {
                idx[3 * k + c] = self.dofs.vertex(tri[k], c);
            }
            let fe = self.mesh.face_edges[f][k];
            if let Some(p) = fe.opposite_vertex {
                for c in 0..3 {
                    idx[9 + 3 * k + c] = self.dofs.vertex(p, c);
                }
            }
            idx[18 + k] = self.dofs.edge(fe.edge);
        }
        idx
    }

    fn directors(
        &self,
        f: usize,
        positions: &[Vec3],
        s: &ShellState,
        clamp: Clamp,
    ) -> [EdgeDirector; 3] {
        std::array::from_fn(|k| {
            let fe = self.mesh.face_edges[f][k];
            if self.mesh.clamp_edges.contains(&fe.edge) {
                EdgeDirector::Clamped {
                    normal: clamp.normal(),
                }
            } else if let Some(p) = fe.opposite_vertex {
                EdgeDirector::Interior {
                    p: positions[p],
                    phi: s.angles[fe.edge],
                    sigma: fe.orientation,
                }
            } else {
                EdgeDirector::Free {
                    phi: s.angles[fe.edge],
                    sigma: fe.orientation,
                }
            }
        })
    }

    /// Energy (J) of the selected terms at load factor `load`.
    pub fn energy_terms(&self, s: &ShellState, load: f64, terms: ShellTerms) -> f64 {
        self.assemble_terms::<SparseSymmetricMatrix>(s, load, terms, None, None, None)
            .energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected terms at load factor `load`.
    /// `grad` and `abs_grad` are overwritten; `hess` is zeroed first.
    pub fn assemble_terms<M: SymmetricMatrix>(
        &self,
        s: &ShellState,
        load: f64,
        terms: ShellTerms,
        mut grad: Option<&mut [f64]>,
        mut hess: Option<&mut M>,
        mut abs_grad: Option<&mut [f64]>,
    ) -> AssemblyInfo {
        if let Some(g) = grad.as_deref_mut() {
            g.fill(0.0);
        }
        if let Some(a) = abs_grad.as_deref_mut() {
            a.fill(0.0);
        }
        if let Some(h) = hess.as_deref_mut() {
            h.set_zero();
        }
        let want_grad = grad.is_some() || abs_grad.is_some();
        let want_hess = hess.is_some();
        let mut info = AssemblyInfo::default();
        let (gravity_factor, clamp) = self.load_path.at(load, self.clamp);
        // The clamped vertices follow the clamp of the load path (a copy only while the clamp
        // turns: on the gravity path the state already holds them).
        let positions: Cow<[Vec3]> = match self.load_path {
            LoadPath::Gravity => Cow::Borrowed(&s.positions),
            LoadPath::ClampRotation { .. } => {
                let mut p = s.positions.clone();
                for &v in &self.mesh.clamp_vertices {
                    p[v] = clamp.position(&self.mesh.rest_positions[v]);
                }
                Cow::Owned(p)
            }
        };
        let (lambda, mu) = self.properties.lame();
        let h = self.properties.thickness;
        for (f, tri) in self.mesh.faces.iter().enumerate() {
            let q = [&positions[tri[0]], &positions[tri[1]], &positions[tri[2]]];
            let idx = self.face_stencil(f);
            if terms.membrane {
                let mut g9 = SVector::<f64, 9>::zeros();
                let mut h9 = SMatrix::<f64, 9, 9>::zeros();
                let e = membrane_energy(
                    q,
                    &self.rest[f],
                    h,
                    lambda,
                    mu,
                    want_grad.then_some(&mut g9),
                    want_hess.then_some(&mut h9),
                );
                info.energy += e;
                info.energy_magnitude += e.abs();
                scatter(
                    &idx[..9],
                    g9.as_slice(),
                    |a, b| h9[(a, b)],
                    &mut grad,
                    &mut abs_grad,
                    &mut hess,
                );
            }
            if terms.bending {
                let mut g21 = SVector::<f64, FACE_VARS>::zeros();
                let mut h21 = SMatrix::<f64, FACE_VARS, FACE_VARS>::zeros();
                let e = bending_energy(
                    q,
                    &self.directors(f, &positions, s, clamp),
                    &self.rest[f],
                    &self.bbar[f],
                    h,
                    lambda,
                    mu,
                    want_grad.then_some(&mut g21),
                    want_hess.then_some(&mut h21),
                );
                info.energy += e;
                info.energy_magnitude += e.abs();
                scatter(
                    &idx,
                    g21.as_slice(),
                    |a, b| h21[(a, b)],
                    &mut grad,
                    &mut abs_grad,
                    &mut hess,
                );
            }
        }
        if terms.gravity {
            let g = self.gravity * gravity_factor;
            let e = gravity_energy(&self.vertex_masses, &positions, &g);
            info.energy += e;
            info.energy_magnitude += e.abs();
            let e_rest = gravity_energy(&self.vertex_masses, &self.mesh.rest_positions, &g);
            info.external_work = e_rest - e;
            for (v, m) in self.vertex_masses.iter().enumerate() {
                for c in 0..3 {
                    let Some(i) = self.dofs.vertex(v, c) else {
                        continue;
                    };
                    let force = m * g[c];
                    info.external_force = info.external_force.max(force.abs());
                    if let Some(gr) = grad.as_deref_mut() {
                        gr[i] -= force;
                    }
                    if let Some(a) = abs_grad.as_deref_mut() {
                        a[i] += force.abs();
                    }
                }
            }
        }
        info
    }
}

/// Adds a local gradient and Hessian (over `idx`, None = fixed) to the global ones.
fn scatter<M: SymmetricMatrix>(
    idx: &[Option<usize>],
    g: &[f64],
    h: impl Fn(usize, usize) -> f64,
    grad: &mut Option<&mut [f64]>,
    abs_grad: &mut Option<&mut [f64]>,
    hess: &mut Option<&mut M>,
) {
    for (a, ia) in idx.iter().enumerate() {
        let Some(i) = *ia else { continue };
        if let Some(gr) = grad.as_deref_mut() {
            gr[i] += g[a];
        }
        if let Some(ab) = abs_grad.as_deref_mut() {
            ab[i] += g[a].abs();
        }
        if let Some(hm) = hess.as_deref_mut() {
            for (b, ib) in idx.iter().enumerate().take(a + 1) {
                let Some(j) = *ib else { continue };
                let v = h(a, b);
                if v != 0.0 {
                    // Two local slots can map to one global DOF only on the diagonal (a = b).
                    if i == j && a != b {
                        hm.add(i, j, 2.0 * v);
                    } else {
                        hm.add(i, j, v);
                    }
                }
            }
        }
    }
}
