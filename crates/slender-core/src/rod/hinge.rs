//! The hinge stencil shared by bending and twisting: a vertex with its two adjacent edges.
//!
//! A hinge touches 11 degrees of freedom, ordered as in the global vector:
//! `[x_{i−1} (3), θ^{e} (1), x_i (3), θ^{f} (1), x_{i+1} (3)]` with e = x_i − x_{i−1} and
//! f = x_{i+1} − x_i. At a clamp one of the edges is the clamp's fixed ghost edge.
//!
//! Derivatives are taken with the reference frames *just transported* to the current
//! positions (time-parallel frames, Bergou et al. 2010): the formulas below are the exact
//! gradient and Hessian of the energy in that setting (checked by finite differences in
//! `tests/derivatives.rs`).

use nalgebra::{Matrix3, SMatrix, SVector};

use crate::geometry::Vec3;

/// Number of degrees of freedom in a hinge stencil.
pub const HINGE_DOFS: usize = 11;
/// Gradient of a scalar over a hinge stencil.
pub type HingeVector = SVector<f64, HINGE_DOFS>;
/// Hessian of a scalar over a hinge stencil.
pub type HingeMatrix = SMatrix<f64, HINGE_DOFS, HINGE_DOFS>;

/// Offsets of the three vertices in the stencil.
const VERTEX_OFFSET: [usize; 3] = [0, 4, 8];
/// Offsets of the two edge angles in the stencil.
const THETA_OFFSET: [usize; 2] = [3, 7];
/// d e / d x_a for the three vertices (e = x₁ − x₀).
const DE_DX: [f64; 3] = [-1.0, 1.0, 0.0];
/// d f / d x_a for the three vertices (f = x₂ − x₁).
const DF_DX: [f64; 3] = [0.0, -1.0, 1.0];

/// The state of one hinge: three vertices, the two edges' reference directions a₁ (adapted to
/// the current tangents), twist angles θ (rad) and the reference twist (rad) between them.
#[derive(Clone, Copy, Debug)]
pub struct HingeState {
    /// Positions x_{i−1}, x_i, x_{i+1} (m).
    pub x: [Vec3; 3],
    /// Reference directions a₁ of edges e and f (unit, ⊥ to their tangents).
    pub a1: [Vec3; 2],
    /// Material angles θ of edges e and f (rad).
    pub theta: [f64; 2],
    /// Reference twist (rad): signed angle about t_f from the transport of a₁ᵉ to a₁ᶠ.
    pub ref_twist: f64,
    /// Unit tangent and length of edges e and f when already measured (a rod's real edges,
    /// from its frames); `None`: [`HingeFrame::new`] measures them from `x`, the same way.
    pub edges: [Option<(Vec3, super::frames::EdgeLength)>; 2],
}

impl HingeState {
    /// Twist strain m = θᶠ − θᵉ + m_ref (rad).
    pub fn twist(&self) -> f64 {
        self.theta[1] - self.theta[0] + self.ref_twist
    }
}

/// Quantities derived once per hinge and shared by the curvature and twist formulas.
#[derive(Clone, Copy, Debug)]
pub struct HingeFrame {
    /// Edge lengths |e|, |f| (m).
    pub len: [f64; 2],
    /// Their reciprocals 1/|e|, 1/|f| (1/m): the derivatives divide by them many times, and a
    /// multiplication costs a fraction of a division.
    pub inv_len: [f64; 2],
    /// Unit tangents t_e, t_f.
    pub t: [Vec3; 2],
    /// χ = 1 + t_e·t_f.
    pub chi: f64,
    /// 1/χ.
    pub inv_chi: f64,
    /// Curvature binormal κb = 2 t_e × t_f / χ (dimensionless, |κb| = 2 tan(φ/2)).
    pub kb: Vec3,
    /// t̃ = (t_e + t_f)/χ.
    pub t_tilde: Vec3,
    /// Material directors m₁ of e and f.
    pub m1: [Vec3; 2],
    /// Material directors m₂ of e and f.
    pub m2: [Vec3; 2],
}

impl HingeFrame {
    /// Derives the frame quantities of a hinge state.
    pub fn new(s: &HingeState) -> Self {
        let measure = |k: usize| {
            s.edges[k].unwrap_or_else(|| {
                let (length, t) = super::frames::EdgeLength::of(&(s.x[k + 1] - s.x[k]));
                (t, length)
            })
        };
        let [(t0, l0), (t1, l1)] = [measure(0), measure(1)];
        let len = [l0.length, l1.length];
        let inv_len = [l0.inv_length, l1.inv_length];
        let t = [t0, t1];
        let chi = 1.0 + t[0].dot(&t[1]);
        let inv_chi = 1.0 / chi;
        let kb = t[0].cross(&t[1]) * (2.0 * inv_chi);
        let mut m1 = [Vec3::zeros(); 2];
        let mut m2 = [Vec3::zeros(); 2];
        for k in 0..2 {
            let a2 = t[k].cross(&s.a1[k]);
            let (sin, cos) = crate::geometry::sin_cos(s.theta[k]);
            m1[k] = s.a1[k] * cos + a2 * sin;
            m2[k] = a2 * cos - s.a1[k] * sin;
        }
        Self {
            len,
            inv_len,
            t,
            chi,
            inv_chi,
            kb,
            t_tilde: (t[0] + t[1]) * inv_chi,
            m1,
            m2,
        }
    }
}

/// First derivatives of a hinge scalar with respect to (e, f, θ_e, θ_f): the 8 edge-space
/// variables every hinge energy depends on, chained to the 11 stencil DOFs by
/// [`Self::add_scaled_into`].
#[derive(Clone, Copy, Debug, Default)]
pub struct EdgeGradient {
    /// ∂/∂e.
    pub e: Vec3,
    /// ∂/∂f.
    pub f: Vec3,
    /// ∂/∂θ_e, ∂/∂θ_f.
    pub theta: [f64; 2],
}

impl EdgeGradient {
    /// Adds `w` times this gradient, chained to the stencil DOFs, into `g`.
    pub fn add_scaled_into(&self, g: &mut HingeVector, w: f64) {
        let (e, f) = (self.e * w, self.f * w);
        for a in 0..3 {
            let v = e * DE_DX[a] + f * DF_DX[a];
            let ra = VERTEX_OFFSET[a];
            for c in 0..3 {
                g[ra + c] += v[c];
            }
        }
        g[THETA_OFFSET[0]] += w * self.theta[0];
        g[THETA_OFFSET[1]] += w * self.theta[1];
    }
}

/// Second derivatives of a hinge scalar with respect to (e, f, θ_e, θ_f).
///
/// Every hinge term gathers its whole Hessian here — the Gauss–Newton part w ∇s ∇sᵀ of each
/// strain s ([`Self::add_outer`]) and the strain-curvature part w ∇²s — and the sum is chained
/// to the 11 stencil DOFs once ([`Self::scatter_into`]): the edge space has 8 variables, so an
/// outer product there costs 36 products instead of the stencil's 66.
#[derive(Clone, Copy, Debug, Default)]
pub struct EdgeHessian {
    /// ∂²/∂e².
    pub ee: Matrix3<f64>,
    /// ∂²/∂e∂f (row e, column f).
    pub ef: Matrix3<f64>,
    /// ∂²/∂f².
    pub ff: Matrix3<f64>,
    /// ∂²/∂e∂θ_k for k = e, f.
    pub e_theta: [Vec3; 2],
    /// ∂²/∂f∂θ_k for k = e, f.
    pub f_theta: [Vec3; 2],
    /// ∂²/∂θ_k² for k = e, f.
    pub theta_theta: [f64; 2],
    /// ∂²/∂θ_e∂θ_f (zero in the strains' own second derivatives; the Gauss–Newton part of a
    /// strain that depends on both angles fills it).
    pub theta_ef: f64,
}

impl EdgeHessian {
    /// Adds the outer product `w` g gᵀ (the Gauss–Newton part of a strain with gradient g).
    pub fn add_outer(&mut self, w: f64, g: &EdgeGradient) {
        let (we, wf) = (g.e * w, g.f * w);
        self.ee += we * g.e.transpose();
        self.ef += we * g.f.transpose();
        self.ff += wf * g.f.transpose();
        for k in 0..2 {
            self.e_theta[k] += we * g.theta[k];
            self.f_theta[k] += wf * g.theta[k];
            self.theta_theta[k] += w * g.theta[k] * g.theta[k];
        }
        self.theta_ef += w * g.theta[0] * g.theta[1];
    }

    /// Writes these edge-space second derivatives, chained to the stencil DOFs, into `h`:
    /// every entry of `h` is set (so the assembler need not zero it first, see
    /// [`StencilTerm::OVERWRITES_HESSIAN`](crate::assembly::StencilTerm::OVERWRITES_HESSIAN)).
    ///
    /// With e = x₁ − x₀ and f = x₂ − x₁ the vertex blocks are
    /// (0,0) = ee, (0,1) = ef − ee, (0,2) = −ef, (1,1) = ee − ef − fe + ff, (1,2) = ef − ff,
    /// (2,2) = ff (and their transposes).
    pub fn write_into(&self, h: &mut HingeMatrix) {
        let fe = self.ef.transpose();
        let blocks = [
            (0, 0, self.ee),
            (0, 1, self.ef - self.ee),
            (0, 2, -self.ef),
            (1, 1, self.ee - self.ef - fe + self.ff),
            (1, 2, self.ef - self.ff),
            (2, 2, self.ff),
        ];
        for (a, b, block) in blocks {
            let (ra, rb) = (VERTEX_OFFSET[a], VERTEX_OFFSET[b]);
            h.fixed_view_mut::<3, 3>(ra, rb).copy_from(&block);
            if a != b {
                h.fixed_view_mut::<3, 3>(rb, ra)
                    .copy_from(&block.transpose());
            }
        }
        for (k, &tk) in THETA_OFFSET.iter().enumerate() {
            for a in 0..3 {
                let v = self.e_theta[k] * DE_DX[a] + self.f_theta[k] * DF_DX[a];
                let ra = VERTEX_OFFSET[a];
                for c in 0..3 {
                    h[(ra + c, tk)] = v[c];
                    h[(tk, ra + c)] = v[c];
                }
            }
            h[(tk, tk)] = self.theta_theta[k];
        }
        let (t0, t1) = (THETA_OFFSET[0], THETA_OFFSET[1]);
        h[(t0, t1)] = self.theta_ef;
        h[(t1, t0)] = self.theta_ef;
    }
}

/// A hinge of the rod, one term of the bending and twisting groups: its vertex, the two edges
/// it joins (a clamp's ghost edge on one side at a clamp), its stencil and its stiffness data.
#[derive(Clone, Debug)]
pub struct Hinge {
    /// Position in the rod's hinge list (indexes the reference twists).
    pub(super) index: usize,
    /// The shared vertex.
    pub(super) vertex: usize,
    /// The two edges, in the direction of the rod.
    pub(super) edges: (super::frames::EdgeId, super::frames::EdgeId),
    /// Free DOF of each stencil slot.
    pub(super) dofs: crate::assembly::Stencil<HINGE_DOFS>,
    /// Bending stiffness and rest curvature.
    pub(super) bending: super::bending::BendingHinge,
    /// Torsional stiffness and rest twist.
    pub(super) twisting: super::twisting::TwistingHinge,
}

impl<'a> crate::assembly::StencilTerm<super::model::RodContext<'a>, HINGE_DOFS> for Hinge {
    fn groups(&self) -> crate::assembly::TermSet {
        super::groups::BENDING
            .set()
            .with(super::groups::TWISTING.set())
    }

    fn stencil(&self) -> &crate::assembly::Stencil<HINGE_DOFS> {
        &self.dofs
    }

    const OVERWRITES_HESSIAN: bool = true;

    fn evaluate(
        &self,
        ctx: &super::model::RodContext<'a>,
        selected: crate::assembly::TermSet,
        out: &mut crate::assembly::LocalDerivatives<'_, HINGE_DOFS>,
    ) {
        let hs = ctx.rod.hinge_state(ctx.state, self);
        let frame = HingeFrame::new(&hs);
        // Bending and twisting second derivatives are gathered in edge space and chained to
        // the stencil once for both terms.
        // Only a Hessian evaluation needs (and zeroes) the edge-space accumulator.
        let mut edge = out.hess.is_some().then(EdgeHessian::default);
        if selected.contains(super::groups::BENDING) {
            let e = self
                .bending
                .energy(&frame, out.grad.as_deref_mut(), edge.as_mut());
            out.add_energy(e);
        }
        if selected.contains(super::groups::TWISTING) {
            let e =
                self.twisting
                    .energy(&frame, hs.twist(), out.grad.as_deref_mut(), edge.as_mut());
            out.add_energy(e);
        }
        if let (Some(h), Some(edge)) = (out.hess.as_deref_mut(), &edge) {
            edge.write_into(h);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `write_into` sets every entry of the stencil Hessian: none of a NaN-filled matrix
    /// survives, which the assembler relies on when it skips zeroing the hinge's matrix.
    #[test]
    fn edge_hessian_writes_every_stencil_entry() {
        let g = EdgeGradient {
            e: Vec3::new(0.3, -1.2, 0.7),
            f: Vec3::new(-0.4, 0.9, 2.1),
            theta: [0.8, -1.7],
        };
        let mut edge = EdgeHessian::default();
        edge.add_outer(1.5, &g);
        let mut h = HingeMatrix::from_element(f64::NAN);
        edge.write_into(&mut h);
        assert!(h.iter().all(|v| v.is_finite()), "{h}");
    }
}
