//! The planar equilibrium, solved by single shooting in Prüfer form, together with its
//! variations and the out-of-plane stability function in one integration.
//!
//! The planar equilibrium (`θ` = tangent angle from the downward vertical toward the curl,
//! `d₃ = (sin θ, 0, −cos θ)`, bending moment `m = m_y e_y`, `m_y = −(θ' − 2πY)`) solves
//!
//! ```text
//! θ'' = Γ(1 − S) sin θ,   θ(0) = 0,   θ'(1) = 2πY.
//! ```
//!
//! Limits: for `Γ → 0` it is the stress-free coil `θ = 2πY S`; for `Γ → ∞` the rod hangs
//! straight (`θ ≈ 0`, carrying the constant moment `m_y = 2πY` that keeps it straight) with a
//! curl of length `ℓ = Γ^{-1/3}` and tip angle `≈ 1.37/X` at its free end.
//!
//! It is solved by *single* shooting on the clamp curvature, written in Prüfer form,
//! `θ = r sin ψ`, `θ' = r cos ψ`, with the log-amplitude measured against the WKB growth,
//! `Λ = ln r + ⅔√Γ (1 − S)^{3/2}`. The shooting unknown is `η = Λ(0) = ln θ'(0) + ⅔√Γ`: it is
//! `ln 2πY` for the stress-free coil and stays of order `ln Γ` on the hanging rod, where
//! `θ'(0) ~ e^{−⅔√Γ}` is far below the smallest double (it reaches ≈70 on the heavy coil at
//! `Y = 20`). Forward integration follows the growing solution, so the shooting is well
//! conditioned for every `Γ` (no multiple shooting needed).

use super::out_of_plane::out_of_plane_rhs;
use crate::ode::{self, OdeError, Options};
use std::f64::consts::PI;

pub(super) const TWO_PI: f64 = 2.0 * PI;

pub(super) fn gamma_of(xi: f64, y: f64) -> f64 {
    (TWO_PI * y * xi.exp()).powi(3)
}

/// `sin t / t` and its derivative (series near 0, where the closed forms cancel).
fn sinc(t: f64) -> (f64, f64) {
    if t.abs() < 1e-3 {
        let t2 = t * t;
        (
            1.0 - t2 / 6.0 + t2 * t2 / 120.0,
            t * (-1.0 / 3.0 + t2 / 30.0),
        )
    } else {
        let (s, c) = t.sin_cos();
        (s / t, (t * c - s) / (t * t))
    }
}

/// `Γ` and `√Γ` of one planar problem.
#[derive(Clone, Copy, Debug)]
pub(super) struct Load {
    gamma: f64,
    sqrt_gamma: f64,
}

impl Load {
    pub(super) fn new(xi: f64, y: f64) -> Self {
        let gamma = gamma_of(xi, y);
        Self {
            gamma,
            sqrt_gamma: gamma.sqrt(),
        }
    }
}

/// The planar state and the Prüfer right-hand side at one point.
pub(super) struct Local {
    /// `ψ'`.
    pub(super) psi_rate: f64,
    /// `Λ'`.
    pub(super) cap_rate: f64,
    /// `θ` (rad).
    pub(super) theta: f64,
    /// `θ'` (1/L).
    pub(super) dtheta: f64,
    /// `Γ(1 − S)`: tension in units of `EI/L²`.
    pub(super) n: f64,
    /// `√(Γ(1 − S))`: the local growth rate of the linearized problems.
    sqrt_n: f64,
    /// `∂(ψ', Λ')/∂(ψ, Λ)`.
    jac: [[f64; 2]; 2],
    /// `∂(ψ', Λ')/∂ξ` at fixed `(ψ, Λ)`, `ξ = ln X`.
    dxi: [f64; 2],
}

/// Prüfer form of `θ'' = N sin θ`: `θ = r sin ψ`, `θ' = r cos ψ`, `ln r = Λ − ⅔√Γ(1 − S)^{3/2}`:
///
/// `ψ' = cos²ψ − N sin²ψ sinc θ`,  `(ln r)' = sin ψ cos ψ (1 + N sinc θ)`.
pub(super) fn planar_local(s: f64, psi: f64, cap: f64, load: &Load) -> Local {
    let w = (1.0 - s).max(0.0);
    let n = load.gamma * w;
    let sw = w.sqrt();
    let sqrt_n = load.sqrt_gamma * sw;
    let w32 = w * sw;
    let r = (cap - 2.0 / 3.0 * load.sqrt_gamma * w32).exp();
    let (sp, cp) = psi.sin_cos();
    let theta = r * sp;
    let (h, hp) = sinc(theta);
    let nh1 = 1.0 + n * h;
    let dpsi_dlam = -n * sp * sp * hp * theta;
    let dlam_dlam = sp * cp * n * hp * theta;
    // ∂(ln r)/∂ξ at fixed Λ (Γ ∝ X³, so ∂Γ/∂ξ = 3Γ).
    let lam_xi = -load.sqrt_gamma * w32;
    Local {
        psi_rate: cp * cp - n * sp * sp * h,
        cap_rate: sp * cp * nh1 - sqrt_n,
        theta,
        dtheta: r * cp,
        n,
        sqrt_n,
        jac: [
            [-2.0 * sp * cp * nh1 - n * sp * sp * hp * r * cp, dpsi_dlam],
            [
                (cp * cp - sp * sp) * nh1 + sp * cp * n * hp * r * cp,
                dlam_dlam,
            ],
        ],
        dxi: [
            -3.0 * n * sp * sp * h + dpsi_dlam * lam_xi,
            3.0 * n * sp * cp * h + dlam_dlam * lam_xi - 1.5 * sqrt_n,
        ],
    }
}

pub(super) fn ode_options(rtol: f64, load: &Load) -> Options {
    Options {
        rtol,
        // The states are O(1) (angles, log-amplitude, rescaled perturbations); the floor only
        // matters for components that start at exactly zero.
        atol: rtol * 1e-6,
        max_steps: 5_000_000,
        // The stiff scale of the Prüfer and rescaled equations is 1/√Γ.
        initial_step: Some((0.5 / (1.0 + load.sqrt_gamma)).min(1.0 / 32.0)),
    }
}

/// Everything known at one `(η, ξ)` from one integration of the planar state, its
/// variations and the reduced out-of-plane system.
#[derive(Clone, Copy, Debug)]
pub(super) struct Shot {
    /// `R = θ'(1)/(2πY) − 1`.
    pub(super) r: f64,
    /// `∂R/∂η` (its sign is `(−1)^{in-plane index}`).
    pub(super) r_eta: f64,
    /// `∂R/∂ξ`.
    pub(super) r_xi: f64,
    /// `f̂ = δm_x(1)/|(φ_x, φ_z, δm_x)(1)|` (its sign is `(−1)^{out-of-plane index}`).
    pub(super) f: f64,
    /// `θ(1)` (rad).
    pub(super) tip: f64,
}

/// Integrates the planar state with its variations and the rescaled out-of-plane system.
pub(super) fn shoot_full(y: f64, c: f64, eta: f64, xi: f64, rtol: f64) -> Result<Shot, OdeError> {
    let load = Load::new(xi, y);
    let m0 = TWO_PI * y;
    let k = 1.0 - 1.0 / c;
    let sol = ode::integrate(
        |s, u: &[f64; 9]| {
            let l = planar_local(s, u[0], u[1], &load);
            let j = &l.jac;
            let o = out_of_plane_rhs(l.theta, m0 - l.dtheta, l.n, k, l.sqrt_n, u[6], u[7], u[8]);
            [
                l.psi_rate,
                l.cap_rate,
                j[0][0] * u[2] + j[0][1] * u[3],
                j[1][0] * u[2] + j[1][1] * u[3],
                j[0][0] * u[4] + j[0][1] * u[5] + l.dxi[0],
                j[1][0] * u[4] + j[1][1] * u[5] + l.dxi[1],
                o[0],
                o[1],
                o[2],
            ]
        },
        0.0,
        [0.0, eta, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0],
        1.0,
        &ode_options(rtol, &load),
    )?;
    let u = sol.y;
    let amplitude = u[1].exp();
    let e = amplitude / m0;
    let (sp, cp) = u[0].sin_cos();
    let norm = (u[6] * u[6] + u[7] * u[7] + u[8] * u[8]).sqrt();
    Ok(Shot {
        r: e * cp - 1.0,
        r_eta: e * (cp * u[3] - sp * u[2]),
        r_xi: e * (cp * u[5] - sp * u[4]),
        f: u[8] / norm,
        tip: amplitude * sp,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The analytic derivatives of the shooting residual against central differences.
    #[test]
    fn shooting_derivatives_match_finite_differences() {
        let r = |y, eta, xi| shoot_full(y, 0.77, eta, xi, 1e-12).unwrap();
        for (y, eta, xi) in [(0.5, 1.2, -0.5), (2.0, 2.5, -1.2), (1.0, 0.3, 0.5)] {
            let s = r(y, eta, xi);
            let e = 1e-6;
            let d_eta = (r(y, eta + e, xi).r - r(y, eta - e, xi).r) / (2.0 * e);
            let d_xi = (r(y, eta, xi + e).r - r(y, eta, xi - e).r) / (2.0 * e);
            assert!(
                (d_eta - s.r_eta).abs() < 1e-6 * (1.0 + s.r_eta.abs()),
                "{d_eta} {}",
                s.r_eta
            );
            assert!(
                (d_xi - s.r_xi).abs() < 1e-6 * (1.0 + s.r_xi.abs()),
                "{d_xi} {}",
                s.r_xi
            );
        }
    }
}
