//! Point moments on a rod, as conservative loads: the same potential as the framed rods'
//! (`framed/moment.rs`), on the material frame of the edge the moment acts on.
//!
//! A moment M on edge j is split at build time, against the edge's rest tangent t̄, into a
//! part M_b n̂ about a fixed axis n̂ ⊥ t̄ and an axial part T t̄. Each part does the work of its
//! magnitude times the *twist angle* τ_a of the edge's material-frame rotation from rest about
//! its fixed spatial axis a (swing–twist decomposition), unwrapped continuously:
//! V = −λ (M_b τ_n̂ + T τ_t̄). For a rotation about n̂ (every planar problem, e.g. an end
//! moment rolling a rod into a circle) or about t̄ (pure torsion) this is the exact work of
//! the dead moment; otherwise it is a conservative approximation of it, the same one as the
//! Cosserat and SE(3) rods', so the three models carry the same load. It is undefined only at
//! half turns about axes ⊥ a.
//!
//! Why not the angle of the edge's projection onto the plane ⊥ n̂ (this file's potential
//! until 2026-12): it ignores the part of the moment along a tilted tangent, so in 3D it is
//! another load than the framed rods' (tips 3 cm apart for M L/EI = 0.94 under gravity), and
//! it is unbounded below: an edge precessing about n̂ winds its projected angle at no elastic
//! cost, and a cantilever under gravity with M L/EI = 1.3 found no equilibrium.
//!
//! The edge's material frame moves with the DOFs as the bending and twisting terms assume
//! (time-parallel reference frames, `hinge.rs`): a change δe of the edge and δθ of its angle
//! turn it by ψ = exp⁻¹(exp(φ) exp(δθ t)) with φ the parallel transport from t to the new
//! tangent, φ = t × δe/ℓ − (t × δe)(t·δe)/ℓ² + O(δe³), so to second order
//! ψ = φ + δθ t + ½ δθ P⊥δe/ℓ (Baker–Campbell–Hausdorff, P⊥ = I − t tᵀ). The potential's
//! gradient and Hessian in ψ (`FrameMoment::potential`) are chained through this map.

use nalgebra::{Matrix3, Rotation3, SMatrix, SVector, UnitQuaternion};

use crate::framed::FrameMoment;
use crate::geometry::Vec3;

/// Number of DOFs of a moment's stencil: `[x_j (3), x_{j+1} (3), θ_j]`.
pub const MOMENT_DOFS: usize = 7;

/// A moment load on one edge (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MomentLoad {
    /// Edge the moment acts on.
    pub edge: usize,
    /// The split moment and the edge's rest material frame.
    pub frame: FrameMoment,
}

/// The orientation of a material frame (m₁, m₂, t): the rotation taking x, y, z to them.
pub fn frame_orientation(frame: &[Vec3; 3]) -> UnitQuaternion<f64> {
    let m = Matrix3::from_columns(frame);
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m))
}

impl MomentLoad {
    /// Splits the moment `moment` (N m) on edge `edge` whose rest material frame is
    /// `rest` (m₁, m₂, t̄).
    pub fn new(edge: usize, moment: Vec3, rest: &[Vec3; 3]) -> Self {
        Self {
            edge,
            frame: FrameMoment::new(edge, moment, frame_orientation(rest)),
        }
    }

    /// The fixed axes n̂ (⊥ the rest tangent) and t̄ of the two parts.
    pub fn axes(&self) -> [Vec3; 2] {
        self.frame.axes
    }

    /// Magnitudes (N m) of the parts about [`Self::axes`].
    pub fn magnitudes(&self) -> [f64; 2] {
        self.frame.magnitudes
    }

    /// The unwrapped angles (rad) at the edge's material frame `new`, continued from
    /// `old_angles` at `old` (each step turns the frame by less than π about the axes).
    pub fn updated_angles(
        &self,
        old: &[Vec3; 3],
        new: &[Vec3; 3],
        old_angles: [f64; 2],
    ) -> [f64; 2] {
        self.frame
            .updated_angles(&frame_orientation(old), &frame_orientation(new), old_angles)
    }

    /// The angles (rad) of material frame `now` in (−2π, 2π] (no whole turns).
    pub fn angles_of(&self, now: &[Vec3; 3]) -> [f64; 2] {
        let q = self.frame.relative(&frame_orientation(now));
        self.frame
            .axes
            .map(|a| crate::lie::twist_angle::twist_angle(&q, &a).value)
    }

    /// The potential V = −λ Σ M_a τ_a (J) at load factor `load`, with the edge's material
    /// frame `frame` (its tangent is the third), length `length` (m) and unwrapped angles
    /// `angles`; writes its gradient and Hessian over the stencil `[x_j, x_{j+1}, θ_j]`.
    /// Also returns ∂V/∂ψ, minus the moment the load exerts on the edge (N m).
    pub fn potential(
        &self,
        frame: &[Vec3; 3],
        length: f64,
        angles: [f64; 2],
        load: f64,
        grad: &mut SVector<f64, MOMENT_DOFS>,
        hess: &mut SMatrix<f64, MOMENT_DOFS, MOMENT_DOFS>,
    ) -> (f64, Vec3) {
        let mut g = Vec3::zeros();
        let mut h = Matrix3::zeros();
        let value = self
            .frame
            .potential(&frame_orientation(frame), angles, load, &mut g, &mut h);
        let t = frame[2];
        let inv = 1.0 / length;
        // ∂ψ/∂e = [t×]/ℓ, ∂ψ/∂θ = t.
        let s = t.cross_matrix() * inv;
        let ge = s.transpose() * g;
        let gt = g.dot(&t);
        // Second-order terms of ψ contracted with g: −(t×δe)(t·δe)/ℓ² gives
        // −(w tᵀ + t wᵀ)/ℓ² with w = g × t; ½ δθ P⊥δe/ℓ gives ½ P⊥g/ℓ in the (e, θ) block.
        let w = g.cross(&t);
        let ee = s.transpose() * h * s - (w * t.transpose() + t * w.transpose()) * (inv * inv);
        let perp_g = g - t * gt;
        let e_theta = s.transpose() * (h * t) + perp_g * (0.5 * inv);
        let theta_theta = t.dot(&(h * t));
        grad.fixed_rows_mut::<3>(0).copy_from(&(-ge));
        grad.fixed_rows_mut::<3>(3).copy_from(&ge);
        grad[6] = gt;
        hess.fixed_view_mut::<3, 3>(0, 0).copy_from(&ee);
        hess.fixed_view_mut::<3, 3>(3, 3).copy_from(&ee);
        hess.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-ee));
        hess.fixed_view_mut::<3, 3>(3, 0).copy_from(&(-ee));
        for k in 0..3 {
            hess[(k, 6)] = -e_theta[k];
            hess[(6, k)] = -e_theta[k];
            hess[(3 + k, 6)] = e_theta[k];
            hess[(6, 3 + k)] = e_theta[k];
        }
        hess[(6, 6)] = theta_theta;
        (value, g)
    }
}
