//! Master curve of the bend–twist benchmark: the stability boundaries of the planar
//! equilibrium of a heavy, naturally curved Kirchhoff rod, computed independently of any rod
//! discretization (design.md §1.2, seed §4).
//!
//! # Problem
//!
//! An inextensible, unshearable rod of length `L`, isotropic bending stiffness `EI`, twisting
//! stiffness `GJ = c·EI` and weight `ρAg` per length has a stress-free shape that is a circle
//! of radius `R` (possibly more than one turn). It is clamped at `s = 0` with its tangent along
//! gravity (`−e_z`) and its curvature plane `xz`; the other end is free. Lengths are scaled by
//! `L` (`S = s/L`), moments by `EI/L`, forces by `EI/L²`. The two benchmark parameters are
//!
//! ```text
//! X = (R/L) Γ^{1/3},   Y = L/(2πR),   so   Γ = ρAgL³/EI = (2πXY)³,   L/R = 2πY.
//! ```
//!
//! With a free end the internal force is known in every configuration,
//! `n(S) = Γ(1 − S) ĝ` (force of the lower part on the upper part, `ĝ = −e_z`). The planar
//! equilibrium (`θ` = tangent angle from the downward vertical toward the curl,
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
//! # Linearized stability
//!
//! A perturbation rotates the frame by an infinitesimal `φ(S)` (`δd_i = φ × d_i`). The natural
//! curvature is attached to the material frame, so `δm = K φ' + φ × m` with the lab-frame
//! stiffness `K = I − (1 − c) d₃d₃ᵀ`, and with `n` known, `δm' = −(φ × d₃) × n`; `φ(0) = 0`,
//! `δm(1) = 0`. The in-plane part (`φ_y, δm_y`) is the linearized planar equation; in the
//! out-of-plane part `δm_z ≡ 0` (the vertical torque is conserved), which leaves, with
//! `v = (δm_x + φ_z m_y, 0, −φ_x m_y)` and `k = 1 − 1/c`,
//!
//! ```text
//! φ_x' = v_x − k (d₃·v) sin θ,   φ_z' = v_z + k (d₃·v) cos θ,
//! δm_x' = Γ(1 − S)(φ_z sin θ + φ_x cos θ),     φ_x(0) = φ_z(0) = 0,  δm_x(0) = 1.
//! ```
//!
//! The planar state is critical where `f = δm_x(1) = 0`. [`general_free_end_moments`]
//! integrates the general (6-D, any stiffness) linearization; the tests check it against
//! Greenhill's column and lateral–torsional buckling, and the reduced system above against it.
//!
//! The sign of `f` only gives the parity of the number of unstable modes. The count itself (the
//! Morse index) comes from a Maslov-type angle: with `u = (φ_x, φ_z)` and the momentum
//! `p = (δm_x + ½m_y φ_z, δm_z − ½m_y φ_x)` the out-of-plane system is Hamiltonian and
//! self-adjoint (this uses the equilibrium equation `m_y' = −Γ(1 − S) sin θ`), with
//! `u' = B(p − Cu)`, `p' = Cᵀu' + Ru`, `B = (I − k d dᵀ)`, `d = (sin θ, −cos θ)`,
//! `C = ½m_y J` (`J` the rotation by +90°), `R = Γ(1 − S)[[cos θ, ½ sin θ], [½ sin θ, 0]]`.
//! The unitary matrix `Θ = (P + iU)(P − iU)⁻¹` of the Lagrangian frame `(U, P)` started at
//! `U = 0, P = I` obeys a Riccati equation (no exponential growth), and its eigen-angles `ω_j`,
//! continued from 0, only cross `0 (mod 2π)` forward (Legendre condition `B > 0`). The number of
//! negative eigenvalues of the second variation with the free end is
//! `Σ_j #{k ≥ 0 : ω_j(1) > π + 2πk}`, computed from `arg det(P + iU)` (integrated along) and the
//! eigenvalues of `Θ(1)`. The in-plane index is the scalar Prüfer count of
//! `δθ'' = Γ(1 − S) cos θ δθ`. Their parities agree with the signs of `f` and of the in-plane
//! shooting derivative at every point the tests visit, which checks both.
//!
//! # Numerics
//!
//! * The planar BVP is solved by *single* shooting on the clamp curvature, written in Prüfer
//!   form, `θ = r sin ψ`, `θ' = r cos ψ`, with the log-amplitude measured against the WKB growth,
//!   `Λ = ln r + ⅔√Γ (1 − S)^{3/2}`. The shooting unknown is `η = Λ(0) = ln θ'(0) + ⅔√Γ`: it is
//!   `ln 2πY` for the stress-free coil and stays of order `ln Γ` on the hanging rod, where
//!   `θ'(0) ~ e^{−⅔√Γ}` is far below the smallest double (it reaches ≈70 on the heavy coil at
//!   `Y = 20`). Forward integration follows the growing solution, so the shooting is well
//!   conditioned for every `Γ` (no multiple shooting needed).
//! * The out-of-plane system is integrated with the continuous positive rescaling
//!   `e^{−∫√(Γ(1−S))}` (it grows like `e^{⅔√Γ}`), which keeps the sign of `f`; the reported
//!   stability function is `f̂ = δm_x(1)/|(φ_x, φ_z, δm_x)(1)|`, which has the sign of `f`.
//! * The planar solutions at fixed `Y` form one curve in the `(η, ln X)` plane, which for
//!   `Y ≳ 1` folds back and forth in `X` (in-plane snaps). It is followed by pseudo-arclength
//!   continuation with step control on the turning of the tangent and on the change of `f̂`.
//!   Sign changes of `f̂` and of the in-plane derivative are refined by Brent's method on the
//!   branch; a local minimum of `f̂` between two points is minimized to catch a pair of
//!   crossings inside one step (near the tongue tip).
//! * All ODEs use the crate's Dormand–Prince integrator ([`crate::ode`]).
//!
//! # Results
//!
//! Along the branch the Morse index goes 0 → 1 → … → 1 → 0: one loss of stability at
//! `X_c1(Y)` (out-of-plane: the loaded coil twists out of its plane) and one recovery at
//! `X_c2(Y)` (the hanging curl becomes stable again). All in-plane folds (snaps; none at
//! `Y = 1`, two at `Y = 1.2`) and every other change of the index lie between them, where every planar
//! equilibrium of the branch is unstable (up to 10 unstable modes at `Y = 10`). For
//! `c = 0.77`: below `Y* = 0.931984` the branch is stable for every `X`; the tongue tip is at
//! `X* = 0.44056` and the window opens like `√(Y − Y*)`; `X_c1` falls monotonically (with a
//! modulation of period ≈1 in `Y`, one per added turn), e.g. 0.3818, 0.2727, 0.1011 at
//! `Y = 1, 2, 10`; `X_c2` rises to its large-`Y` limit 0.580557 (reached to 1e-8 by `Y ≈ 3`: the
//! mode lives in the tip curl of length `Γ^{-1/3}`, and the rest of the rod only matters
//! through `e^{−⅔(2πXY)^{3/2}}`). Cheaper twisting widens the window: the limit of `X_c2` is
//! 0.7114 at `c = 0.5` and 0.5165 at `c = 1`, and `Y*` is 0.7874 and 1.0172.
//!
//! The discrete rod model (DER with 100·Y elements) reproduces both boundaries to ~0.03 %
//! (tests), and there both bifurcations are supercritical (the 3-D amplitude grows like the
//! square root of the distance into the window; no 3-D state was found just outside it).

use crate::ode::{self, OdeError, Options};
use nalgebra::{Complex, Matrix2, Matrix3, Vector3};
use std::f64::consts::PI;

/// Smallest accepted `Y = L/(2πR)`.
pub const Y_MIN: f64 = 0.01;
/// Largest accepted `Y` (the cost grows like `Y^{3/2}` through `√Γ` at the upper boundary).
pub const Y_MAX: f64 = 20.0;
/// Smallest accepted torsion ratio `c = GJ/EI` (a round section has `1/(1 + ν)`).
pub const C_MIN: f64 = 0.5;
/// Largest accepted torsion ratio `c = GJ/EI`. Above 1 (twisting stiffer than bending) the
/// first instability of the loaded coil can be an in-plane snap onto a stable hanging sheet
/// (observed at `c = 2`), and the two-boundary description no longer holds.
pub const C_MAX: f64 = 1.0;
/// Largest load parameter `Γ = (2πXY)³` at which [`stability_function`] is evaluated.
pub const GAMMA_MAX: f64 = 1e10;

/// `X` where the continuation from the hanging branch starts. Every change of stability lies
/// below it over `[Y_MIN, Y_MAX] × [C_MIN, C_MAX]`: the largest `X_c2` is the large-`Y` limit
/// at `c = 0.5`, 0.7114; the tests trace the whole branch beyond it.
const X_TOP: f64 = 1.2;
/// The continuation from the coil starts at `X = min(X_START, 1/(2πY))`, i.e. `Γ ≤ 1`, far
/// below every instability (the lowest, `X_c1` at `Y = Y_MAX`, has `Γ ≈ 10³`).
const X_START: f64 = 0.02;

const TWO_PI: f64 = 2.0 * PI;

type C64 = Complex<f64>;

// ---------------------------------------------------------------------------------------
// Public types
// ---------------------------------------------------------------------------------------

/// Why a master-curve quantity could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BendTwistError {
    /// An input is NaN, infinite or outside its valid range.
    #[error("invalid {name} = {value}: must be {range}")]
    InvalidParameter {
        /// Which input (`x`, `y`, `c`, `rtol`, …).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The valid range.
        range: String,
    },
    /// The numerics failed (not expected inside the documented ranges).
    #[error("bend-twist master curve failed at Y = {y}, c = {c}: {detail}")]
    NoConvergence {
        /// The aspect parameter `Y` (NaN for [`general_free_end_moments`]).
        y: f64,
        /// The torsion ratio `c` (NaN for [`general_free_end_moments`]).
        c: f64,
        /// What went wrong.
        detail: String,
    },
}

/// The stability boundaries of the planar equilibrium at one `Y`.
///
/// The planar equilibrium is unstable (the rod buckles out of plane: "3-D") exactly for
/// `lower < X < upper`, and stable ("2-D") for all `X` when both are `None` (`Y < Y*`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabilityBoundary {
    /// `Y = L/(2πR)` (dimensionless).
    pub y: f64,
    /// `X_c1 = (R/L)Γ^{1/3}` where the coil, loaded from `Γ = 0`, loses stability
    /// (dimensionless).
    pub lower: Option<f64>,
    /// `X_c2`, above which the hanging curl is stable again (dimensionless).
    pub upper: Option<f64>,
}

impl StabilityBoundary {
    /// True if the planar equilibrium at `x` is stable (outside the open window
    /// `(lower, upper)`).
    pub fn planar_stable(&self, x: f64) -> bool {
        match (self.lower, self.upper) {
            (Some(l), Some(u)) => !(x > l && x < u),
            _ => true,
        }
    }
}

/// Numerical settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// Relative tolerance of every ODE integration (dimensionless; the absolute tolerance is
    /// `1e-6·rtol` in the scaled units). Default `1e-10`; the boundaries then move by < 1e-8
    /// relative when it is halved. Must be in `[1e-13, 1e-6]`.
    pub rtol: f64,
}

impl Default for Settings {
    fn default() -> Self {
        Self { rtol: 1e-10 }
    }
}

/// Kind of a change of stability along the planar branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// An out-of-plane eigenvalue crosses zero (`f = 0`): a bifurcation to 3-D shapes.
    OutOfPlane,
    /// An in-plane eigenvalue crosses zero: a fold of the planar branch in `X` (snap).
    InPlaneFold,
}

/// A point of the planar branch where an eigenvalue of the second variation crosses zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BranchEvent {
    /// `X` at the event (dimensionless).
    pub x: f64,
    /// What crosses zero.
    pub kind: EventKind,
    /// `(in-plane, out-of-plane)` number of unstable modes just before the event (along the
    /// branch, coming from `X → 0`).
    pub index_before: (u32, u32),
    /// The same just after the event.
    pub index_after: (u32, u32),
}

/// The planar branch at one `Y`, traced from the stress-free coil to a given `X`.
#[derive(Clone, Debug, PartialEq)]
pub struct PlanarBranch {
    /// `Y` (dimensionless).
    pub y: f64,
    /// `c = GJ/EI`.
    pub c: f64,
    /// Every change of stability, in order along the branch.
    pub events: Vec<BranchEvent>,
    /// Number of continuation points.
    pub points: usize,
    /// `(in-plane, out-of-plane)` index at the last point.
    pub final_index: (u32, u32),
}

impl PlanarBranch {
    /// Number of separate stretches of the branch on which the planar state is stable.
    pub fn stable_stretches(&self) -> usize {
        let mut stable = true;
        let mut count = 1;
        for e in &self.events {
            let now = e.index_after == (0, 0);
            if now && !stable {
                count += 1;
            }
            stable = now;
        }
        count
    }
}

/// A planar equilibrium (on the branch continued from the stress-free coil).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarEquilibrium {
    /// `X` (dimensionless).
    pub x: f64,
    /// `Y` (dimensionless).
    pub y: f64,
    /// `Γ = (2πXY)³`.
    pub gamma: f64,
    /// Clamp curvature `θ'(0)` in units of `1/L` (may underflow to 0 for the hanging rod).
    pub clamp_curvature: f64,
    /// `ln θ'(0)`, finite even where `θ'(0)` underflows.
    pub ln_clamp_curvature: f64,
    /// Clamp bending moment `m_y(0) = 2πY − θ'(0)` in units of `EI/L`.
    pub clamp_moment: f64,
    /// Tip angle `θ(1)` (rad) from the downward vertical.
    pub tip_angle: f64,
    /// Normalized stability function `f̂` (sign of `f = δm_x(1)`).
    pub stability_function: f64,
    /// `(in-plane, out-of-plane)` number of unstable modes.
    pub index: (u32, u32),
}

// ---------------------------------------------------------------------------------------
// Input checks
// ---------------------------------------------------------------------------------------

fn check_y(y: f64) -> Result<(), BendTwistError> {
    if y.is_finite() && (Y_MIN..=Y_MAX).contains(&y) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "y",
            value: y,
            range: format!("finite and in [{Y_MIN}, {Y_MAX}]"),
        })
    }
}

fn check_c(c: f64) -> Result<(), BendTwistError> {
    if c.is_finite() && (C_MIN..=C_MAX).contains(&c) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "c",
            value: c,
            range: format!("finite and in [{C_MIN}, {C_MAX}] (c = GJ/EI)"),
        })
    }
}

fn check_x_positive(x: f64) -> Result<(), BendTwistError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "x",
            value: x,
            range: "finite and > 0".into(),
        })
    }
}

fn check_settings(s: &Settings) -> Result<(), BendTwistError> {
    if s.rtol.is_finite() && (1e-13..=1e-6).contains(&s.rtol) {
        Ok(())
    } else {
        Err(BendTwistError::InvalidParameter {
            name: "rtol",
            value: s.rtol,
            range: "in [1e-13, 1e-6]".into(),
        })
    }
}

// ---------------------------------------------------------------------------------------
// The planar equilibrium in Prüfer form
// ---------------------------------------------------------------------------------------

fn gamma_of(xi: f64, y: f64) -> f64 {
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
struct Load {
    gamma: f64,
    sqrt_gamma: f64,
}

impl Load {
    fn new(xi: f64, y: f64) -> Self {
        let gamma = gamma_of(xi, y);
        Self {
            gamma,
            sqrt_gamma: gamma.sqrt(),
        }
    }
}

/// The planar state and the Prüfer right-hand side at one point.
struct Local {
    /// `ψ'`.
    psi_rate: f64,
    /// `Λ'`.
    cap_rate: f64,
    /// `θ` (rad).
    theta: f64,
    /// `θ'` (1/L).
    dtheta: f64,
    /// `Γ(1 − S)`: tension in units of `EI/L²`.
    n: f64,
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
fn planar_local(s: f64, psi: f64, cap: f64, load: &Load) -> Local {
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

fn ode_options(rtol: f64, load: &Load) -> Options {
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

/// Right-hand side of the reduced out-of-plane system `(φ_x, φ_z, δm_x)` (design.md §1.2),
/// rescaled by `e^{−∫g}`.
#[allow(clippy::too_many_arguments)]
fn out_of_plane_rhs(
    theta: f64,
    m_y: f64,
    n: f64,
    k: f64,
    g: f64,
    phi_x: f64,
    phi_z: f64,
    dm_x: f64,
) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    let vx = dm_x + phi_z * m_y;
    let vz = -phi_x * m_y;
    let d3v = st * vx - ct * vz;
    [
        vx - k * d3v * st - g * phi_x,
        vz + k * d3v * ct - g * phi_z,
        n * (phi_z * st + phi_x * ct) - g * dm_x,
    ]
}

/// Everything known at one `(η, ξ)` from one integration of the planar state, its
/// variations and the reduced out-of-plane system.
#[derive(Clone, Copy, Debug)]
struct Shot {
    /// `R = θ'(1)/(2πY) − 1`.
    r: f64,
    /// `∂R/∂η` (its sign is `(−1)^{in-plane index}`).
    r_eta: f64,
    /// `∂R/∂ξ`.
    r_xi: f64,
    /// `f̂ = δm_x(1)/|(φ_x, φ_z, δm_x)(1)|` (its sign is `(−1)^{out-of-plane index}`).
    f: f64,
    /// `θ(1)` (rad).
    tip: f64,
}

/// Integrates the planar state with its variations and the rescaled out-of-plane system.
fn shoot_full(y: f64, c: f64, eta: f64, xi: f64, rtol: f64) -> Result<Shot, OdeError> {
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

// ---------------------------------------------------------------------------------------
// Morse index (Maslov angle of the Hamiltonian out-of-plane system, Prüfer in-plane)
// ---------------------------------------------------------------------------------------

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
fn morse_index(y: f64, c: f64, eta: f64, xi: f64, rtol: f64) -> Result<(u32, u32), String> {
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

// ---------------------------------------------------------------------------------------
// Continuation of the planar branch
// ---------------------------------------------------------------------------------------

/// A converged point of the planar branch.
#[derive(Clone, Copy, Debug)]
struct Point {
    /// `(η, ξ)`.
    p: [f64; 2],
    /// Unit tangent in the direction of travel.
    t: [f64; 2],
    /// `∂R/∂η` (sign: in-plane parity).
    r_eta: f64,
    /// `f̂` (sign: out-of-plane parity).
    f: f64,
}

impl Point {
    fn x(&self) -> f64 {
        self.p[1].exp()
    }
}

/// Largest turn of the tangent per continuation step (rad).
const MAX_TURN: f64 = 0.12;
/// Largest change of `f̂` per continuation step without a change of sign.
const MAX_DF: f64 = 0.2;
/// Largest and smallest step length in the `(η, ln X)` plane.
const H_MAX: f64 = 1.0;
const H_MIN: f64 = 1e-9;
/// Most continuation steps of one walk (a full trace at `Y = 20` takes ~400).
const MAX_WALK: usize = 100_000;
/// Loosest integration tolerance used while walking along the branch; events are refined
/// with the requested tolerance.
const RTOL_WALK: f64 = 1e-8;

/// The planar problem at one `(Y, c)`, integrated at one tolerance.
#[derive(Clone, Copy, Debug)]
struct Tracer {
    y: f64,
    c: f64,
    rtol: f64,
    /// Newton on the branch stops after an update below this (the update is applied, the
    /// data are those of the previous iterate).
    newton_tol: f64,
}

impl Tracer {
    /// The walking tracer (loose) and the refining tracer (as requested).
    fn pair(y: f64, c: f64, rtol: f64) -> (Self, Self) {
        let walk = Self {
            y,
            c,
            rtol: rtol.max(RTOL_WALK),
            // Quadratic convergence: the point after an update of 1e-5 is accurate to ~1e-10,
            // while f̂ and the tangent are those 1e-5 away (enough to walk).
            newton_tol: 1e-5,
        };
        let mut fine = Self {
            y,
            c,
            rtol,
            newton_tol: 0.0,
        };
        fine.newton_tol = fine.noise();
        // (`correct` raises it to the noise level at the current η.)
        (walk, fine)
    }

    /// Level below which Newton updates at `η` are integration noise: the log-amplitude `Λ`
    /// is integrated to `rtol·|Λ|`, and `|Λ|` reaches `|η|` (≈70 for the coil at `Y = 20`,
    /// where the branch is known to ~5e-6 at `rtol = 1e-8`).
    fn noise_at(&self, eta: f64) -> f64 {
        (30.0 * self.rtol * (1.0 + 0.1 * eta.abs())).max(1e-11)
    }

    /// [`Self::noise_at`] for `|η| ≤ 1`.
    fn noise(&self) -> f64 {
        self.noise_at(0.0)
    }

    fn fail(&self, detail: impl Into<String>) -> BendTwistError {
        BendTwistError::NoConvergence {
            y: self.y,
            c: self.c,
            detail: detail.into(),
        }
    }

    fn shoot(&self, p: [f64; 2]) -> Result<Shot, OdeError> {
        shoot_full(self.y, self.c, p[0], p[1], self.rtol)
    }

    /// Completes a point with its tangent, oriented along `dir`.
    fn point(&self, p: [f64; 2], shot: &Shot, dir: [f64; 2]) -> Result<Point, BendTwistError> {
        let norm = shot.r_eta.hypot(shot.r_xi);
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(self.fail("singular branch (zero gradient)"));
        }
        let mut t = [-shot.r_xi / norm, shot.r_eta / norm];
        if t[0] * dir[0] + t[1] * dir[1] < 0.0 {
            t = [-t[0], -t[1]];
        }
        Ok(Point {
            p,
            t,
            r_eta: shot.r_eta,
            f: shot.f,
        })
    }

    /// Damped Newton in `η` at fixed `ξ` from `eta`, on a branch where `∂R/∂η > 0`.
    fn solve_at_xi(&self, xi: f64, mut eta: f64) -> Result<Point, BendTwistError> {
        for _ in 0..60 {
            let shot = self
                .shoot([eta, xi])
                .map_err(|e| self.fail(e.to_string()))?;
            if shot.r_eta.is_nan() || shot.r_eta <= 0.0 {
                // Off the in-plane stable branch: walk toward the root instead.
                eta -= shot.r.signum() * 0.5;
                continue;
            }
            let d = (-shot.r / shot.r_eta).clamp(-1.0, 1.0);
            if d.abs() <= self.noise_at(eta) {
                return self.point([eta + d, xi], &shot, [0.0, 1.0]);
            }
            eta += d;
        }
        Err(self.fail(format!("no planar solution found at X = {}", xi.exp())))
    }

    /// Newton on `R(p) = 0`, `a·p = b` from `guess`: the point and the shot of the last
    /// iterate, and the number of iterations.
    fn correct(&self, guess: [f64; 2], a: [f64; 2], b: f64) -> Option<([f64; 2], Shot, usize)> {
        self.correct_to(guess, a, b, self.newton_tol)
    }

    /// [`Self::correct`] with an explicit tolerance on the Newton update.
    fn correct_to(
        &self,
        guess: [f64; 2],
        a: [f64; 2],
        b: f64,
        tol: f64,
    ) -> Option<([f64; 2], Shot, usize)> {
        let tol = tol.max(self.noise_at(guess[0]));
        let mut p = guess;
        for it in 1..=8 {
            let shot = self.shoot(p).ok()?;
            let g = a[0] * p[0] + a[1] * p[1] - b;
            let det = shot.r_eta * a[1] - shot.r_xi * a[0];
            if det == 0.0 || !det.is_finite() {
                return None;
            }
            let d0 = (-shot.r * a[1] + shot.r_xi * g) / det;
            let d1 = (-shot.r_eta * g + a[0] * shot.r) / det;
            if !(d0.is_finite() && d1.is_finite()) || d0.abs().max(d1.abs()) > 1.0 {
                return None;
            }
            p = [p[0] + d0, p[1] + d1];
            if d0.abs().max(d1.abs()) <= tol {
                return Some((p, shot, it));
            }
        }
        None
    }

    /// One accepted continuation step from `last` with trial length `h` (adapted in place).
    fn step(&self, last: &Point, h: &mut f64) -> Result<Point, BendTwistError> {
        loop {
            if *h < H_MIN {
                return Err(self.fail(format!("continuation step underflow at X = {}", last.x())));
            }
            let pred = [last.p[0] + *h * last.t[0], last.p[1] + *h * last.t[1]];
            let b = last.t[0] * pred[0] + last.t[1] * pred[1];
            // Tight enough for the tangent and f̂ (taken at the last iterate) at this scale,
            // not below the noise of the integration.
            let noise = self.noise_at(last.p[0]);
            let tol = (1e-3 * *h).min(self.newton_tol).max(noise);
            let Some((p, shot, iterations)) = self.correct_to(pred, last.t, b, tol) else {
                *h *= 0.5;
                continue;
            };
            let next = self.point(p, &shot, last.t)?;
            let turn = (next.t[0] * last.t[0] + next.t[1] * last.t[1])
                .clamp(-1.0, 1.0)
                .acos();
            let same_sign = (next.f > 0.0) == (last.f > 0.0);
            let df = if same_sign {
                (next.f - last.f).abs()
            } else {
                0.0
            };
            let drift = (p[0] - pred[0]).hypot(p[1] - pred[1]);
            // Small turns and a corrector that stays close to the predictor keep the walk on
            // the branch (coarse steps jump between the tightly packed sheets of the folded
            // branch); small changes of f̂ resolve its dips (a change of sign is refined
            // anyway).
            if turn > MAX_TURN || df > MAX_DF || drift > 0.2 * *h + 10.0 * tol {
                *h *= 0.5;
                continue;
            }
            if iterations <= 2 && df < 0.5 * MAX_DF {
                // Aim at half the largest turn.
                *h = (*h * (0.5 * MAX_TURN / turn.max(1e-3)).clamp(0.7, 1.6)).min(H_MAX);
            }
            return Ok(next);
        }
    }

    /// The point of the branch between `a` and `b` whose projection on the chord is at
    /// fraction `tau`, from a cubic Hermite guess built on the end tangents.
    fn on_chord(&self, a: &Point, b: &Point, tau: f64) -> Result<Point, BendTwistError> {
        let chord = [b.p[0] - a.p[0], b.p[1] - a.p[1]];
        let len2 = chord[0] * chord[0] + chord[1] * chord[1];
        // End tangents scaled to d(position)/dτ (their projection on the chord is |chord|²).
        let scaled = |t: [f64; 2]| {
            let proj = t[0] * chord[0] + t[1] * chord[1];
            if proj > 0.1 * len2.sqrt() {
                [t[0] * len2 / proj, t[1] * len2 / proj]
            } else {
                chord
            }
        };
        let (ta, tb) = (scaled(a.t), scaled(b.t));
        let (t2, t3) = (tau * tau, tau * tau * tau);
        let (h00, h10, h01, h11) = (
            2.0 * t3 - 3.0 * t2 + 1.0,
            t3 - 2.0 * t2 + tau,
            -2.0 * t3 + 3.0 * t2,
            t3 - t2,
        );
        let guess: [f64; 2] =
            std::array::from_fn(|i| h00 * a.p[i] + h10 * ta[i] + h01 * b.p[i] + h11 * tb[i]);
        let rhs = chord[0] * (a.p[0] + tau * chord[0]) + chord[1] * (a.p[1] + tau * chord[1]);
        // Converged to the noise level (`correct_to` raises 0 to it): events are located with
        // these points.
        let (p, shot, _) = self
            .correct_to(guess, chord, rhs, 0.0)
            .ok_or_else(|| self.fail("no branch point on a chord"))?;
        self.point(p, &shot, a.t)
    }

    /// `a` re-evaluated at this tracer's tolerance (same position: walk points are on the
    /// branch to ~1e-10).
    fn reevaluate(&self, a: &Point) -> Result<Point, BendTwistError> {
        let shot = self.shoot(a.p).map_err(|e| self.fail(e.to_string()))?;
        self.point(a.p, &shot, a.t)
    }

    /// Root of `event` on the branch between `a` and `b`, or `None` if at this tracer's
    /// tolerance the event does not change sign between them (a walk at a looser tolerance
    /// can see a spurious change when the event is ~1e-8 from zero at a point).
    fn refine(
        &self,
        a: &Point,
        b: &Point,
        event: EventFn,
    ) -> Result<Option<Point>, BendTwistError> {
        let ea = event(&self.reevaluate(a)?);
        let eb = event(&self.reevaluate(b)?);
        if ea.signum() == eb.signum() {
            return Ok(None);
        }
        let tau = brent_root(
            |tau| Ok(event(&self.on_chord(a, b, tau)?)),
            0.0,
            ea,
            1.0,
            eb,
            1e-10,
        )?;
        self.on_chord(a, b, tau).map(Some)
    }

    /// The minimum of `f̂` on the branch between `a` and `b`.
    fn minimize_f(&self, a: &Point, b: &Point) -> Result<Point, BendTwistError> {
        let tau = golden_min(|tau| Ok(self.on_chord(a, b, tau)?.f), 0.0, 1.0, 1e-7)?;
        self.on_chord(a, b, tau)
    }

    fn start_coil(&self) -> Result<Point, BendTwistError> {
        let x0 = X_START.min(1.0 / (TWO_PI * self.y));
        self.solve_at_xi(x0.ln(), (TWO_PI * self.y).ln())
    }

    /// The hanging state at `x_top`, walking down in `X`. The first guess is the linear tip
    /// layer `θ ≈ A Ai((1 − S)Γ^{1/3})`, whose `η` is `ln(2πY Γ^{1/12}/(2√π |Ai'(0)|))`.
    fn start_hanging(&self, x_top: f64) -> Result<Point, BendTwistError> {
        const AI_PRIME_0: f64 = 0.258_819_403_792_806_8;
        let xi = x_top.ln();
        let gamma = gamma_of(xi, self.y);
        let guess =
            (TWO_PI * self.y * gamma.powf(1.0 / 12.0) / (2.0 * PI.sqrt() * AI_PRIME_0)).ln();
        let mut p = self.solve_at_xi(xi, guess)?;
        if p.t[1] > 0.0 {
            p.t = [-p.t[0], -p.t[1]];
        }
        Ok(p)
    }
}

/// What a walk along the branch found.
enum WalkEnd {
    /// First loss of stability, refined: the point on the branch.
    Loss(Point),
    /// Left the `X` range without loss.
    Stable,
}

/// Distance between two points in the `(η, ln X)` plane.
fn walk_distance(a: &Point, b: &Point) -> f64 {
    (b.p[0] - a.p[0]).hypot(b.p[1] - a.p[1])
}

/// An event function on the branch: it changes sign where an eigenvalue crosses zero.
type EventFn = fn(&Point) -> f64;

/// Event functions.
fn f_event(p: &Point) -> f64 {
    p.f
}
fn fold_event(p: &Point) -> f64 {
    p.r_eta
}

/// Walks from the stable point `start` until stability is lost (refined with `fine`) or `X`
/// leaves `(x_low, x_high)`.
fn walk_to_loss(
    walk: &Tracer,
    fine: &Tracer,
    start: Point,
    x_low: f64,
    x_high: f64,
) -> Result<WalkEnd, BendTwistError> {
    let (lo, hi) = (x_low.ln(), x_high.ln());
    let mut h = 0.1;
    let mut before: Option<Point> = None;
    let mut a = start;
    for _ in 0..MAX_WALK {
        let b = walk.step(&a, &mut h)?;
        if b.f <= 0.0 {
            if let Some(e) = fine.refine(&a, &b, f_event)? {
                return Ok(WalkEnd::Loss(e));
            }
        }
        if b.r_eta <= 0.0 {
            if let Some(e) = fine.refine(&a, &b, fold_event)? {
                return Ok(WalkEnd::Loss(e));
            }
        }
        // A local minimum of f̂ at a: two crossings may hide between its neighbours.
        if let Some(z) = before {
            if a.f < z.f && a.f < b.f && a.f < 0.5 {
                let m = walk.minimize_f(&z, &b)?;
                if m.f <= 0.0 {
                    if let Some(e) = fine.refine(&z, &m, f_event)? {
                        return Ok(WalkEnd::Loss(e));
                    }
                }
            }
        }
        if b.p[1] >= hi || b.p[1] <= lo {
            return Ok(WalkEnd::Stable);
        }
        before = Some(a);
        a = b;
    }
    Err(walk.fail("too many continuation steps"))
}

// ---------------------------------------------------------------------------------------
// 1-D root finding and minimization
// ---------------------------------------------------------------------------------------

/// Brent's root finder on `[a, b]` with `f(a) = fa`, `f(b) = fb` of opposite signs.
fn brent_root<F>(
    mut f: F,
    a: f64,
    fa: f64,
    b: f64,
    fb: f64,
    tol: f64,
) -> Result<f64, BendTwistError>
where
    F: FnMut(f64) -> Result<f64, BendTwistError>,
{
    let (mut a, mut fa, mut b, mut fb) = (a, fa, b, fb);
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            if 2.0 * p < (3.0 * xm * q - (tol1 * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b)?;
    }
    Ok(b)
}

/// Golden-section minimization of `f` on `[a, b]`.
fn golden_min<F>(mut f: F, a: f64, b: f64, tol: f64) -> Result<f64, BendTwistError>
where
    F: FnMut(f64) -> Result<f64, BendTwistError>,
{
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (a, b);
    let mut x1 = b - g * (b - a);
    let mut x2 = a + g * (b - a);
    let mut f1 = f(x1)?;
    let mut f2 = f(x2)?;
    while b - a > tol {
        if f1 < f2 {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - g * (b - a);
            f1 = f(x1)?;
        } else {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + g * (b - a);
            f2 = f(x2)?;
        }
    }
    Ok(0.5 * (a + b))
}

// ---------------------------------------------------------------------------------------
// Public functions
// ---------------------------------------------------------------------------------------

/// The stability boundaries `X_c1(Y)`, `X_c2(Y)` at torsion ratio `c = GJ/EI`, with default
/// [`Settings`].
///
/// `lower` is where the planar branch, continued from the stress-free coil (`X → 0`), first
/// loses stability; `upper` is where the branch, continued down from the hanging rod, first
/// loses stability. Both are `None` when the coil reaches the hanging state without losing
/// stability (`Y < Y*`, see [`threshold_y`]). Refined to ~1e-9 relative in `X`.
///
/// Results are memoized per `(y, c)` (the sweeps ask for the same `Y` many times). Cost of a
/// first call in release builds: 1–25 ms for `Y ≤ 1`, ~40 ms at `Y = 2`, ~0.1 s at `Y = 10`,
/// ~0.25 s at `Y = 20`; a repeated call is a hash lookup (~30 ns). `y` must be in
/// `[Y_MIN, Y_MAX]`, `c` in `[C_MIN, C_MAX]`.
pub fn critical_boundaries(y: f64, c: f64) -> Result<StabilityBoundary, BendTwistError> {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    static CACHE: OnceLock<Mutex<HashMap<(u64, u64), StabilityBoundary>>> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    let key = (y.to_bits(), c.to_bits());
    // A poisoned lock only means another thread panicked while inserting; the map is still
    // a valid cache.
    if let Some(b) = cache.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        return Ok(*b);
    }
    let b = critical_boundaries_with(y, c, &Settings::default())?;
    cache
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, b);
    Ok(b)
}

/// [`critical_boundaries`] with explicit numerical settings (not memoized).
pub fn critical_boundaries_with(
    y: f64,
    c: f64,
    settings: &Settings,
) -> Result<StabilityBoundary, BendTwistError> {
    check_y(y)?;
    check_c(c)?;
    check_settings(settings)?;
    let (walk, fine) = Tracer::pair(y, c, settings.rtol);
    let x_top = x_top(c);
    let start = walk.start_coil()?;
    require_stable(&walk, &start, "the stress-free coil")?;
    let lower = match walk_to_loss(&walk, &fine, start, 0.0, x_top)? {
        WalkEnd::Stable => {
            return Ok(StabilityBoundary {
                y,
                lower: None,
                upper: None,
            })
        }
        WalkEnd::Loss(p) => p.x(),
    };
    let top = walk.start_hanging(x_top)?;
    require_stable(&walk, &top, "the hanging rod")?;
    // Walk on below X_c1: near the tongue tip the whole window can lie inside one step, and
    // the dip of f̂ only shows once f̂ rises again.
    let upper = match walk_to_loss(&walk, &fine, top, 0.5 * lower, f64::INFINITY)? {
        WalkEnd::Loss(p) => p.x(),
        WalkEnd::Stable => {
            return Err(
                walk.fail("the branch from the hanging rod passed X_c1 without losing stability")
            )
        }
    };
    if upper <= lower {
        return Err(walk.fail(format!(
            "inconsistent boundaries X_c1 = {lower}, X_c2 = {upper}"
        )));
    }
    Ok(StabilityBoundary {
        y,
        lower: Some(lower),
        upper: Some(upper),
    })
}

/// `X` where the continuation from the hanging rod starts: above every stability change of
/// the branch. Cheaper twisting (smaller `c`) destabilizes the tip curl up to larger `X`.
fn x_top(_c: f64) -> f64 {
    X_TOP
}

/// Checks, with the Morse index, that a start point of a walk is stable.
fn require_stable(tr: &Tracer, p: &Point, what: &str) -> Result<(), BendTwistError> {
    let index = morse_index(tr.y, tr.c, p.p[0], p.p[1], tr.rtol).map_err(|e| tr.fail(e))?;
    if index == (0, 0) && p.f > 0.0 && p.r_eta > 0.0 {
        Ok(())
    } else {
        Err(tr.fail(format!(
            "{what} at X = {} is not stable (index {index:?})",
            p.x()
        )))
    }
}

/// Ground-truth classification: `true` ("2-D") if the planar equilibrium at `(x, y)` is
/// stable, `false` ("3-D") if it is unstable, i.e. `X_c1(Y) < x < X_c2(Y)`.
///
/// Inside that window every planar equilibrium of the branch is unstable (checked by a full
/// trace of the branch with its Morse index in the tests), so the answer does not depend on
/// which planar state a loading path would follow. Uses the memoized
/// [`critical_boundaries`]. `x` must be finite and `> 0`.
pub fn planar_stable(x: f64, y: f64, c: f64) -> Result<bool, BendTwistError> {
    check_x_positive(x)?;
    Ok(critical_boundaries(y, c)?.planar_stable(x))
}

/// The stability function `f̂(X, Y)`: the sign of `f = δm_x(1)` of the reduced out-of-plane
/// system, normalized as `δm_x(1)/|(φ_x, φ_z, δm_x)(1)|` (dimensionless, in `[−1, 1]`).
///
/// It is evaluated on the planar branch continued from the stress-free coil: the first point
/// along the branch (from `X → 0`) with `X = x`. Before the first in-plane fold this is the
/// quasi-static loading path from `Γ = 0`. `f̂ > 0` for `x < X_c1` and `x > X_c2`; inside the
/// window its sign is `(−1)^{number of unstable out-of-plane modes}`, so it may be positive
/// there too (use [`planar_stable`] to classify). `x` must be `> 0` with
/// `Γ = (2πxy)³ ≤ GAMMA_MAX`.
pub fn stability_function(x: f64, y: f64, c: f64) -> Result<f64, BendTwistError> {
    Ok(planar_equilibrium(x, y, c)?.stability_function)
}

/// The planar equilibrium at `(x, y)` on the branch continued from the stress-free coil (first
/// point along the branch with `X = x`), with its stability data. Same domain as
/// [`stability_function`].
pub fn planar_equilibrium(x: f64, y: f64, c: f64) -> Result<PlanarEquilibrium, BendTwistError> {
    check_x_positive(x)?;
    check_y(y)?;
    check_c(c)?;
    let gamma = (TWO_PI * x * y).powi(3);
    if gamma > GAMMA_MAX {
        return Err(BendTwistError::InvalidParameter {
            name: "x",
            value: x,
            range: format!(
                "> 0 with Γ = (2πxy)³ ≤ {GAMMA_MAX:e}, i.e. x ≤ {} at y = {y}",
                GAMMA_MAX.cbrt() / (TWO_PI * y)
            ),
        });
    }
    let (walk, fine) = Tracer::pair(y, c, Settings::default().rtol);
    let xi = x.ln();
    let mut a = walk.start_coil()?;
    let guess = if a.p[1] >= xi {
        // Below the start (Γ ≤ 1), where the branch is a graph over X.
        a.p[0]
    } else {
        let mut h = 0.1;
        let mut guess = None;
        for _ in 0..MAX_WALK {
            let b = walk.step(&a, &mut h)?;
            if b.p[1] >= xi {
                guess = Some(a.p[0] + (b.p[0] - a.p[0]) * (xi - a.p[1]) / (b.p[1] - a.p[1]));
                break;
            }
            a = b;
        }
        guess.ok_or_else(|| walk.fail("too many continuation steps"))?
    };
    // Land exactly on X = x (Newton in η at fixed ξ from the interpolated η).
    let (p, _, _) = fine
        .correct([guess, xi], [0.0, 1.0], xi)
        .ok_or_else(|| fine.fail("could not land on the requested X"))?;
    let shot = fine.shoot(p).map_err(|e| fine.fail(e.to_string()))?;
    let index = morse_index(y, c, p[0], xi, fine.rtol).map_err(|e| fine.fail(e))?;
    let ln_k0 = p[0] - 2.0 / 3.0 * gamma.sqrt();
    Ok(PlanarEquilibrium {
        x,
        y,
        gamma,
        clamp_curvature: ln_k0.exp(),
        ln_clamp_curvature: ln_k0,
        clamp_moment: TWO_PI * y - ln_k0.exp(),
        tip_angle: shot.tip,
        stability_function: shot.f,
        index,
    })
}

/// Traces the planar branch at `(y, c)` from the stress-free coil up to `X = x_max` and
/// returns every change of stability with the Morse index on both sides (diagnostics: the
/// structure of the solution set; ~0.1 s at `Y = 1`, seconds at `Y = 10`). At every
/// continuation point it also checks that the index parities agree with the signs of `f̂`
/// and of the in-plane shooting derivative, and that the index only changes where one of
/// them changes sign.
///
/// `x_max` must be `> 0` with `(2π x_max y)³ ≤ GAMMA_MAX`.
pub fn planar_branch(
    y: f64,
    c: f64,
    x_max: f64,
    settings: &Settings,
) -> Result<PlanarBranch, BendTwistError> {
    check_y(y)?;
    check_c(c)?;
    check_x_positive(x_max)?;
    check_settings(settings)?;
    if (TWO_PI * x_max * y).powi(3) > GAMMA_MAX {
        return Err(BendTwistError::InvalidParameter {
            name: "x_max",
            value: x_max,
            range: format!("> 0 with (2π x_max y)³ ≤ {GAMMA_MAX:e}"),
        });
    }
    let (walk, _) = Tracer::pair(y, c, settings.rtol);
    let index_of =
        |p: &Point| morse_index(y, c, p.p[0], p.p[1], walk.rtol).map_err(|e| walk.fail(e));
    let mut a = walk.start_coil()?;
    let mut index_a = index_of(&a)?;
    let mut events = Vec::new();
    let mut points = 1;
    let mut h = 0.1;
    let xi_max = x_max.ln();
    while a.p[1] < xi_max {
        if points > MAX_WALK {
            return Err(walk.fail("too many continuation steps"));
        }
        // A step is kept when the index changes exactly as the signs of f̂ and ∂R/∂η say
        // (one eigenvalue per sign change); otherwise two changes hid in it: retry shorter.
        let mut tries = 0;
        let (b, index_b, f_crossed, fold_crossed) = loop {
            let b = walk.step(&a, &mut h)?;
            let index_b = index_of(&b)?;
            if (b.f > 0.0) != (index_b.1 % 2 == 0) || (b.r_eta > 0.0) != (index_b.0 % 2 == 0) {
                return Err(walk.fail(format!(
                    "index {index_b:?} inconsistent with the signs of f and R_η at X = {}",
                    b.x()
                )));
            }
            let f_crossed = (a.f > 0.0) != (b.f > 0.0);
            let fold_crossed = (a.r_eta > 0.0) != (b.r_eta > 0.0);
            let d_in = index_b.0.abs_diff(index_a.0);
            let d_out = index_b.1.abs_diff(index_a.1);
            if d_in == u32::from(fold_crossed) && d_out == u32::from(f_crossed) {
                break (b, index_b, f_crossed, fold_crossed);
            }
            tries += 1;
            if tries > 20 {
                return Err(walk.fail(format!(
                    "index changes from {index_a:?} to {index_b:?} near X = {} not resolved",
                    b.x()
                )));
            }
            h = 0.25 * h.min(walk_distance(&a, &b));
        };
        points += 1;
        let crossings: [(bool, EventKind, EventFn); 2] = [
            (f_crossed, EventKind::OutOfPlane, f_event),
            (fold_crossed, EventKind::InPlaneFold, fold_event),
        ];
        for (crossed, kind, event) in crossings {
            if crossed {
                // Located at the walking tolerance (diagnostics).
                let e = walk.refine(&a, &b, event)?.unwrap_or(b);
                events.push(BranchEvent {
                    x: e.x(),
                    kind,
                    index_before: index_a,
                    index_after: index_b,
                });
            }
        }
        index_a = index_b;
        a = b;
    }
    Ok(PlanarBranch {
        y,
        c,
        events,
        points,
        final_index: index_a,
    })
}

/// The threshold `Y*(c)` below which the planar equilibrium is stable for every `X`: the tip
/// of the unstable tongue, where `X_c1 = X_c2` (see [`tongue_tip`]).
pub fn threshold_y(c: f64) -> Result<f64, BendTwistError> {
    Ok(tongue_tip(c)?.0)
}

/// `(Y*, X*)`: the tip of the unstable tongue, found as the root in `Y` of the first local
/// minimum of `f̂` along the branch from the coil (positive below `Y*`, negative above);
/// `X*` is where that minimum lies at `Y*`. Refined to ~1e-9 in `Y`. Cost: ~0.2 s.
pub fn tongue_tip(c: f64) -> Result<(f64, f64), BendTwistError> {
    check_c(c)?;
    let rtol = Settings::default().rtol;
    let min_f = |y: f64| -> Result<(f64, f64), BendTwistError> {
        let (walk, fine) = Tracer::pair(y, c, rtol);
        let mut a = walk.start_coil()?;
        let mut h = 0.1;
        let mut before: Option<Point> = None;
        for _ in 0..MAX_WALK {
            let b = walk.step(&a, &mut h)?;
            if let Some(z) = before {
                if a.f <= z.f && a.f < b.f {
                    let m = fine.minimize_f(&z, &b)?;
                    return Ok((m.f, m.x()));
                }
            }
            if b.p[1] > x_top(c).ln() {
                break;
            }
            before = Some(a);
            a = b;
        }
        Err(walk.fail("no minimum of the stability function"))
    };
    // Bracket: f̂ has a positive minimum below Y*, a negative one above.
    let (mut lo, mut hi) = (0.7, 1.0);
    let mut g_lo = min_f(lo)?.0;
    let mut g_hi = min_f(hi)?.0;
    for _ in 0..10 {
        if g_lo > 0.0 && g_hi <= 0.0 {
            break;
        }
        if g_lo <= 0.0 {
            (hi, g_hi) = (lo, g_lo);
            lo = (0.7 * lo).max(Y_MIN);
            g_lo = min_f(lo)?.0;
        } else {
            (lo, g_lo) = (hi, g_hi);
            hi = (1.4 * hi).min(Y_MAX);
            g_hi = min_f(hi)?.0;
        }
    }
    if !(g_lo > 0.0 && g_hi <= 0.0) {
        return Err(BendTwistError::NoConvergence {
            y: hi,
            c,
            detail: "no sign change of the minimum of f̂ in Y".into(),
        });
    }
    let y_star = brent_root(|y| Ok(min_f(y)?.0), lo, g_lo, hi, g_hi, 1e-9)?;
    Ok((y_star, min_f(y_star)?.1))
}

// ---------------------------------------------------------------------------------------
// General linearization (verification)
// ---------------------------------------------------------------------------------------

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

#[cfg(test)]
mod tests {
    use super::*;

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
