//! One SE(3) beam element: the strain d/L₀ with d = log(H_A⁻¹ H_B) = (u, θ), θ the rotation
//! vector of R_Aᵀ R_B and u = W(θ) R_Aᵀ(x_B − x_A), on the stencil [x_A, ω_A, x_B, ω_B].
//!
//! With σ = C(d − d̄)/L₀ the gradient is J_dᵀσ and the Hessian
//! J_dᵀ (C/L₀) J_d + Σ σ_u,i ∇²u_i + Σ σ_θ,k ∇²θ_k, where
//! * ∇²θ_k comes from the relative rotation's expansion and the logarithm's derivatives;
//! * ∇²u_i = J_θᵀ ∂²u/∂θ² J_θ + J_θᵀ ∂²u/∂θ∂r J_r + transpose + Σ (∂u_i/∂θ_k) ∇²θ_k +
//!   Σ W_im ∇²r_m, with r = R_Aᵀ exp(−ω_A)(x_B − x_A + δx_B − δx_A) expanded to second
//!   order (as a Cosserat edge strain).

use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

use crate::assembly::{LocalDerivatives, Stencil, StencilTerm, TermSet};
use crate::framed::full_stencil::FullStencil;
use crate::framed::groups::{component_mask, BENDING, SHEAR, STRETCHING, TWISTING};
use crate::framed::FramedState;
use crate::geometry::cross_matrix;
use crate::lie::darboux::{rotation_log, rotation_log_value};
use crate::lie::quaternion::relative_quaternion;
use crate::lie::se3::{translation_log_value, TranslationLog};
use crate::lie::RelativeRotation;

use super::model::Se3Context;

/// Offsets in the stencil.
const XA: usize = 0;
const WA: usize = 3;
const XB: usize = 6;
const WB: usize = 9;

/// The element between nodes `element` and `element + 1`.
#[derive(Clone, Debug)]
pub struct Se3Element {
    pub(crate) element: usize,
    pub(crate) dofs: Stencil<12>,
    pub(crate) full: Stencil<12>,
    /// Rest length L₀ (m): the arc length of the rest curve between the nodes.
    pub(crate) rest_length: f64,
    /// (κGA₁, κGA₂, EA, EI₂, EI₁, GJ).
    pub(crate) stiffness: [f64; 6],
    /// Rest value d̄ of d (ε̄ L₀).
    pub(crate) rest: SVector<f64, 6>,
}

/// d = log(H_A⁻¹ H_B) of the element from node `j` to `j + 1` in state `s`.
pub fn element_twist(s: &FramedState, j: usize) -> SVector<f64, 6> {
    let q = relative_quaternion(&s.frames[j], &s.frames[j + 1]);
    let theta = rotation_log_value(&q);
    let r = s.frames[j].inverse() * (s.positions[j + 1] - s.positions[j]);
    let u = translation_log_value(&theta, &r);
    SVector::<f64, 6>::new(u[0], u[1], u[2], theta[0], theta[1], theta[2])
}

/// The chord x_B − x_A of element `j` after the step α dx in the retraction: the end frames
/// turned by the exponential map, the translational strain u moved by exactly α times its
/// linearization (δu = ∂u/∂θ δθ + W δr), and the chord rebuilt from them,
/// e = R_A′ V(θ′) u′. So the stiff shear and extension change linearly along the step, and an
/// element that moves rigidly keeps its strain.
pub(crate) fn chord_after_step(
    core: &crate::framed::FramedCore,
    s: &FramedState,
    dx: &[f64],
    alpha: f64,
    j: usize,
) -> Vector3<f64> {
    let (pa, pb) = (s.frames[j], s.frames[j + 1]);
    let wa = core.frame_step(dx, j, alpha);
    let wb = core.frame_step(dx, j + 1, alpha);
    let de = core.vertex_step(dx, j + 1, alpha) - core.vertex_step(dx, j, alpha);
    let e = s.positions[j + 1] - s.positions[j];
    let rel = RelativeRotation::new(&pa, &pb);
    let lg = rotation_log(&rel.q);
    let r = pa.inverse() * e;
    let tl = TranslationLog::new(&lg.value, &r);
    let mut w6 = SVector::<f64, 6>::zeros();
    w6.fixed_rows_mut::<3>(0).copy_from(&wa);
    w6.fixed_rows_mut::<3>(3).copy_from(&wb);
    let dtheta = lg.jac * (rel.jacobian() * w6);
    let dr = pa.inverse() * (de + e.cross(&wa));
    let u = tl.u + tl.du_dtheta * dtheta + tl.w * dr;
    let pa2 = nalgebra::UnitQuaternion::from_scaled_axis(wa) * pa;
    let pb2 = nalgebra::UnitQuaternion::from_scaled_axis(wb) * pb;
    let theta2 = rotation_log_value(&relative_quaternion(&pa2, &pb2));
    pa2 * (crate::lie::se3::v_matrix(&theta2) * u)
}

fn add3(h: &mut SMatrix<f64, 12, 12>, r0: usize, c0: usize, m: &Matrix3<f64>) {
    let mut v = h.fixed_view_mut::<3, 3>(r0, c0);
    v += m;
}

impl StencilTerm<Se3Context<'_>, 12> for Se3Element {
    fn groups(&self) -> TermSet {
        SHEAR
            .set()
            .with(STRETCHING.set())
            .with(BENDING.set())
            .with(TWISTING.set())
    }

    fn stencil(&self) -> &Stencil<12> {
        &self.dofs
    }

    fn evaluate(
        &self,
        ctx: &Se3Context<'_>,
        selected: TermSet,
        out: &mut LocalDerivatives<'_, 12>,
    ) {
        let s = ctx.state;
        let j = self.element;
        let mask = component_mask(selected);
        let l0 = self.rest_length;
        let c = SVector::<f64, 6>::from_fn(|k, _| self.stiffness[k] * mask[k]);
        let add_parts = |out: &mut LocalDerivatives<'_, 12>, dd: &SVector<f64, 6>| {
            let part =
                |a: usize, b: usize| (a..b).map(|k| c[k] * dd[k] * dd[k]).sum::<f64>() / (2.0 * l0);
            out.add_energy(part(0, 2));
            out.add_energy(part(2, 3));
            out.add_energy(part(3, 5));
            out.add_energy(part(5, 6));
        };
        if !out.wants_gradient() && !out.wants_hessian() {
            // Energy only (line searches): the logarithms without their derivatives.
            add_parts(out, &(element_twist(s, j) - self.rest));
            return;
        }
        let (pa, pb) = (s.frames[j], s.frames[j + 1]);
        let ra = pa.to_rotation_matrix().into_inner();
        let rel = RelativeRotation::new(&pa, &pb);
        let lg = rotation_log(&rel.q);
        let theta = lg.value;
        let e = s.positions[j + 1] - s.positions[j];
        let r = ra.transpose() * e;
        let tl = TranslationLog::new(&theta, &r);
        let d = SVector::<f64, 6>::new(tl.u[0], tl.u[1], tl.u[2], theta[0], theta[1], theta[2]);
        let dd = d - self.rest;
        let mask = component_mask(selected);
        let l0 = self.rest_length;
        let c = SVector::<f64, 6>::from_fn(|k, _| self.stiffness[k] * mask[k]);
        let part =
            |a: usize, b: usize| (a..b).map(|k| c[k] * dd[k] * dd[k]).sum::<f64>() / (2.0 * l0);
        out.add_energy(part(0, 2));
        out.add_energy(part(2, 3));
        out.add_energy(part(3, 5));
        out.add_energy(part(5, 6));
        if !out.wants_gradient() && !out.wants_hessian() {
            return;
        }
        let sigma = c.component_mul(&dd) / l0;
        let sigma_u = Vector3::new(sigma[0], sigma[1], sigma[2]);
        let sigma_t = Vector3::new(sigma[3], sigma[4], sigma[5]);
        // d = (u, θ) depends on the slots through p = (θ, r): d = M-linear to first order with
        // M = [[∂u/∂θ, W], [I, 0]]; J_p (6×12) holds J_θ (rotation slots) and J_r.
        let jq = rel.jacobian();
        let jt6: SMatrix<f64, 3, 6> = lg.jac * jq;
        let rat = ra.transpose();
        let mut jp = SMatrix::<f64, 6, 12>::zeros();
        jp.fixed_view_mut::<3, 3>(0, WA)
            .copy_from(&jt6.fixed_view::<3, 3>(0, 0));
        jp.fixed_view_mut::<3, 3>(0, WB)
            .copy_from(&jt6.fixed_view::<3, 3>(0, 3));
        jp.fixed_view_mut::<3, 3>(3, XA).copy_from(&(-rat));
        jp.fixed_view_mut::<3, 3>(3, WA)
            .copy_from(&(rat * cross_matrix(&e)));
        jp.fixed_view_mut::<3, 3>(3, XB).copy_from(&rat);
        // λ = Mᵀσ: the weights of the second derivatives of θ and r.
        let lambda_t = sigma_t + tl.du_dtheta.transpose() * sigma_u;
        let lambda_r = tl.w.transpose() * sigma_u;
        if let Some(g) = out.grad.as_deref_mut() {
            let mut lam = SVector::<f64, 6>::zeros();
            lam.fixed_rows_mut::<3>(0).copy_from(&lambda_t);
            lam.fixed_rows_mut::<3>(3).copy_from(&lambda_r);
            *g = jp.transpose() * lam;
        }
        if let Some(h) = out.hess.as_deref_mut() {
            // K = Mᵀ (C/L₀) M + [[Σσ_u ∂²u/∂θ², Σσ_u ∂²u/∂θ∂r], [·ᵀ, 0]].
            let mut m = SMatrix::<f64, 6, 6>::zeros();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&tl.du_dtheta);
            m.fixed_view_mut::<3, 3>(0, 3).copy_from(&tl.w);
            m.fixed_view_mut::<3, 3>(3, 0)
                .copy_from(&Matrix3::identity());
            let cm = SMatrix::<f64, 6, 6>::from_diagonal(&(c / l0)) * m;
            let mut k = m.transpose() * cm;
            let (s_tt, s_tr) = tl.contracted(&sigma_u);
            {
                let mut v = k.fixed_view_mut::<3, 3>(0, 0);
                v += s_tt;
            }
            {
                let mut v = k.fixed_view_mut::<3, 3>(0, 3);
                v += s_tr;
            }
            {
                let mut v = k.fixed_view_mut::<3, 3>(3, 0);
                v += s_tr.transpose();
            }
            // Jₚᵀ K Jₚ by 3×3 blocks: the slot columns of Jₚ are (θ, r) = XA (0, −Rᵀ),
            // WA (T_A, Rᵀ[e]×), XB (0, Rᵀ), WB (T_B, 0); XB's blocks are −XA's.
            let ktt: Matrix3<f64> = k.fixed_view::<3, 3>(0, 0).into_owned();
            let ktr: Matrix3<f64> = k.fixed_view::<3, 3>(0, 3).into_owned();
            let krt: Matrix3<f64> = k.fixed_view::<3, 3>(3, 0).into_owned();
            let krr: Matrix3<f64> = k.fixed_view::<3, 3>(3, 3).into_owned();
            let ta: Matrix3<f64> = jt6.fixed_view::<3, 3>(0, 0).into_owned();
            let tb: Matrix3<f64> = jt6.fixed_view::<3, 3>(0, 3).into_owned();
            let b = rat * cross_matrix(&e);
            let (kxa_t, kxa_r) = (-(ktr * rat), -(krr * rat));
            let (kwa_t, kwa_r) = (ktt * ta + ktr * b, krt * ta + krr * b);
            let kwb_t = ktt * tb;
            let xa_xa = -(ra * kxa_r);
            let wa_xa = ta.transpose() * kxa_t + b.transpose() * kxa_r;
            let wb_xa = tb.transpose() * kxa_t;
            let wa_wa = ta.transpose() * kwa_t + b.transpose() * kwa_r;
            let wb_wa = tb.transpose() * kwa_t;
            let wb_wb = tb.transpose() * kwb_t;
            let xa_wa = -(ra * kwa_r);
            let blocks = [
                (XA, XA, xa_xa),
                (WA, XA, wa_xa),
                (XB, XA, -xa_xa),
                (WB, XA, wb_xa),
                (WA, WA, wa_wa),
                (XB, WA, -xa_wa),
                (WB, WA, wb_wa),
                (XB, XB, xa_xa),
                (WB, XB, -wb_xa),
                (WB, WB, wb_wb),
            ];
            for (r0, c0, m) in blocks {
                h.fixed_view_mut::<3, 3>(r0, c0).copy_from(&m);
                if r0 != c0 {
                    h.fixed_view_mut::<3, 3>(c0, r0).copy_from(&m.transpose());
                }
            }
            // Σ λ_θ,k ∇²θ_k on the rotation slots.
            let lambda_q = lg.jac.transpose() * lambda_t;
            let h6 = jq.transpose() * lg.contracted_hessian(&lambda_t) * jq
                + rel.contracted_hessian(&lambda_q);
            for (a, oa) in [(0, WA), (3, WB)] {
                for (b, ob) in [(0, WA), (3, WB)] {
                    let m: Matrix3<f64> = h6.fixed_view::<3, 3>(a, b).into_owned();
                    add3(h, oa, ob, &m);
                }
            }
            // Σ λ_r,m ∇²r_m: r depends on ω_A and the positions only.
            let big_l = ra * lambda_r;
            let le = big_l * e.transpose();
            let ww = (le + le.transpose()) * 0.5 - Matrix3::identity() * big_l.dot(&e);
            let xw = cross_matrix(&big_l);
            add3(h, WA, WA, &ww);
            add3(h, XA, WA, &xw);
            add3(h, WA, XA, &xw.transpose());
            add3(h, XB, WA, &(-xw));
            add3(h, WA, XB, &(-xw.transpose()));
        }
    }
}

impl FullStencil<12> for Se3Element {
    fn full_stencil(&self) -> &Stencil<12> {
        &self.full
    }
}
