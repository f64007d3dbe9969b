//! Bending and twist at one vertex of a discrete Cosserat rod: the discrete Darboux vector
//! g(q) of the relative rotation q = p̄_a p_b of the two neighbouring frames (edge frames, or a
//! clamp's frame and the first edge's), on the stencil [ω_a (3), ω_b (3)].
//!
//! Derivatives by the chain rule through the exact second-order expansion of q
//! ([`RelativeRotation`]) and the measure's own derivatives ([`DarbouxMeasure`]):
//! ∇E = J_qᵀ J_gᵀ f and ∇²E = J_qᵀ (J_gᵀ (C/h̄) J_g + Σ f_k ∇²g_k) J_q + Σ_m (J_gᵀ f)_m ∇²q_m,
//! with f = C (g − ḡ)/h̄.

use nalgebra::{Matrix3, SMatrix, Vector3};

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::framed::full_stencil::FullStencil;
use crate::framed::groups::{component_mask, BENDING, TWISTING};
use crate::framed::FramedState;
use crate::lie::{DarbouxMeasure, RelativeRotation};

use super::model::CosseratContext;

/// Which frame a vertex term reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameRef {
    /// The frame of edge j.
    Edge(usize),
    /// The frame a clamp holds at end 0 (s = 0) or 1 (s = L).
    Clamp(usize),
}

impl FrameRef {
    /// The frame in state `s`.
    pub fn of(self, s: &FramedState) -> nalgebra::UnitQuaternion<f64> {
        match self {
            Self::Edge(j) => s.frames[j],
            Self::Clamp(end) => s.clamp_frames[end].expect("a clamp holds this frame"),
        }
    }
}

/// Bending and twist at vertex `vertex`, between frames `frames.0` and `frames.1`.
#[derive(Clone, Debug)]
pub struct BendTwistTerm {
    pub(crate) vertex: usize,
    pub(crate) frames: (FrameRef, FrameRef),
    pub(crate) dofs: Stencil<6>,
    pub(crate) full: Stencil<6>,
    /// Distance h̄ (m) between the two frames along the rest rod.
    pub(crate) length: f64,
    /// (EI₂, EI₁, GJ): stiffness against rotation about d₁, d₂, d₃ (N m²).
    pub(crate) stiffness: [f64; 3],
    /// Rest Darboux vector ḡ (dimensionless, = h̄ K̄).
    pub(crate) rest: Vector3<f64>,
    pub(crate) measure: DarbouxMeasure,
}

impl BendTwistTerm {
    /// The Darboux vector g (dimensionless) in state `s`.
    pub fn darboux(&self, s: &FramedState) -> Vector3<f64> {
        let rel = RelativeRotation::new(&self.frames.0.of(s), &self.frames.1.of(s));
        self.measure.evaluate(&rel.q).value
    }
}

impl StencilTerm<CosseratContext<'_>, 6> for BendTwistTerm {
    fn groups(&self) -> TermSet {
        BENDING.set().with(TWISTING.set())
    }

    fn stencil(&self) -> &Stencil<6> {
        &self.dofs
    }

    fn evaluate(
        &self,
        ctx: &CosseratContext<'_>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, 6>,
    ) {
        let s = ctx.state;
        let rel = RelativeRotation::new(&self.frames.0.of(s), &self.frames.1.of(s));
        let map = self.measure.evaluate(&rel.q);
        let dg = map.value - self.rest;
        let mask = component_mask(selected);
        let c = Vector3::new(
            self.stiffness[0] * mask[3],
            self.stiffness[1] * mask[4],
            self.stiffness[2] * mask[5],
        );
        let hl = self.length;
        out.add_energy(0.5 * (c[0] * dg[0] * dg[0] + c[1] * dg[1] * dg[1]) / hl);
        out.add_energy(0.5 * c[2] * dg[2] * dg[2] / hl);
        if !out.wants_gradient() && !out.wants_hessian() {
            return;
        }
        let f = c.component_mul(&dg) / hl;
        let lambda = map.jac.transpose() * f;
        let jq = rel.jacobian();
        if let Some(g) = out.grad.as_deref_mut() {
            *g = jq.transpose() * lambda;
        }
        if let Some(h) = out.hess.as_deref_mut() {
            let cg = Matrix3::from_diagonal(&(c / hl)) * map.jac;
            let inner = map.jac.transpose() * cg + map.contracted_hessian(&f);
            let hq: SMatrix<f64, 6, 6> = rel.contracted_hessian(&lambda);
            *h = jq.transpose() * inner * jq + hq;
        }
    }
}

impl FullStencil<6> for BendTwistTerm {
    fn full_stencil(&self) -> &Stencil<6> {
        &self.full
    }
}
