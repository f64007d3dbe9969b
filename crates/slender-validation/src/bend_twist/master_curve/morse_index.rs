//! The Morse index of a planar equilibrium: the number of unstable modes, in-plane and
//! out-of-plane.
//!
//! The sign of the stability function `f` only gives the parity of the number of unstable
//! modes. The count itself (the Morse index) comes from a Maslov-type angle: with
//! `u = (φ_x, φ_z)` and the momentum `p = (δm_x + ½m_y φ_z, δm_z − ½m_y φ_x)` the
//! out-of-plane system is Hamiltonian and self-adjoint (this uses the equilibrium equation
//! `m_y' = −Γ(1 − S) sin θ`), with `u' = B(p − Cu)`, `p' = Cᵀu' + Ru`, `B = (I − k d dᵀ)`,
//! `d = (sin θ, −cos θ)`, `C = ½m_y J` (`J` the rotation by +90°),
//! `R = Γ(1 − S)[[cos θ, ½ sin θ], [½ sin θ, 0]]`. The unitary matrix `Θ = (P + iU)(P − iU)⁻¹`
//! of the Lagrangian frame `(U, P)` started at `U = 0, P = I` obeys a Riccati equation (no
//! exponential growth), and its eigen-angles `ω_j`, continued from 0, only cross
//! `0 (mod 2π)` forward (Legendre condition `B > 0`). The number of negative eigenvalues of
//! the second variation with the free end is `Σ_j #{k ≥ 0 : ω_j(1) > π + 2πk}`, computed from
//! `arg det(P + iU)` (integrated along) and the eigenvalues of `Θ(1)`. The in-plane index is
//! the scalar Prüfer count of `δθ'' = Γ(1 − S) cos θ δθ`. Their parities agree with the signs
//! of `f` and of the in-plane shooting derivative at every point the tests visit, which
//! checks both.

use super::planar::{ode_options, planar_local, Load, TWO_PI};
use crate::ode;
use nalgebra::{Complex, Matrix2};
use std::f64::consts::PI;

type C64 = Complex<f64>;

/// Number of extra states of [`index_rhs`]: in-plane Prüfer angle, `Θ` (2×2 complex), and
/// `arg det(P + iU)`.
const NI: usize = 10;

/// Right-hand side of the index states at a base point `(θ, m_y, N)`, `k = 1 − 1/c`.
///
/// `Θ' = M₁Θ + M₂ − ΘM̄₁ − ΘM̄₂Θ` and `(arg det Z)' = Im tr(M₁ + M₂Θ̄)` for the Hamiltonian
/// system `U' = aU + bP`, `P' = c̃U + dP`, with `M₁ = ½[(a + d) + i(b − c̃)]`,
/// `M₂ = ½[(d − a) + i(b + c̃)]` (checked against the scalar Prüfer equation in the tests).
fn index_rhs(theta: f64, m_y: f64, n: f64, k: f64, v: &[f64]) -> [f64; NI] {
    let (st, ct) = theta.sin_cos();
    let mut out = [0.0; NI];
    // In-plane: (δm_y)' = N cos θ φ_y, φ_y' = δm_y (stiffness 1).
    let (sw, cw) = v[0].sin_cos();
    out[0] = cw * cw - n * ct * sw * sw;
    let d = [st, -ct];
    let b = Matrix2::new(
        1.0 - k * d[0] * d[0],
        -k * d[0] * d[1],
        -k * d[1] * d[0],
        1.0 - k * d[1] * d[1],
    );
    let cm = Matrix2::new(0.0, -0.5 * m_y, 0.5 * m_y, 0.0);
    let r = Matrix2::new(n * ct, 0.5 * n * st, 0.5 * n * st, 0.0);
    let a = -(b * cm);
    let ct_b = cm.transpose() * b;
    let c_ = r - ct_b * cm;
    let dd = ct_b;
    let cx = |re: Matrix2<f64>, im: Matrix2<f64>| {
        Matrix2::from_fn(|i, j| C64::new(0.5 * re[(i, j)], 0.5 * im[(i, j)]))
    };
    let m1 = cx(a + dd, b - c_);
    let m2 = cx(dd - a, b + c_);
    let th = Matrix2::new(
        C64::new(v[1], v[2]),
        C64::new(v[3], v[4]),
        C64::new(v[5], v[6]),
        C64::new(v[7], v[8]),
    );
    let m1b = m1.map(|z| z.conj());
    let m2b = m2.map(|z| z.conj());
    let dth = m1 * th + m2 - th * m1b - th * m2b * th;
    for (i, z) in dth.iter().enumerate() {
        // Column-major storage: (0,0), (1,0), (0,1), (1,1).
        let slot = [0, 2, 1, 3][i];
        out[1 + 2 * slot] = z.re;
        out[2 + 2 * slot] = z.im;
    }
    out[9] = (m1 + m2 * th.map(|z| z.conj())).trace().im;
    out
}

/// Initial index states: in-plane angle 0, `Θ = I`, `arg det Z = 0`.
fn index_start() -> [f64; NI] {
    let mut v = [0.0; NI];
    v[1] = 1.0;
    v[7] = 1.0;
    v
}

/// `(in-plane, out-of-plane)` index from the index states at `S = 1`, and the distance of the
/// winding number from an integer (a consistency check; ~1e-10 in practice).
fn index_from(v: &[f64]) -> (u32, u32, f64) {
    let in_plane = (v[0] / PI + 0.5).floor().max(0.0) as u32;
    let th = Matrix2::new(
        C64::new(v[1], v[2]),
        C64::new(v[3], v[4]),
        C64::new(v[5], v[6]),
        C64::new(v[7], v[8]),
    );
    let t = th.trace();
    let disc = (t * t - th.determinant() * 4.0).sqrt();
    let angle = |z: C64| {
        let a = z.im.atan2(z.re);
        if a < 0.0 {
            a + TWO_PI
        } else {
            a
        }
    };
    let a1 = angle((t + disc) * 0.5);
    let a2 = angle((t - disc) * 0.5);
    // Σω_j = 2 arg det Z; ω_j = 2πk_j + α_j with α_j ∈ [0, 2π).
    let windings = (2.0 * v[9] - a1 - a2) / TWO_PI;
    let k = windings.round();
    let out = k + f64::from(u8::from(a1 > PI)) + f64::from(u8::from(a2 > PI));
    (in_plane, out.max(0.0) as u32, (windings - k).abs())
}

/// Morse index `(in-plane, out-of-plane)` of the planar state `(η, ξ)`.
pub(super) fn morse_index(
    y: f64,
    c: f64,
    eta: f64,
    xi: f64,
    rtol: f64,
) -> Result<(u32, u32), String> {
    let load = Load::new(xi, y);
    let m0 = TWO_PI * y;
    let k = 1.0 - 1.0 / c;
    let mut u0 = [0.0; 2 + NI];
    u0[1] = eta;
    u0[2..].copy_from_slice(&index_start());
    let sol = ode::integrate(
        |s, u: &[f64; 2 + NI]| {
            let l = planar_local(s, u[0], u[1], &load);
            let r = index_rhs(l.theta, m0 - l.dtheta, l.n, k, &u[2..]);
            let mut out = [0.0; 2 + NI];
            out[0] = l.psi_rate;
            out[1] = l.cap_rate;
            out[2..].copy_from_slice(&r);
            out
        },
        0.0,
        u0,
        1.0,
        &ode_options(rtol, &load),
    )
    .map_err(|e| e.to_string())?;
    let (i, o, miss) = index_from(&sol.y[2..]);
    if miss > 1e-3 {
        return Err(format!("Maslov winding not an integer (off by {miss:e})"));
    }
    Ok((i, o))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::Options;

    /// Standing column (θ ≡ 0, m = 0, Γ < 0): the index counts Greenhill's modes
    /// (critical Γ = −7.837, −55.98, …) in both planes; the out-of-plane count with c ≠ 1
    /// must not depend on c (twist decouples when m = 0).
    #[test]
    fn index_counts_greenhill_modes() {
        let count = |gamma: f64, c: f64| {
            let k = 1.0 - 1.0 / c;
            let sol = ode::integrate(
                |s, v: &[f64; NI]| index_rhs(0.0, 0.0, gamma * (1.0 - s), k, v),
                0.0,
                index_start(),
                1.0,
                &Options::with_tolerances(1e-11, 1e-14),
            )
            .unwrap();
            let (i, o, miss) = index_from(&sol.y);
            assert!(miss < 1e-6);
            (i, o)
        };
        for c in [0.5, 0.77, 2.0] {
            assert_eq!(count(-5.0, c), (0, 0));
            assert_eq!(count(-7.8, c), (0, 0));
            assert_eq!(count(-7.9, c), (1, 1));
            assert_eq!(count(-55.0, c), (1, 1));
            assert_eq!(count(-57.0, c), (2, 2));
            assert_eq!(count(50.0, c), (0, 0));
        }
    }
}
