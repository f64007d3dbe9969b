//! Joint hinges: bending and twisting carried across a joint between two members, as if the
//! cable continued through it (a splice, a branch point, the closure of a ring).
//!
//! A joint hinge is a discrete-elastic-rod hinge (`rod/hinge.rs`, `bending.rs`, `twisting.rs`)
//! between an edge of one member ending at the joint and an edge of another starting there. An
//! edge stored in the opposite direction is seen *reversed* by the hinge: tangent −t, the same
//! reference director a₁, material angle −θ (its material frame is then (m₁, −m₂, −t), still
//! right-handed, and parallel transport along t and along −t agree). Its reference twist is the
//! structure's, continued after every step like a rod's. Rest curvature and twist are those of
//! the rest state, so a branch at an angle is stress-free at rest.

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::rod::bending::BendingHinge;
use crate::rod::frames::{updated_ref_twist, EdgeFrame, EdgeId};
use crate::rod::groups::{BENDING, TWISTING};
use crate::rod::hinge::{EdgeHessian, HingeFrame, HingeState, HINGE_DOFS};
use crate::rod::twisting::TwistingHinge;

use super::member::MemberState;
use super::model::{StructureContext, StructureState};

/// One side of a joint hinge: an edge of a member at the joint vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HingeSide {
    /// Member index.
    pub member: usize,
    /// The edge.
    pub edge: usize,
    /// The joint vertex (an end of the edge).
    pub joint_vertex: usize,
    /// The edge's other vertex.
    pub outer_vertex: usize,
    /// +1 if the edge is stored in the hinge's direction (into the joint on side 0, out of it
    /// on side 1), −1 if reversed.
    pub sign: f64,
}

/// A joint hinge (a term of the bending and twisting groups on 11 global DOFs).
#[derive(Clone, Debug)]
pub struct JointHinge {
    /// Index of its reference twist in the structure state.
    pub(super) index: usize,
    /// Incoming side (0) and outgoing side (1).
    pub(super) sides: [HingeSide; 2],
    /// Global free DOF of each slot: [x_outer0, θ0, x_joint, θ1, x_outer1].
    pub(super) dofs: Stencil<HINGE_DOFS>,
    /// Bending stiffness and rest curvature.
    pub(super) bending: BendingHinge,
    /// Torsional stiffness and rest twist.
    pub(super) twisting: TwistingHinge,
}

fn rod_state(s: &MemberState) -> &crate::rod::RodState {
    s.as_der().expect("joint hinges join discrete elastic rods")
}

impl JointHinge {
    /// The edge frame of side `k` as the hinge sees it.
    fn frame(&self, state: &StructureState, k: usize) -> EdgeFrame {
        let side = self.sides[k];
        let f = rod_state(&state.members[side.member])
            .frames()
            .edge(EdgeId::Real(side.edge));
        EdgeFrame {
            tangent: f.tangent * side.sign,
            a1: f.a1,
        }
    }

    /// The hinge's state (positions, hinge-view directors and angles, reference twist).
    pub(super) fn hinge_state(&self, state: &StructureState) -> HingeState {
        let [s0, s1] = self.sides;
        let r0 = rod_state(&state.members[s0.member]);
        let r1 = rod_state(&state.members[s1.member]);
        HingeState {
            x: [
                r0.positions()[s0.outer_vertex],
                r0.positions()[s0.joint_vertex],
                r1.positions()[s1.outer_vertex],
            ],
            a1: [self.frame(state, 0).a1, self.frame(state, 1).a1],
            theta: [
                r0.thetas()[s0.edge] * s0.sign,
                r1.thetas()[s1.edge] * s1.sign,
            ],
            ref_twist: state.joint_twists[self.index],
            edges: [None, None],
        }
    }

    /// The reference twist continued from `previous` to the frames of `state`.
    pub(super) fn continued_twist(&self, state: &StructureState, previous: f64) -> f64 {
        updated_ref_twist(&self.frame(state, 0), &self.frame(state, 1), previous)
    }
}

impl<'a> StencilTerm<StructureContext<'a>, HINGE_DOFS> for JointHinge {
    fn groups(&self) -> TermSet {
        BENDING.set().with(TWISTING.set())
    }

    fn stencil(&self) -> &Stencil<HINGE_DOFS> {
        &self.dofs
    }

    const OVERWRITES_HESSIAN: bool = true;

    fn evaluate(
        &self,
        ctx: &StructureContext<'a>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, HINGE_DOFS>,
    ) {
        let hs = self.hinge_state(ctx.state);
        let frame = HingeFrame::new(&hs);
        let mut edge = EdgeHessian::default();
        let want_hess = out.hess.is_some();
        if selected.contains(BENDING) {
            let e = self.bending.energy(
                &frame,
                out.grad.as_deref_mut(),
                want_hess.then_some(&mut edge),
            );
            out.add_energy(e);
        }
        if selected.contains(TWISTING) {
            let e = self.twisting.energy(
                &frame,
                hs.twist(),
                out.grad.as_deref_mut(),
                want_hess.then_some(&mut edge),
            );
            out.add_energy(e);
        }
        if let Some(h) = out.hess.as_deref_mut() {
            edge.write_into(h);
        }
        // The hinge's angles are ±θ of the stored edges: chain rule on slots 3 and 7.
        for (slot, sign) in [(3, self.sides[0].sign), (7, self.sides[1].sign)] {
            if sign < 0.0 {
                if let Some(g) = out.grad.as_deref_mut() {
                    g[slot] = -g[slot];
                }
                if let Some(h) = out.hess.as_deref_mut() {
                    for c in 0..HINGE_DOFS {
                        h[(slot, c)] = -h[(slot, c)];
                    }
                    for r in 0..HINGE_DOFS {
                        h[(r, slot)] = -h[(r, slot)];
                    }
                }
            }
        }
    }
}
