//! The shell model: mesh, material, clamp, gravity, and assembly of energy, gradient and
//! Hessian over the free DOFs.

use std::ops::AddAssign;

use nalgebra::{SMatrix, SVector, Vector3};

use crate::assembly::{Assembler, LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::assembly::{AssemblyInfo, FIXED};
use crate::geometry::Vec3;
use crate::linalg::{ScatterPlan, SparseSymmetricMatrix, SymmetricMatrix};
use crate::rod::Grading;
use crate::scratch::Scratch;

use super::bending::{bending_energy, EdgeDirector, FACE_VARS};
use super::clamp::Clamp;
use super::dofs::ShellDofs;
use super::groups;
use super::load_path::LoadPath;
use super::membrane::{membrane_energy, FaceRest};
use super::mesh::StripMesh;
use super::state::ShellState;
use super::strip_guess::StripGuess;
use crate::bspline_shell::StripEnd;

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

/// A Kirchhoff–Love shell strip clamped at x = 0, at x = L or both (see the module docs of
/// `shell`).
#[derive(Clone, Debug)]
pub struct Shell {
    pub(crate) mesh: StripMesh,
    pub(crate) properties: ShellProperties,
    pub(crate) rest: Vec<FaceRest>,
    pub(crate) faces: Vec<FaceTerm>,
    pub(crate) bbar: Vec<Vector3<f64>>,
    pub(crate) dofs: ShellDofs,
    pub(crate) half_bandwidth: usize,
    pub(crate) vertex_masses: Vec<f64>,
    pub(crate) edge_inertia: Vec<f64>,
    pub(crate) gravity: Vec3,
    pub(crate) load_path: LoadPath,
    pub(crate) grading: Grading,
    /// Which ends are clamped (indexed by [`StripEnd::index`]).
    pub(crate) clamped: [bool; 2],
    /// Per mesh edge: the end whose clamp sets its director (None: not a clamp edge).
    pub(crate) edge_clamp: Vec<Option<usize>>,
    /// Dead point forces (vertex, force in N at load factor 1), scaled with gravity.
    pub(crate) point_forces: Vec<(usize, Vec3)>,
    /// Where the face terms' Hessian entries go in [`Self::sparse_hessian`]'s pattern.
    pub(crate) scatter: ScatterPlan,
    /// Working memory of the both-ends first guess, kept between calls.
    pub(crate) guess: Scratch<StripGuess>,
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

    /// Turns the start clamp of `state` about x to `sigma` (rad) and moves its clamped
    /// vertices with it.
    pub fn set_clamp_rotation(&self, sigma: f64, state: &mut ShellState) {
        self.set_clamp(Clamp::about_x(sigma), state);
    }

    /// Puts the start clamp of `state` at pose `clamp` and moves its clamped vertices with it.
    pub fn set_clamp(&self, clamp: Clamp, state: &mut ShellState) {
        self.set_clamp_at(StripEnd::Start, clamp, state);
    }

    /// Puts the clamp of `end` in `state` at pose `clamp` and moves its clamped vertices with
    /// it (an end that is not clamped only records the pose).
    pub fn set_clamp_at(&self, end: StripEnd, clamp: Clamp, state: &mut ShellState) {
        state.clamps[end.index()] = clamp;
        self.apply_clamp(state);
    }

    /// Whether `end` is clamped.
    pub fn is_clamped(&self, end: StripEnd) -> bool {
        self.clamped[end.index()]
    }

    /// Dead point forces (vertex, N at load factor 1).
    pub fn point_forces(&self) -> &[(usize, Vec3)] {
        &self.point_forces
    }

    /// Sets point force `k` (in the order they were built) to `force` (N at load factor 1).
    ///
    /// # Panics
    /// If there is no point force `k` (callers check the index against the scene).
    pub fn set_point_force(&mut self, k: usize, force: Vec3) {
        self.point_forces[k].1 = force;
    }

    /// What the load factor drives (gravity by default).
    pub fn load_path(&self) -> LoadPath {
        self.load_path
    }

    /// Sets what the load factor drives.
    pub fn set_load_path(&mut self, path: LoadPath) {
        self.load_path = path;
    }

    /// Puts the clamped vertices of `state` where its clamp holds them.
    pub fn apply_clamp(&self, state: &mut ShellState) {
        for end in StripEnd::BOTH {
            if !self.is_clamped(end) {
                continue;
            }
            let clamp = state.clamps[end.index()];
            for &v in &self.mesh.end_vertices[end.index()] {
                state.positions[v] = clamp.position(&self.mesh.rest_positions[v]);
            }
        }
    }

    /// The rest (flat, unloaded) state.
    pub fn rest_state(&self) -> ShellState {
        let mut s = ShellState {
            positions: self.mesh.rest_positions.clone(),
            angles: vec![0.0; self.mesh.edges.len()],
            clamps: [Clamp::default(); 2],
            membrane_remainder: Vec::new(),
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
    /// stencil (the bending stencil contains the membrane one): the pattern of the shell's
    /// scatter plan.
    pub fn sparse_hessian(&self) -> SparseSymmetricMatrix {
        SparseSymmetricMatrix::zeros_of(&self.scatter)
    }

    /// The zero Hessian of the face terms over `n_free` DOFs and the plan of their scatter
    /// into it (built once with the shell).
    pub(crate) fn hessian_plan(faces: &[FaceTerm], n_free: usize) -> ScatterPlan {
        let mut pairs = Vec::new();
        for t in faces {
            let idx: Vec<usize> = t.dofs.iter().copied().filter(|&i| i != FIXED).collect();
            for (a, &i) in idx.iter().enumerate() {
                for &j in &idx[..a] {
                    pairs.push((i, j));
                }
            }
        }
        let hessian = SparseSymmetricMatrix::from_pattern(n_free, pairs);
        hessian.scatter_plan(faces.iter().map(|t| &t.dofs))
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
        clamps: &[Clamp; 2],
    ) -> [EdgeDirector; 3] {
        std::array::from_fn(|k| {
            let fe = self.mesh.face_edges[f][k];
            if let Some(end) = self.edge_clamp[fe.edge] {
                EdgeDirector::Clamped {
                    normal: clamps[end].normal(),
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

    /// Energy (J) of the selected term groups (see [`groups`](super::groups)) at load
    /// factor `load`.
    pub fn energy_terms(&self, s: &ShellState, load: f64, terms: TermSet) -> f64 {
        let mut asm = Assembler::<SparseSymmetricMatrix>::energy_only(terms);
        self.assemble_into(s, load, &mut asm);
        asm.finish().energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected term groups at load factor
    /// `load`. `grad` and `abs_grad` are overwritten; `hess` is zeroed first.
    pub fn assemble_terms<M: SymmetricMatrix>(
        &self,
        s: &ShellState,
        load: f64,
        terms: TermSet,
        grad: Option<&mut [f64]>,
        hess: Option<&mut M>,
        abs_grad: Option<&mut [f64]>,
    ) -> AssemblyInfo {
        let mut asm = Assembler::new(terms, grad, hess, abs_grad);
        self.assemble_into(s, load, &mut asm);
        asm.finish()
    }

    /// Runs the shell's term groups through `asm`: membrane and bending per face, then the
    /// self-weight and the point forces (both in the gravity group: the dead loads the load
    /// factor scales).
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        s: &ShellState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let gravity_factor = self.load_path.gravity_factor(load);
        let positions = &s.positions;
        let ctx = ShellContext {
            shell: self,
            positions,
            state: s,
            clamps: s.clamps,
        };
        asm.terms_planned(&ctx, &self.faces, Some(&self.scatter));
        if asm.selects(groups::GRAVITY) {
            let g = self.gravity * gravity_factor;
            for (v, m) in self.vertex_masses.iter().enumerate() {
                // One potential per vertex, so that the round-off scale of the energy is
                // Σ|m g·x| (the terms of a strip hanging about z = 0 cancel in the sum).
                let force = g * *m;
                asm.external_energy(
                    -force.dot(&positions[v]),
                    force.dot(&(positions[v] - self.mesh.rest_positions[v])),
                );
                for c in 0..3 {
                    let Some(i) = self.dofs.vertex(v, c) else {
                        continue;
                    };
                    asm.external_force(force[c].abs());
                    asm.generalized_force(i, force[c]);
                }
            }
            for &(v, f) in &self.point_forces {
                let force = f * gravity_factor;
                asm.external_energy(
                    -force.dot(&positions[v]),
                    force.dot(&(positions[v] - self.mesh.rest_positions[v])),
                );
                for c in 0..3 {
                    let Some(i) = self.dofs.vertex(v, c) else {
                        continue;
                    };
                    asm.external_force(force[c].abs());
                    asm.generalized_force(i, force[c]);
                }
            }
        }
    }
}

/// What a shell term is evaluated at.
pub struct ShellContext<'a> {
    /// The shell.
    pub shell: &'a Shell,
    /// Vertex positions (m).
    pub positions: &'a [Vec3],
    /// The state (edge angles).
    pub state: &'a ShellState,
    /// The clamps (the state's), by end.
    pub clamps: [Clamp; 2],
}

/// One face of the shell, a term of the membrane and bending groups on the 21-slot stencil
/// (q₀, q₁, q₂, the three opposite vertices, the three edge angles; the membrane uses the
/// first nine).
#[derive(Clone, Debug)]
pub struct FaceTerm {
    /// The face.
    pub(crate) face: usize,
    /// Free DOF of each slot.
    pub(crate) dofs: Stencil<FACE_VARS>,
}

impl<'a> StencilTerm<ShellContext<'a>, FACE_VARS> for FaceTerm {
    fn groups(&self) -> TermSet {
        groups::MEMBRANE.set().with(groups::BENDING.set())
    }

    fn stencil(&self) -> &Stencil<FACE_VARS> {
        &self.dofs
    }

    fn evaluate(
        &self,
        ctx: &ShellContext<'a>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, FACE_VARS>,
    ) {
        let shell = ctx.shell;
        let f = self.face;
        let tri = shell.mesh.faces[f];
        let p = ctx.positions;
        let q = [&p[tri[0]], &p[tri[1]], &p[tri[2]]];
        let (lambda, mu) = shell.properties.lame();
        let h = shell.properties.thickness;
        if selected.contains(groups::MEMBRANE) {
            let mut g9 = SVector::<f64, 9>::zeros();
            let mut h9 = SMatrix::<f64, 9, 9>::zeros();
            let e = membrane_energy(
                q,
                &shell.rest[f],
                h,
                lambda,
                mu,
                ctx.state.membrane_remainder.get(f),
                out.grad.is_some().then_some(&mut g9),
                out.hess.is_some().then_some(&mut h9),
            );
            out.add_energy(e);
            if let Some(g) = out.grad.as_deref_mut() {
                g.fixed_rows_mut::<9>(0).add_assign(&g9);
            }
            if let Some(hm) = out.hess.as_deref_mut() {
                hm.fixed_view_mut::<9, 9>(0, 0).add_assign(&h9);
            }
        }
        if selected.contains(groups::BENDING) {
            let e = bending_energy(
                q,
                &shell.directors(f, p, ctx.state, &ctx.clamps),
                &shell.rest[f],
                &shell.bbar[f],
                h,
                lambda,
                mu,
                out.grad.as_deref_mut(),
                out.hess.as_deref_mut(),
            );
            out.add_energy(e);
        }
    }
}
