//! The general linearization of a planar heavy rod (6-D, any stiffness): a check of the
//! reduced out-of-plane system against classical buckling loads.

use super::error::BendTwistError;
use crate::ode::{self, Options};
use nalgebra::{Matrix3, Vector3};

/// A planar base state of a heavy rod for the general linearization
/// ([`general_free_end_moments`]), in the units of this module (lengths by `L`, moments by
/// `EI_ref/L`, stiffnesses by `EI_ref`).
///
/// The rod is clamped at `S = 0`, free at `S = 1`, loaded by its weight
/// `n(S) = Γ(1 − S)ĝ` with `ĝ = −e_z` (`Γ < 0` reverses gravity: a standing column). It lies in
/// the `xz` plane: `d₃ = (sin θ, 0, −cos θ)`, `d₁ = e_y` (the in-plane bending axis, which
/// carries the natural curvature), `d₂ = d₃ × d₁`, and the base state solves
/// `θ' = κ̄ − m_y/K₁`, `m_y' = −Γ(1 − S) sin θ` from the clamp values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GeneralBase {
    /// Tangent angle at the clamp `θ(0)` (rad, from `−e_z` toward `+e_x`).
    pub theta0: f64,
    /// Bending moment at the clamp `m_y(0)` (units `EI_ref/L`).
    pub clamp_moment: f64,
    /// Natural curvature `κ̄` about `d₁` (units `1/L`; `2πY` for the bend–twist rod).
    pub natural_curvature: f64,
    /// `Γ = ρAgL³/EI_ref`.
    pub gamma: f64,
    /// `[K₁, K₂, K₃]`: bending about `d₁` (in-plane), bending about `d₂` (out-of-plane) and
    /// twisting, in units of `EI_ref`; `K₁ = ∞` freezes the in-plane shape (`θ' = κ̄`).
    pub stiffness: [f64; 3],
}

/// Integrates the general linearized Kirchhoff equations about `base`,
/// `φ' = K_lab⁻¹(δm − φ × m)`, `δm' = −(φ × d₃) × n`, from `φ(0) = 0`, `δm(0) = e_j`, and
/// returns `δm(1)` as columns `j = x, y, z` (`[j][i]` = component `i` of column `j`).
///
/// The base is critical where the free-end condition `δm(1) = 0` has a solution, i.e. where
/// the determinant (or the relevant block, since the isotropic planar problem decouples into
/// the `y` column and the `x, z` columns) vanishes. Not rescaled: meant for moderate `|Γ|`
/// (entries grow like `e^{⅔√|Γ|}`). Every stiffness must be `> 0` (`K₁` may be infinite).
pub fn general_free_end_moments(base: &GeneralBase) -> Result<[[f64; 3]; 3], BendTwistError> {
    let [k1, k2, k3] = base.stiffness;
    let finite = [
        ("theta0", base.theta0),
        ("clamp_moment", base.clamp_moment),
        ("natural_curvature", base.natural_curvature),
        ("gamma", base.gamma),
    ];
    for (name, v) in finite {
        if !v.is_finite() {
            return Err(BendTwistError::InvalidParameter {
                name,
                value: v,
                range: "finite".into(),
            });
        }
    }
    for (name, v, inf_ok) in [
        ("stiffness[0]", k1, true),
        ("stiffness[1]", k2, false),
        ("stiffness[2]", k3, false),
    ] {
        if v.is_nan() || v <= 0.0 || (!inf_ok && !v.is_finite()) {
            return Err(BendTwistError::InvalidParameter {
                name,
                value: v,
                range: if inf_ok {
                    "> 0 (may be infinite)"
                } else {
                    "finite and > 0"
                }
                .into(),
            });
        }
    }
    let inv = [1.0 / k1, 1.0 / k2, 1.0 / k3];
    let gamma = base.gamma;
    let kappa = base.natural_curvature;
    // State: θ, m_y, then three columns of (φ, δm).
    let mut u0 = [0.0; 20];
    u0[0] = base.theta0;
    u0[1] = base.clamp_moment;
    for j in 0..3 {
        u0[2 + 6 * j + 3 + j] = 1.0;
    }
    let rhs = |s: f64, u: &[f64; 20]| {
        let (st, ct) = u[0].sin_cos();
        let my = u[1];
        let w = 1.0 - s;
        let d3 = Vector3::new(st, 0.0, -ct);
        let d1 = Vector3::new(0.0, 1.0, 0.0);
        let d2 = d3.cross(&d1);
        let k_inv: Matrix3<f64> = d1 * d1.transpose() * inv[0]
            + d2 * d2.transpose() * inv[1]
            + d3 * d3.transpose() * inv[2];
        let m = Vector3::new(0.0, my, 0.0);
        let n = Vector3::new(0.0, 0.0, -gamma * w);
        let mut out = [0.0; 20];
        out[0] = kappa - my * inv[0];
        out[1] = -gamma * w * st;
        for j in 0..3 {
            let o = 2 + 6 * j;
            let phi = Vector3::new(u[o], u[o + 1], u[o + 2]);
            let dm = Vector3::new(u[o + 3], u[o + 4], u[o + 5]);
            let dphi = k_inv * (dm - phi.cross(&m));
            let ddm = -(phi.cross(&d3)).cross(&n);
            out[o..o + 3].copy_from_slice(dphi.as_slice());
            out[o + 3..o + 6].copy_from_slice(ddm.as_slice());
        }
        out
    };
    let sol = ode::integrate(rhs, 0.0, u0, 1.0, &Options::with_tolerances(1e-12, 1e-14)).map_err(
        |e| BendTwistError::NoConvergence {
            y: f64::NAN,
            c: f64::NAN,
            detail: e.to_string(),
        },
    )?;
    let u = sol.y;
    let mut out = [[0.0; 3]; 3];
    for (j, col) in out.iter_mut().enumerate() {
        col.copy_from_slice(&u[2 + 6 * j + 3..2 + 6 * j + 6]);
    }
    Ok(out)
}
