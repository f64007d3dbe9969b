//! A discrete elastic rod ready to be solved, and the assembly of its energy, gradient and
//! banded Hessian over the free DOFs.

use nalgebra::{SMatrix, SVector};

use crate::geometry::Vec3;
use crate::linalg::SymmetricBandMatrix;
use crate::solver::problem::{AssemblyInfo, EquilibriumProblem};

use super::bending::BendingHinge;
use super::builder::Supports;
use super::dofs::{DofMap, FIXED};
use super::frames::EdgeId;
use super::hinge::{EdgeHessian, HingeFrame, HingeMatrix, HingeState, HingeVector, HINGE_DOFS};
use super::moment::MomentLoad;
use super::section::RodProperties;
use super::state::RodState;
use super::stretching::stretching_energy;
use super::twisting::TwistingHinge;

/// Which energy terms an assembly includes (all by default; tests select single terms).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Terms {
    /// Stretching.
    pub stretching: bool,
    /// Bending.
    pub bending: bool,
    /// Twisting.
    pub twisting: bool,
    /// Gravity and point loads.
    pub external: bool,
}

impl Terms {
    /// Every term.
    pub const ALL: Self = Self {
        stretching: true,
        bending: true,
        twisting: true,
        external: true,
    };
    /// No term (combine with struct update syntax).
    pub const NONE: Self = Self {
        stretching: false,
        bending: false,
        twisting: false,
        external: false,
    };
}

/// A hinge of the rod: topology, DOF map and its bending and twisting data.
#[derive(Clone, Debug)]
pub(super) struct Hinge {
    pub(super) vertex: usize,
    pub(super) edges: (EdgeId, EdgeId),
    pub(super) dofs: [usize; HINGE_DOFS],
    pub(super) bending: BendingHinge,
    pub(super) twisting: TwistingHinge,
}

/// A discrete elastic rod ready to be solved (see the crate docs and design.md §2).
#[derive(Clone, Debug)]
pub struct Rod {
    pub(super) properties: RodProperties,
    pub(super) rest_lengths: Vec<f64>,
    pub(super) length: f64,
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
    pub(super) supports: Supports,
    pub(super) gravity: Vec3,
    pub(super) rest: RodState,
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

    /// Free-DOF vector of a state (coordinates in m, angles in rad).
    pub fn dof_vector(&self, s: &RodState) -> Vec<f64> {
        let mut v = vec![0.0; self.dofs.n_free()];
        self.dof_values(s, &mut v);
        v
    }

    /// Free indices of the two end vertices of edge `j` (the stretching stencil).
    fn edge_dofs(&self, j: usize) -> [usize; 6] {
        let mut map = [FIXED; 6];
        for k in 0..3 {
            map[k] = self.dofs.vertex(j, k);
            map[3 + k] = self.dofs.vertex(j + 1, k);
        }
        map
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

    pub(super) fn hinge_state(&self, s: &RodState, hinge: &Hinge, k: usize) -> HingeState {
        let v = hinge.vertex;
        let (l, r) = hinge.edges;
        let (x0, theta_l) = match l {
            EdgeId::Real(j) => (s.positions[j], s.thetas[j]),
            _ => {
                let g = s.frames.ghost_start.expect("start clamp");
                (s.positions[v] - g.frame.tangent * g.length, g.theta)
            }
        };
        let (x2, theta_r) = match r {
            EdgeId::Real(j) => (s.positions[j + 1], s.thetas[j]),
            _ => {
                let g = s.frames.ghost_end.expect("end clamp");
                (s.positions[v] + g.frame.tangent * g.length, g.theta)
            }
        };
        HingeState {
            x: [x0, s.positions[v], x2],
            a1: [s.frames.edge(l).a1, s.frames.edge(r).a1],
            theta: [theta_l, theta_r],
            ref_twist: s.frames.ref_twist[k],
        }
    }

    /// Energy (J) of the selected terms at load factor `load`.
    pub fn energy_terms(&self, s: &RodState, load: f64, terms: Terms) -> f64 {
        self.assemble_terms(s, load, terms, None, None, None).energy
    }

    /// Energy, gradient (free DOFs) and Hessian of the selected terms. `grad` and `abs_grad`
    /// are overwritten; `hess` is zeroed first.
    pub fn assemble_terms(
        &self,
        s: &RodState,
        load: f64,
        terms: Terms,
        mut grad: Option<&mut [f64]>,
        mut hess: Option<&mut SymmetricBandMatrix>,
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

        if terms.stretching {
            let ea = self.properties.stiffness.ea;
            let mut g6 = SVector::<f64, 6>::zeros();
            let mut h6 = SMatrix::<f64, 6, 6>::zeros();
            for (j, &rest_length) in self.rest_lengths.iter().enumerate() {
                g6.fill(0.0);
                h6.fill(0.0);
                let e = stretching_energy(
                    &s.positions[j],
                    &s.positions[j + 1],
                    rest_length,
                    ea,
                    want_grad.then_some(&mut g6),
                    want_hess.then_some(&mut h6),
                );
                info.energy += e;
                info.energy_magnitude += e.abs();
                scatter(
                    &self.edge_dofs(j),
                    g6.as_slice(),
                    &h6,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
            }
        }

        if terms.bending || terms.twisting {
            let mut g = HingeVector::zeros();
            let mut h = HingeMatrix::zeros();
            let mut edge = EdgeHessian::default();
            for (k, hinge) in self.hinges.iter().enumerate() {
                let hs = self.hinge_state(s, hinge, k);
                let frame = HingeFrame::new(&hs);
                g.fill(0.0);
                if want_hess {
                    h.fill(0.0);
                    edge = EdgeHessian::default();
                }
                if terms.bending {
                    let e = hinge.bending.energy(
                        &frame,
                        want_grad.then_some(&mut g),
                        want_hess.then_some((&mut h, &mut edge)),
                    );
                    info.energy += e;
                    info.energy_magnitude += e.abs();
                }
                if terms.twisting {
                    let e = hinge.twisting.energy(
                        &frame,
                        hs.twist(),
                        want_grad.then_some(&mut g),
                        want_hess.then_some((&mut h, &mut edge)),
                    );
                    info.energy += e;
                    info.energy_magnitude += e.abs();
                }
                if want_hess {
                    edge.scatter_into(&mut h);
                }
                scatter(
                    &hinge.dofs,
                    g.as_slice(),
                    &h,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
            }
        }

        if terms.external {
            // Dead loads: V = −λ Σ f_v·x_v, measured from the rest positions so that the
            // energy scale is the work done, not an arbitrary datum.
            for (v, (f, f0)) in self
                .nodal_forces
                .iter()
                .zip(&self.preload_forces)
                .enumerate()
            {
                let f = f * load + f0;
                let du = s.positions[v] - self.rest.positions[v];
                let w = f.dot(&du);
                info.energy -= w;
                info.energy_magnitude += w.abs();
                info.external_work += w;
                info.external_force = info.external_force.max(f.amax());
                for k in 0..3 {
                    let i = self.dofs.vertex(v, k);
                    if i == FIXED {
                        continue;
                    }
                    if let Some(gr) = grad.as_deref_mut() {
                        gr[i] -= f[k];
                    }
                    if let Some(a) = abs_grad.as_deref_mut() {
                        a[i] += f[k].abs();
                    }
                }
            }
            let mut g6 = SVector::<f64, 6>::zeros();
            let mut h6 = SMatrix::<f64, 6, 6>::zeros();
            for (m, &alpha) in self.moments.iter().zip(&s.load_angles) {
                let j = m.edge;
                let e = s.positions[j + 1] - s.positions[j];
                let v = m.bending_potential(&e, alpha, load, &mut g6, &mut h6);
                let dtheta = s.thetas[j] - self.rest.thetas[j];
                let w = -v + load * m.axial * dtheta;
                info.energy -= w;
                info.energy_magnitude += w.abs();
                info.external_work += w;
                info.external_force = info
                    .external_force
                    .max(load * (m.bending + m.axial.abs()) / self.length);
                scatter(
                    &self.edge_dofs(j),
                    g6.as_slice(),
                    &h6,
                    &mut grad,
                    &mut hess,
                    &mut abs_grad,
                );
                let i = self.dofs.theta(j);
                if i != FIXED {
                    if let Some(gr) = grad.as_deref_mut() {
                        gr[i] -= load * m.axial;
                    }
                    if let Some(a) = abs_grad.as_deref_mut() {
                        a[i] += (load * m.axial).abs();
                    }
                }
            }
        }
        info
    }
}

/// Adds a stencil's gradient and Hessian into the global (free-DOF) arrays.
fn scatter<const D: usize>(
    map: &[usize; D],
    g: &[f64],
    h: &SMatrix<f64, D, D>,
    grad: &mut Option<&mut [f64]>,
    hess: &mut Option<&mut SymmetricBandMatrix>,
    abs_grad: &mut Option<&mut [f64]>,
) {
    for (a, &i) in map.iter().enumerate() {
        if i == FIXED {
            continue;
        }
        if let Some(gr) = grad.as_deref_mut() {
            gr[i] += g[a];
        }
        if let Some(ab) = abs_grad.as_deref_mut() {
            ab[i] += g[a].abs();
        }
        if let Some(hm) = hess.as_deref_mut() {
            for (b, &j) in map.iter().enumerate() {
                // Lower triangle only: the band matrix stores each pair once.
                if j != FIXED && j <= i {
                    hm.add(i, j, h[(a, b)]);
                }
            }
        }
    }
}
