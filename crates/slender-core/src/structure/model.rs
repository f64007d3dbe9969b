//! The structure as one [`EquilibriumProblem`].

// Members have one formulation today; the `if let`s over member kinds stay for the others.
#![allow(irrefutable_let_patterns)]

use crate::assembly::{Assembler, TermGroup, TermSet, FIXED};
use crate::geometry::Vec3;
use crate::linalg::{AdaptiveMatrix, SymmetricMatrix};
use crate::rod::groups::{ALL_GROUPS, BENDING, TWISTING};

/// The term groups of a structure with shearable members (Cosserat rods, SE(3) beams): the
/// discrete elastic rod's, which they share bit for bit, and shear.
const WITH_SHEAR: [TermGroup; 5] = [
    ALL_GROUPS[0],
    ALL_GROUPS[1],
    ALL_GROUPS[2],
    ALL_GROUPS[3],
    crate::framed::groups::SHEAR,
];
use crate::solver::{EquilibriumProblem, MassMetric};

use super::builder::{SliderSupport, TwistHold};
use super::dof_map::GlobalDofs;
use super::joint::JointHinge;
use super::member::{Member, MemberState};

/// The state of a structure: its members' states and the joint hinges' reference twists.
#[derive(Debug, PartialEq)]
pub struct StructureState {
    /// One state per member.
    pub members: Vec<MemberState>,
    /// Reference twist (rad) of each joint hinge, continued like a rod's.
    pub(super) joint_twists: Vec<f64>,
}

/// Written out so that `clone_from` reuses the buffers (a derived one allocates a clone): the
/// solvers copy states into their workspaces on every re-solve.
impl Clone for StructureState {
    fn clone(&self) -> Self {
        Self {
            members: self.members.clone(),
            joint_twists: self.joint_twists.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.members.clone_from(&source.members);
        self.joint_twists.clone_from(&source.joint_twists);
    }
}

/// What structure-level supports do along the load path (member supports move with their
/// members' own load paths).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StructurePath {
    /// Sliders translated as λ goes from 0 to 1: (slider index, translation in m). Only the
    /// part across the slider's axis moves the vertex (it slides freely along the axis).
    pub sliders: Vec<(usize, Vec3)>,
    /// Twist holds turned about their edge as λ goes from 0 to 1: (hold index, angle in rad).
    pub holds: Vec<(usize, f64)>,
}

/// Several members joined at shared vertices, with sliders and twist holds (see the module
/// docs). Build it with [`StructureBuilder`](super::StructureBuilder).
#[derive(Clone, Debug)]
pub struct Structure {
    pub(super) members: Vec<Member>,
    pub(super) dofs: GlobalDofs,
    pub(super) joints: Vec<JointHinge>,
    /// Vertices identified by each joint: (member, vertex), the master first.
    pub(super) joint_groups: Vec<Vec<(usize, usize)>>,
    pub(super) sliders: Vec<SliderSupport>,
    pub(super) holds: Vec<TwistHold>,
    pub(super) hessian: AdaptiveMatrix,
    pub(super) rest: StructureState,
    pub(super) path: StructurePath,
}

/// What a structure-level term is evaluated at.
pub struct StructureContext<'a> {
    /// The structure.
    pub structure: &'a Structure,
    /// The state.
    pub state: &'a StructureState,
}

impl Structure {
    /// Where coordinate `k` of vertex `v` of member `m` goes among the structure's free DOFs
    /// (global DOF and coefficient; the DOF is [`FIXED`] when a support holds it).
    pub fn vertex_slot(&self, m: usize, v: usize, k: usize) -> crate::assembly::MapSlot {
        let own = self.members[m].vertex_dof(v, k);
        if own == FIXED {
            crate::assembly::MapSlot {
                dof: FIXED,
                coef: 0.0,
            }
        } else {
            self.dofs.maps[m][own]
        }
    }

    /// Where member `m`'s own free DOF `own` goes among the structure's free DOFs (global
    /// DOF and coefficient; the DOF is [`FIXED`] when a structure-level support drops it).
    pub fn member_dof(&self, m: usize, own: usize) -> crate::assembly::MapSlot {
        self.dofs.maps[m][own]
    }

    /// The members.
    pub fn members(&self) -> &[Member] {
        &self.members
    }

    /// Mutable access to member `m` (e.g. to set its load path).
    pub fn member_mut(&mut self, m: usize) -> &mut Member {
        &mut self.members[m]
    }

    /// The rest state.
    pub fn rest_state(&self) -> &StructureState {
        &self.rest
    }

    /// The sliders.
    pub fn sliders(&self) -> &[SliderSupport] {
        &self.sliders
    }

    /// The twist holds.
    pub fn holds(&self) -> &[TwistHold] {
        &self.holds
    }

    /// The joints: identified (member, vertex) pairs, master first.
    pub fn joints(&self) -> &[Vec<(usize, usize)>] {
        &self.joint_groups
    }

    /// True if the Hessian is stored banded (a single chain: the fast path).
    pub fn is_banded(&self) -> bool {
        matches!(self.hessian, AdaptiveMatrix::Band(_))
    }

    /// What the structure-level supports do along the load path.
    pub fn path(&self) -> &StructurePath {
        &self.path
    }

    /// Sets what the structure-level supports do along the load path (indices checked).
    pub fn set_path(&mut self, path: StructurePath) -> Result<(), crate::ModelError> {
        for &(k, t) in &path.sliders {
            if k >= self.sliders.len() || t.iter().any(|c| !c.is_finite()) {
                return Err(crate::ModelError::structure(
                    "path.sliders",
                    format!(
                        "slider {k}: must be < {} with a finite translation",
                        self.sliders.len()
                    ),
                ));
            }
        }
        for &(k, a) in &path.holds {
            if k >= self.holds.len() || !a.is_finite() {
                return Err(crate::ModelError::structure(
                    "path.holds",
                    format!(
                        "twist hold {k}: must be < {} with a finite angle",
                        self.holds.len()
                    ),
                ));
            }
        }
        self.path = path;
        Ok(())
    }

    /// Adds the joint hinges' generalized forces to the members' full gradients (see
    /// [`Rod::full_gradient`](crate::rod::Rod::full_gradient)): the forces supports at or
    /// next to a joint carry. Joints join discrete elastic rods only.
    pub fn add_joint_gradients(&self, state: &StructureState, out: &mut [super::HeldForces]) {
        use crate::assembly::{LocalDerivatives, StencilTerm, TermSet};
        fn der(h: &mut super::HeldForces) -> &mut crate::rod::FullGradient {
            match h {
                super::HeldForces::Der(g) => g,
                super::HeldForces::Framed(_) => unreachable!("joints join discrete elastic rods"),
            }
        }
        let ctx = StructureContext {
            structure: self,
            state,
        };
        for j in &self.joints {
            let mut g = nalgebra::SVector::<f64, 11>::zeros();
            let mut out_local = LocalDerivatives {
                energy: 0.0,
                magnitude: 0.0,
                grad: Some(&mut g),
                hess: None,
            };
            j.evaluate(&ctx, TermSet::ALL, &mut out_local);
            let [s0, s1] = j.sides;
            let slot = |a: usize| Vec3::new(g[a], g[a + 1], g[a + 2]);
            der(&mut out[s0.member]).vertices[s0.outer_vertex] += slot(0);
            der(&mut out[s0.member]).vertices[s0.joint_vertex] += slot(4);
            der(&mut out[s1.member]).vertices[s1.outer_vertex] += slot(8);
            der(&mut out[s0.member]).thetas[s0.edge] += g[3];
            der(&mut out[s1.member]).thetas[s1.edge] += g[7];
        }
        // A joint is one point: its forces are gathered on the master end's vertex.
        for group in &self.joint_groups {
            let (m0, v0) = group[0];
            for &(m, v) in &group[1..] {
                let f = std::mem::take(&mut der(&mut out[m]).vertices[v]);
                der(&mut out[m0]).vertices[v0] += f;
            }
        }
    }

    /// Moves slider `i` by `translation` (m) along the load path (replacing other slider
    /// motions).
    pub fn set_slider_motion(&mut self, i: usize, translation: Vec3) {
        self.path.sliders.clear();
        self.path.sliders.push((i, translation));
    }

    /// Turns twist hold `i` by `angle` (rad) along the load path.
    pub fn set_hold_motion(&mut self, i: usize, angle: f64) {
        self.path.holds.clear();
        self.path.holds.push((i, angle));
    }

    /// Clears every load path: the structure's and its members' (back to the plain ramp).
    pub fn clear_paths(&mut self) {
        self.path.sliders.clear();
        self.path.holds.clear();
        for m in self.members.iter_mut() {
            m.clear_load_path();
        }
    }

    /// Measures the joint hinges' reference twists afresh from the frames of `state` (after
    /// its members were rebuilt from snapshots with every material angle 0).
    pub fn reset_joint_twists(&self, state: &mut StructureState) {
        for (k, j) in self.joints.iter().enumerate() {
            state.joint_twists[k] = j.continued_twist(state, 0.0);
        }
    }

    /// Continues the joint hinges' reference twists from `previous` to the frames of `state`.
    fn continue_twists(&self, previous: &StructureState, state: &mut StructureState) {
        for (k, j) in self.joints.iter().enumerate() {
            state.joint_twists[k] = j.continued_twist(state, previous.joint_twists[k]);
        }
    }

    /// Re-adapts member `m`'s frames after its positions were changed in place.
    fn refresh(&self, state: &mut StructureState, m: usize) {
        if let (Member::Der(r), MemberState::Der(s)) = (&self.members[m], &mut state.members[m]) {
            r.refresh_frames(s);
        }
    }
}

impl MassMetric for Structure {
    fn inertia_metric(&self, i: usize) -> f64 {
        self.dofs.inertia[i]
    }

    fn eigenvalue_scale(&self) -> f64 {
        self.members
            .iter()
            .map(|m| m.eigenvalue_scale())
            .fold(f64::INFINITY, f64::min)
    }
}

impl EquilibriumProblem for Structure {
    type State = StructureState;
    type Hessian = AdaptiveMatrix;

    fn n_free(&self) -> usize {
        self.dofs.n_free
    }

    fn new_hessian(&self) -> AdaptiveMatrix {
        let mut h = self.hessian.clone();
        h.set_zero();
        h
    }

    fn term_groups(&self) -> &[TermGroup] {
        if self.members.iter().any(|m| m.as_der().is_none()) {
            &WITH_SHEAR
        } else {
            &ALL_GROUPS
        }
    }

    /// A structure of discrete elastic rods lags its hinges' (and joints') bending and
    /// twisting Hessians on the first step of a warm re-solve; other models assemble whole
    /// (their groups number differently).
    fn lagged_hessian_groups(&self) -> TermSet {
        if self.members.iter().all(|m| m.as_der().is_some()) {
            BENDING.set().with(TWISTING.set())
        } else {
            TermSet::NONE
        }
    }

    fn assemble_selected<M: SymmetricMatrix>(
        &self,
        state: &StructureState,
        load: f64,
        asm: &mut Assembler<'_, M>,
    ) {
        for (m, member) in self.members.iter().enumerate() {
            let mut part = asm.part(&self.dofs.maps[m]);
            member.assemble_into(&state.members[m], load, &mut part);
            let info = part.finish();
            asm.absorb(info);
        }
        let ctx = StructureContext {
            structure: self,
            state,
        };
        asm.terms(&ctx, &self.joints);
    }

    fn difference(&self, a: &StructureState, b: &StructureState, out: &mut [f64]) {
        out.fill(0.0);
        for (m, member) in self.members.iter().enumerate() {
            let map = &self.dofs.maps[m];
            member.difference(&a.members[m], &b.members[m], |i, d| {
                let s = map[i];
                if s.dof != FIXED {
                    out[s.dof] += s.coef * d / self.dofs.weight[s.dof];
                }
            });
        }
    }

    fn displace(&self, state: &StructureState, dx: &[f64], alpha: f64, out: &mut StructureState) {
        for (m, member) in self.members.iter().enumerate() {
            // The same values either way (coefficients of 1 multiply exactly); the slice
            // spares the map lookups of every DOF of every step.
            match self.dofs.offsets[m] {
                Some(o) => member.displace_slice(
                    &state.members[m],
                    &dx[o..o + member.n_free()],
                    alpha,
                    &mut out.members[m],
                ),
                None => member.displace_by(
                    &state.members[m],
                    |i| self.dofs.gather(m, i, dx),
                    alpha,
                    &mut out.members[m],
                ),
            }
        }
        self.continue_twists(state, out);
    }

    fn chart(&self, state: &StructureState, dx: &[f64], out: &mut StructureState) {
        for (m, member) in self.members.iter().enumerate() {
            member.chart_by(
                &state.members[m],
                |i| self.dofs.gather(m, i, dx),
                &mut out.members[m],
            );
        }
        self.continue_twists(state, out);
    }

    fn impose_load(&self, state: &mut StructureState, from: f64, to: f64, guess: bool) {
        for (m, member) in self.members.iter().enumerate() {
            member.impose_load(&mut state.members[m], from, to, guess);
        }
        let d = to - from;
        for &(k, t) in &self.path.sliders {
            let s = &self.sliders[k];
            let across = t - s.axis * s.axis.dot(&t);
            if let MemberState::Der(r) = &mut state.members[s.member] {
                r.translate_vertex(s.vertex, across * d);
            }
            self.refresh(state, s.member);
        }
        for &(k, angle) in &self.path.holds {
            let h = &self.holds[k];
            if let MemberState::Der(r) = &mut state.members[h.member] {
                r.turn_edge(h.edge, angle * d);
            }
        }
        // Identified vertices follow their joint's master (which may be held and moved).
        for group in &self.joint_groups {
            let (m0, v0) = group[0];
            let x = state.members[m0].positions()[v0];
            for &(m, v) in &group[1..] {
                if state.members[m].positions()[v] != x {
                    if let MemberState::Der(r) = &mut state.members[m] {
                        r.translate_vertex(v, x - r.positions()[v]);
                    }
                    self.refresh(state, m);
                }
            }
        }
        // Each twist is continued from its own previous value (in place: nothing allocated).
        for (k, j) in self.joints.iter().enumerate() {
            state.joint_twists[k] = j.continued_twist(state, state.joint_twists[k]);
        }
    }

    fn refresh_loads(&self, state: &mut StructureState) -> f64 {
        let mut change: f64 = 0.0;
        for (m, member) in self.members.iter().enumerate() {
            if let (Member::Der(r), MemberState::Der(s)) = (member, &mut state.members[m]) {
                change = change.max(r.refresh_loads(s));
            }
        }
        change
    }

    fn has_lagged_loads(&self) -> bool {
        self.members
            .iter()
            .any(|m| m.as_der().is_some_and(|r| r.has_follower_loads()))
    }

    fn lagged_loads(&self, state: &StructureState, out: &mut Vec<f64>) {
        out.clear();
        for (member, s) in self.members.iter().zip(&state.members) {
            if let (Member::Der(r), MemberState::Der(s)) = (member, s) {
                r.append_lagged_loads(s, out);
            }
        }
    }

    fn set_lagged_loads(&self, state: &mut StructureState, values: &[f64]) {
        let mut rest = values;
        for (member, s) in self.members.iter().zip(&mut state.members) {
            if let (Member::Der(r), MemberState::Der(s)) = (member, s) {
                rest = r.take_lagged_loads(s, rest);
            }
        }
    }

    fn merit_is_energy(&self) -> bool {
        // No `merit` override: the line search measures the energy itself.
        true
    }

    fn max_step(&self, state: &StructureState, dx: &[f64]) -> f64 {
        self.members
            .iter()
            .enumerate()
            .map(|(m, member)| match self.dofs.offsets[m] {
                Some(o) => member.max_step_slice(&state.members[m], &dx[o..o + member.n_free()]),
                None => member.max_step_by(&state.members[m], |i| self.dofs.gather(m, i, dx)),
            })
            .fold(1.0, f64::min)
    }

    fn force_length(&self, i: usize) -> f64 {
        let (m, local) = self.dofs.owner[i];
        self.members[m].force_length(local)
    }

    fn dof_magnitude(&self, state: &StructureState, i: usize) -> f64 {
        let (m, local) = self.dofs.owner[i];
        self.members[m].dof_magnitude(&state.members[m], local)
    }

    fn dof_scales(&self, state: &StructureState, force_length: &mut [f64], magnitude: &mut [f64]) {
        // Each global DOF takes its scales from its owner, as the per-DOF methods do.
        for (m, member) in self.members.iter().enumerate() {
            if let Some(o) = self.dofs.owned_offsets[m] {
                // Own DOF i is global DOF o + i, owned by this member: no lookups.
                let n = member.n_free();
                let (lengths, magnitudes) = (&mut force_length[o..o + n], &mut magnitude[o..o + n]);
                member.dof_scales_each(&state.members[m], |i, l, mag| {
                    lengths[i] = l;
                    magnitudes[i] = mag;
                });
                continue;
            }
            let map = &self.dofs.maps[m];
            member.dof_scales_each(&state.members[m], |i, l, mag| {
                let g = map[i].dof;
                if g != crate::assembly::FIXED && self.dofs.owner[g] == (m, i) {
                    force_length[g] = l;
                    magnitude[g] = mag;
                }
            });
        }
    }
}

#[cfg(feature = "testing")]
impl crate::testing::RigidMotion for Structure {
    fn rigidly_moved(
        &self,
        state: &StructureState,
        rotation: &nalgebra::Rotation3<f64>,
        offset: &Vec3,
    ) -> StructureState {
        StructureState {
            members: state
                .members
                .iter()
                .map(|m| match m {
                    MemberState::Der(s) => {
                        MemberState::Der(s.rigidly_transformed(rotation, offset))
                    }
                    MemberState::Framed(s) => {
                        MemberState::Framed(s.rigidly_transformed(rotation, offset))
                    }
                })
                .collect(),
            joint_twists: state.joint_twists.clone(),
        }
    }

    fn rest(&self) -> StructureState {
        self.rest.clone()
    }

    fn internal_terms(&self) -> crate::assembly::TermSet {
        crate::rod::groups::INTERNAL
    }
}
