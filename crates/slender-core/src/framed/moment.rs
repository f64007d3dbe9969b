//! Point moments on a frame, as conservative loads.
//!
//! A moment M on frame j is split at build time, against the frame's rest tangent t̄ (its d₃),
//! into a part M_b n̂ about a fixed axis n̂ ⊥ t̄ and an axial part T t̄ (as the discrete elastic
//! rod splits its moments, `rod/moment.rs`). Each part does the work of its magnitude times
//! the *twist angle* τ_a of the frame's rotation from rest, q = p ⊗ p̄_rest, about its fixed
//! spatial axis a (swing–twist decomposition, `lie/twist_angle.rs`), unwrapped continuously:
//! V = −λ (M_b τ_n̂ + T τ_t̄). For any rotation about n̂ (every planar problem, e.g. an end
//! moment rolling a rod into a circle) or about t̄ (pure torsion) this is the exact work of the
//! dead moment; otherwise it is a conservative approximation of it, as for the discrete
//! elastic rod. It is undefined only at half turns about axes ⊥ a.

use nalgebra::{Matrix3, UnitQuaternion, Vector3};

use crate::geometry::{any_orthogonal, Vec3};
use crate::lie::quaternion::{conj, from_unit, mul, Quat};
use crate::lie::twist_angle::{twist_angle, wrapped_difference};
use crate::lie::SingleRotation;

/// A moment load on one frame, split as described in the module docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameMoment {
    /// The frame slot the moment acts on.
    pub frame: usize,
    /// The fixed unit axes: n̂ (⊥ the rest tangent) and t̄ (the rest tangent).
    pub axes: [Vec3; 2],
    /// Magnitudes (N m) of the parts about `axes`.
    pub magnitudes: [f64; 2],
    /// The frame's rest orientation.
    pub rest: UnitQuaternion<f64>,
}

impl FrameMoment {
    /// Splits `moment` (N m) on frame `frame` with rest orientation `rest`.
    pub fn new(frame: usize, moment: Vec3, rest: UnitQuaternion<f64>) -> Self {
        let tangent = rest * Vec3::z();
        let axial = moment.dot(&tangent);
        let perp = moment - tangent * axial;
        let bending = perp.norm();
        let axis = if bending > 0.0 {
            perp / bending
        } else {
            any_orthogonal(&tangent)
        };
        Self {
            frame,
            axes: [axis, tangent],
            magnitudes: [bending, axial],
            rest,
        }
    }

    /// The rotation of `frame` from rest, in space: q = p ⊗ p̄_rest.
    pub(crate) fn relative(&self, frame: &UnitQuaternion<f64>) -> Quat {
        mul(&from_unit(frame), &conj(&from_unit(&self.rest)))
    }

    /// The unwrapped angles at `new`, continued from `old_angles` at `old` (each step must turn
    /// the frame by less than π about the axes).
    pub fn updated_angles(
        &self,
        old: &UnitQuaternion<f64>,
        new: &UnitQuaternion<f64>,
        old_angles: [f64; 2],
    ) -> [f64; 2] {
        let (qo, qn) = (self.relative(old), self.relative(new));
        let mut out = old_angles;
        for (a, o) in self.axes.iter().zip(out.iter_mut()) {
            let before = twist_angle(&qo, a).value;
            let after = twist_angle(&qn, a).value;
            *o += wrapped_difference(after, before);
        }
        out
    }

    /// The potential −λ Σ M_a τ_a (J) at load factor `load` with the unwrapped angles `angles`,
    /// and its gradient and Hessian in the frame's spatial rotation increment.
    pub fn potential(
        &self,
        frame: &UnitQuaternion<f64>,
        angles: [f64; 2],
        load: f64,
        grad: &mut Vector3<f64>,
        hess: &mut Matrix3<f64>,
    ) -> f64 {
        let rot = SingleRotation::new(self.relative(frame));
        let mut dq = Quat::zeros();
        let mut hq = nalgebra::Matrix4::zeros();
        let mut value = 0.0;
        for ((a, &m), &tau) in self.axes.iter().zip(&self.magnitudes).zip(&angles) {
            let s = -load * m;
            let t = twist_angle(&rot.q, a);
            dq += t.grad * s;
            hq += t.hess * s;
            value += s * tau;
        }
        *grad = rot.jac.transpose() * dq;
        *hess = rot.jac.transpose() * hq * rot.jac + rot.contracted_hessian(&dq);
        value
    }
}
