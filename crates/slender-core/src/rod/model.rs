//! A discrete elastic rod ready to be solved, and the assembly of its energy, gradient and
//! banded Hessian over the free DOFs.

use crate::assembly::AssemblyInfo;
use crate::assembly::{Assembler, TermSet, FIXED};
use crate::geometry::Vec3;
use crate::linalg::{SymmetricBandMatrix, SymmetricMatrix};

use super::dofs::DofMap;
use super::frames::EdgeId;
use super::groups;
use super::hinge::{Hinge, HingeState, HINGE_DOFS};
use super::moment::MomentLoad;
use super::section::RodProperties;
use super::state::RodState;
use super::stretching::StretchTerm;
use super::supports::Supports;

/// A discrete elastic rod ready to be solved (see the crate docs and design.md §2).
#[derive(Clone, Debug)]
pub struct Rod {
    pub(super) properties: RodProperties,
    pub(super) rest_lengths: Vec<f64>,
    pub(super) length: f64,
    pub(super) stretch_terms: Vec<StretchTerm>,
    pub(super) hinges: Vec<Hinge>,
    pub(super) hinge_edges: Vec<(EdgeId, EdgeId)>,
    pub(super) vertex_masses: Vec<f64>,
    /// Dead nodal forces (N) at load factor 1: gravity plus point forces.
    pub(super) nodal_forces: Vec<Vec3>,
    /// Dead nodal forces (N) on at every load factor (preload gravity).
    pub(super) preload_forces: Vec<Vec3>,
    pub(super) dofs: DofMap,
    /// Point moments, split into bending and axial parts.
    pub(super) moments: Vec<MomentLoad>,
    /// Vertices with fixed positions (clamps and pins), sorted.
    pub(super) fixed_vertices: Vec<usize>,
    /// Where the retraction's walks start: the fixed vertices plus any vertex a structure
    /// moves linearly (joints, sliders), sorted.
    pub(super) anchors: Vec<usize>,
    pub(super) supports: Supports,
    pub(super) gravity: Vec3,
    pub(super) rest: RodState,
    /// Arc length (m) of every vertex from vertex 0 along the rest polygon.
    pub(super) arclengths: Vec<f64>,
    /// What the load factor drives.
    pub(super) load_path: super::load_path::RodLoadPath,
    /// Follower loads (applied lagged, see `follower.rs`).
    pub(super) followers: Vec<super::follower::FollowerLoad>,
    /// The dead loads before a gravity change (see `Rod::save_loads`).
    pub(super) saved_loads: super::load_path::SavedLoads,
}

impl Rod {
    /// Number of edges.
    pub fn n_edges(&self) -> usize {
        self.rest_lengths.len()
    }

    /// Rest length of the centerline (m).
    pub fn length(&self) -> f64 {
        self.length
    }

    /// Section properties.
    pub fn properties(&self) -> &RodProperties {
        &self.properties
    }

    /// Rest edge lengths (m).
    pub fn rest_lengths(&self) -> &[f64] {
        &self.rest_lengths
    }

    /// Supports.
    pub fn supports(&self) -> &Supports {
        &self.supports
    }

    /// Gravitational acceleration (m/s²) at load factor 1.
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The stress-free state (also the default initial state).
    pub fn rest_state(&self) -> &RodState {
        &self.rest
    }

    /// Lumped vertex masses (kg).
    pub fn vertex_masses(&self) -> &[f64] {
        &self.vertex_masses
    }

    /// Calls `f` with the stencil (free DOFs, [`FIXED`](crate::assembly::FIXED) for others)
    /// of every term: the Hessian's sparsity pattern.
    pub fn for_each_stencil(&self, mut f: impl FnMut(&[usize])) {
        for t in &self.stretch_terms {
            f(&t.dofs);
        }
        for h in &self.hinges {
            f(&h.dofs);
        }
        for m in &self.moments {
            f(&self.moment_dofs(m.edge));
        }
    }

    /// Re-adapts the reference frames of `s` to its positions after they were changed in
    /// place (frames transported, reference twists continued).
    pub fn refresh_frames(&self, s: &mut RodState) {
        s.frames.transport_in_place(&s.positions, &self.hinge_edges);
    }

    /// Sets the vertices that the retraction moves linearly by their own step, besides the
    /// fixed ones (a structure's joints and sliders; see [`Rod::retract_by`]).
    pub fn set_anchors(&mut self, extra: &[usize]) {
        let mut a = self.fixed_vertices.clone();
        a.extend_from_slice(extra);
        a.sort_unstable();
        a.dedup();
        self.anchors = a;
    }

    /// Vertices whose positions the rod's own supports fix (clamps and pins), sorted.
    pub fn fixed_vertices(&self) -> &[usize] {
        &self.fixed_vertices
    }

    /// The hinges' edge pairs (for output of strains per hinge).
    pub fn hinge_count(&self) -> usize {
        self.hinges.len()
    }

    /// Free-DOF vector of a state (coordinates in m, angles in rad).
    pub fn dof_vector(&self, s: &RodState) -> Vec<f64> {
        let mut v = vec![0.0; self.dofs.n_free()];
        self.dof_values(s, &mut v);
        v
    }

    /// Free indices of the two end vertices of edge `j` (the stretching stencil).
    pub(super) fn edge_dofs(&self, j: usize) -> [usize; 6] {
        let mut map = [FIXED; 6];
        for k in 0..3 {
            map[k] = self.dofs.vertex(j, k);
            map[3 + k] = self.dofs.vertex(j + 1, k);
        }
        map
    }

    /// The stencil of a moment on edge `j`: `[x_j, x_{j+1}, θ_j]` (see `moment.rs`).
    pub(super) fn moment_dofs(&self, j: usize) -> [usize; super::moment::MOMENT_DOFS] {
        let mut d = [FIXED; super::moment::MOMENT_DOFS];
        d[..6].copy_from_slice(&self.edge_dofs(j));
        d[6] = self.dofs.theta(j);
        d
    }

    pub(super) fn hinge_dofs(&self, vertex: usize, l: EdgeId, r: EdgeId) -> [usize; HINGE_DOFS] {
        let mut d = [FIXED; HINGE_DOFS];
        let put_vertex = |slot: usize, v: usize, d: &mut [usize; HINGE_DOFS]| {
            for k in 0..3 {
                d[slot + k] = self.dofs.vertex(v, k);
            }
        };
        if let EdgeId::Real(j) = l {
            put_vertex(0, j, &mut d);
            d[3] = self.dofs.theta(j);
        }
        put_vertex(4, vertex, &mut d);
        if let EdgeId::Real(j) = r {
            d[7] = self.dofs.theta(j);
            put_vertex(8, j + 1, &mut d);
        }
        d
    }

    #[inline]
    pub(super) fn hinge_state(&self, s: &RodState, hinge: &Hinge) -> HingeState {
        let k = hinge.index;
        let v = hinge.vertex;
        let (l, r) = hinge.edges;
        let (x0, theta_l) = match l {
            EdgeId::Real(j) => (s.positions[j], s.thetas[j]),
            _ => self.ghost_point(s, v, false),
        };
        let (x2, theta_r) = match r {
            EdgeId::Real(j) => (s.positions[j + 1], s.thetas[j]),
            _ => self.ghost_point(s, v, true),
        };
        // A real edge's tangent and length as the frames measured them (they are adapted to
        // the positions); a ghost edge is measured by the hinge.
        let measured = |id: EdgeId| match id {
            EdgeId::Real(j) => {
                let m = (s.frames.edges[j].tangent, s.frames.lengths[j]);
                // (A trial state with NaN positions passes: its energy is NaN either way.)
                debug_assert!(
                    !((m.1.length - (s.positions[j + 1] - s.positions[j]).norm()).abs()
                        > 1e-12 * m.1.length),
                    "edge {j}: frames not adapted to the positions"
                );
                Some(m)
            }
            _ => None,
        };
        HingeState {
            x: [x0, s.positions[v], x2],
            a1: [s.frames.edge(l).a1, s.frames.edge(r).a1],
            theta: [theta_l, theta_r],
            ref_twist: s.frames.ref_twist[k],
            edges: [measured(l), measured(r)],
        }
    }

    /// Energy (J) of the selected term groups (see [`groups`](super::groups)) at load
    /// factor `load`.
    pub fn energy_terms(&self, s: &RodState, load: f64, terms: TermSet) -> f64 {
        let mut asm = Assembler::<SymmetricBandMatrix>::energy_only(terms);
        self.assemble_into(s, load, &mut asm);
        asm.finish().energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected term groups into any Hessian
    /// storage whose pattern holds the rod's band. `grad` and `abs_grad` are overwritten;
    /// `hess` is zeroed first.
    pub fn assemble_terms<M: SymmetricMatrix>(
        &self,
        s: &RodState,
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

    /// Runs every term group of the rod through `asm`: stretching per edge, bending and
    /// twisting per hinge, then the external loads.
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        s: &RodState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        let ctx = RodContext {
            rod: self,
            state: s,
        };
        asm.terms(&ctx, &self.stretch_terms);
        asm.terms(&ctx, &self.hinges);
        if asm.selects(groups::EXTERNAL) {
            self.assemble_loads(s, load, asm);
        }
    }
}

/// What a rod term is evaluated at: the rod and a state adapted to it.
pub struct RodContext<'a> {
    /// The rod.
    pub rod: &'a Rod,
    /// The state (frames adapted to its positions).
    pub state: &'a RodState,
}
