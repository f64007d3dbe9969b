//! The members a structure is made of, behind one interface (an enum: a structure may mix
//! formulations).

use crate::assembly::Assembler;
use crate::linalg::SymmetricMatrix;
use crate::rod::{Rod, RodState};
use crate::solver::{EquilibriumProblem, MassMetric};

/// A member of a structure.
#[derive(Clone, Debug)]
pub enum Member {
    /// A discrete elastic rod.
    Der(Rod),
}

/// The state of a member.
#[derive(Clone, Debug, PartialEq)]
pub enum MemberState {
    /// A discrete elastic rod's state.
    Der(RodState),
}

impl MemberState {
    /// The rod state, if this is a discrete elastic rod.
    pub fn as_der(&self) -> Option<&RodState> {
        match self {
            Self::Der(s) => Some(s),
        }
    }

    /// Vertex positions (m).
    pub fn positions(&self) -> &[crate::geometry::Vec3] {
        match self {
            Self::Der(s) => s.positions(),
        }
    }
}

macro_rules! der {
    ($s:expr) => {
        match $s {
            MemberState::Der(s) => s,
        }
    };
}

impl Member {
    /// The rod, if this is a discrete elastic rod.
    pub fn as_der(&self) -> Option<&Rod> {
        match self {
            Self::Der(r) => Some(r),
        }
    }

    /// Mutable access to the rod.
    pub fn as_der_mut(&mut self) -> Option<&mut Rod> {
        match self {
            Self::Der(r) => Some(r),
        }
    }

    /// Number of the member's own free DOFs.
    pub fn n_free(&self) -> usize {
        match self {
            Self::Der(r) => r.n_free(),
        }
    }

    /// The rest state.
    pub fn rest_state(&self) -> MemberState {
        match self {
            Self::Der(r) => MemberState::Der(r.rest_state().clone()),
        }
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        match self {
            Self::Der(r) => r.n_edges() + 1,
        }
    }

    /// Runs the member's terms through `asm` (a part assembler mapping its DOFs).
    pub fn assemble_into<M: SymmetricMatrix>(
        &self,
        state: &MemberState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        match self {
            Self::Der(r) => r.assemble_into(der!(state), load, asm),
        }
    }

    /// The retraction with the member's step given by `dx`.
    pub fn displace_by(
        &self,
        state: &MemberState,
        dx: impl Fn(usize) -> f64,
        alpha: f64,
        out: &mut MemberState,
    ) {
        match (self, out) {
            (Self::Der(r), MemberState::Der(o)) => r.retract_by(der!(state), dx, alpha, o),
        }
    }

    /// The chart (see [`EquilibriumProblem::chart`]) with the member's step given by `dx`.
    pub fn chart_by(&self, state: &MemberState, dx: impl Fn(usize) -> f64, out: &mut MemberState) {
        match (self, out) {
            (Self::Der(r), MemberState::Der(o)) => r.displace_linear_by(der!(state), dx, 1.0, o),
        }
    }

    /// Calls `f(i, d)` with the difference `a ⊖ b` of every own free DOF `i`.
    pub fn difference(&self, a: &MemberState, b: &MemberState, mut f: impl FnMut(usize, f64)) {
        match self {
            Self::Der(r) => {
                let (a, b) = (der!(a), der!(b));
                for i in 0..r.n_free() {
                    f(i, r.dof_value(a, i) - r.dof_value(b, i));
                }
            }
        }
    }

    /// The member's step cap for the step `dx`.
    pub fn max_step_by(&self, state: &MemberState, dx: impl Fn(usize) -> f64 + Copy) -> f64 {
        match self {
            Self::Der(r) => r.max_step_by(der!(state), dx),
        }
    }

    /// See [`EquilibriumProblem::force_length`].
    pub fn force_length(&self, i: usize) -> f64 {
        match self {
            Self::Der(r) => r.force_length(i),
        }
    }

    /// See [`EquilibriumProblem::dof_magnitude`].
    pub fn dof_magnitude(&self, state: &MemberState, i: usize) -> f64 {
        match self {
            Self::Der(r) => r.dof_magnitude(der!(state), i),
        }
    }

    /// See [`MassMetric::inertia_metric`].
    pub fn inertia_metric(&self, i: usize) -> f64 {
        match self {
            Self::Der(r) => r.inertia_metric(i),
        }
    }

    /// See [`MassMetric::eigenvalue_scale`].
    pub fn eigenvalue_scale(&self) -> f64 {
        match self {
            Self::Der(r) => r.eigenvalue_scale(),
        }
    }

    /// See [`EquilibriumProblem::impose_load`].
    pub fn impose_load(&self, state: &mut MemberState, from: f64, to: f64, guess: bool) {
        match self {
            Self::Der(r) => r.impose_load(der!(state), from, to, guess),
        }
    }

    /// Calls `f` with every term's stencil (own free DOFs).
    pub fn for_each_stencil(&self, f: impl FnMut(&[usize])) {
        match self {
            Self::Der(r) => r.for_each_stencil(f),
        }
    }

    /// The own free DOF of coordinate `k` of vertex `v`, or FIXED.
    pub fn vertex_dof(&self, v: usize, k: usize) -> usize {
        match self {
            Self::Der(r) => r.dofs().vertex(v, k),
        }
    }
}
