//! What the inertial term needs to know about a model's DOFs: which are plain coordinates
//! and which turn material frames on SO(3).

use nalgebra::{UnitQuaternion, Vector3};

use crate::assembly::FIXED;
use crate::framed::FramedModel;
use crate::rod::Rod;
use crate::solver::EquilibriumProblem;
use crate::structure::{Member, MemberState, Structure};

use super::frames::FrameInertia;

/// A model the time stepper can integrate: its DOFs are plain coordinates in its chart
/// (`difference(chart(b, d), b) = d` exactly: positions, the discrete elastic rod's edge
/// angles), except the rotation DOFs of the frames it lists in [`Self::frames`].
///
/// On a coordinate the inertial term ‖y ⊖ xₙ − τ vₙ‖²_M/(2τ²) has the exact gradient
/// M(y ⊖ xₙ − τ vₙ)/τ² and Hessian M/τ² in the chart the model's derivatives are taken in. A
/// frame's rotation is measured by a log map from xₙ, whose derivative in the models' chart
/// (spatial increments) is dexp⁻¹, not the identity, and its inertia turns with it: the step
/// differentiates both exactly (see [`IncrementalProblem`](super::IncrementalProblem)), for
/// which it needs the frames' DOFs, principal moments and orientations.
pub trait FlatDofs: EquilibriumProblem {
    /// True if every DOF is a coordinate (the model has no frames).
    fn has_flat_dofs(&self) -> bool;

    /// The frames whose rotations are DOFs (at least one free component), in a fixed order,
    /// with their principal moments of inertia. Default: none.
    fn frames(&self) -> Vec<FrameInertia> {
        Vec::new()
    }

    /// Replaces `out` by the orientations of [`Self::frames`] in `state`, in the same order.
    /// Default: none.
    fn frame_orientations(&self, state: &Self::State, out: &mut Vec<UnitQuaternion<f64>>) {
        let _ = state;
        out.clear();
    }
}

impl FlatDofs for Rod {
    fn has_flat_dofs(&self) -> bool {
        true
    }
}

/// Principal moments of inertia (kg m²) of a slice of length `length` (m) of a section with
/// stiffnesses `s` and mass per length `rho_a` (kg/m): ρA·(I₂, I₁, I₁ + I₂)/A·ℓ about
/// (d₁, d₂, d₃), with Iₖ/A = EIₖ/EA (one material). EI₂ resists rotation about d₁, EI₁ about
/// d₂ (see [`SectionStiffness`](crate::rod::SectionStiffness)); about d₃ the polar moment
/// I₁ + I₂ (not the torsion constant J of GJ, which equals it for a circle only).
fn slice_moments(s: &crate::rod::SectionStiffness, rho_a: f64, length: f64) -> Vector3<f64> {
    let per_length = rho_a * length / s.ea;
    Vector3::new(s.ei2, s.ei1, s.ei1 + s.ei2) * per_length
}

/// The frames of a framed model whose rotation is free in at least one component, with the
/// free DOFs mapped by `dof` (own index → free index of the whole, [`FIXED`] when dropped).
fn framed_frames<T: FramedModel>(r: &T, dof: impl Fn(usize) -> usize) -> Vec<FrameInertia> {
    let core = r.core();
    let p = core.properties();
    (0..core.dofs().n_frames())
        .filter_map(|j| {
            let dofs = core
                .dofs()
                .frame_slots(j)
                .map(|i| if i == FIXED { FIXED } else { dof(i) });
            (dofs.iter().any(|&i| i != FIXED)).then(|| FrameInertia {
                dofs,
                principal: slice_moments(&p.stiffness, p.linear_density, core.frame_lengths[j]),
            })
        })
        .collect()
}

impl<T: FramedModel> FlatDofs for T {
    fn has_flat_dofs(&self) -> bool {
        false
    }

    fn frames(&self) -> Vec<FrameInertia> {
        framed_frames(self, |i| i)
    }

    fn frame_orientations(&self, state: &Self::State, out: &mut Vec<UnitQuaternion<f64>>) {
        out.clear();
        let dofs = self.core().dofs();
        for j in 0..dofs.n_frames() {
            if dofs.frame_slots(j).iter().any(|&i| i != FIXED) {
                out.push(state.frames()[j]);
            }
        }
    }
}

impl FlatDofs for Structure {
    /// A structure is flat when all its members are discrete elastic rods.
    fn has_flat_dofs(&self) -> bool {
        self.members().iter().all(|m| matches!(m, Member::Der(_)))
    }

    /// The frames of its Cosserat and SE(3) members, member by member.
    fn frames(&self) -> Vec<FrameInertia> {
        let mut out = Vec::new();
        for (m, member) in self.members().iter().enumerate() {
            let map = |i: usize| self.frame_dof(m, i);
            let frames = match member {
                Member::Der(_) => continue,
                Member::Cosserat(r) => framed_frames(r, map),
                Member::Se3(r) => framed_frames(r, map),
            };
            out.extend(frames);
        }
        out
    }

    fn frame_orientations(&self, state: &Self::State, out: &mut Vec<UnitQuaternion<f64>>) {
        out.clear();
        for (m, member) in self.members().iter().enumerate() {
            let (MemberState::Framed(s), Some(core)) = (&state.members[m], member.as_framed())
            else {
                continue;
            };
            let dofs = core.dofs();
            for j in 0..dofs.n_frames() {
                let slots = dofs.frame_slots(j);
                if slots
                    .iter()
                    .any(|&i| i != FIXED && self.frame_dof(m, i) != FIXED)
                {
                    out.push(s.frames()[j]);
                }
            }
        }
    }
}

/// The structure's free DOF that member `m`'s own rotation DOF `own` is.
trait FrameDof {
    fn frame_dof(&self, m: usize, own: usize) -> usize;
}

impl FrameDof for Structure {
    /// Framed members are never joined (joints, sliders and twist holds take discrete elastic
    /// rods only), so their DOFs map one to one with coefficient 1. A rotation DOF that did
    /// not (a tie) would not be one frame's rotation: it is left out of the frame.
    fn frame_dof(&self, m: usize, own: usize) -> usize {
        let slot = self.member_dof(m, own);
        if slot.coef == 1.0 {
            slot.dof
        } else {
            FIXED
        }
    }
}
