//! Master curve of the cantilever under self-weight: the inextensible heavy elastica,
//! computed independently of any rod model.
//!
//! A uniform, inextensible, unshearable rod of length `L`, bending stiffness `EI` and weight
//! per length `ρAg` is clamped horizontally at `s = 0` and free at `s = L`; gravity points
//! along `−y`. With `ŝ = s/L` and `θ(ŝ)` the tangent angle measured *below* the horizontal,
//! the moment balance is
//!
//! ```text
//! θ'' = −Γ (1 − ŝ) cos θ,   θ(0) = 0,   θ'(1) = 0,   Γ = ρ A g L³ / (E I),
//! Δx = ∫₀¹ cos θ dŝ,        Δy = ∫₀¹ sin θ dŝ       (in units of L),
//! ```
//!
//! and the master curve is the ratio `Δy/Δx` of the end-point coordinate differences as
//! a function of `Γ`. For `Γ → 0` it tends to the small-deflection beam, `Γ/8`; for large
//! `Γ` the rod hangs almost vertically below a clamp boundary layer of width `~1/√Γ`.
//!
//! Two methods that share nothing but the equations:
//!
//! * [`heavy_elastica`]: multiple shooting. Single shooting on `θ'(0)` is hopeless for
//!   large `Γ`: the linearised problem `δθ'' = Γ(1 − ŝ) sin θ δθ` has modes growing like
//!   `exp(∫√(Γ(1 − ŝ)) dŝ) = exp(⅔√Γ)` (`e^66` at `Γ = 10⁴`). The interval is cut into
//!   segments with a growth of at most `e²` each, the unknowns are `(θ, θ')` at every
//!   segment start, and Newton solves the matching conditions with the Jacobian from the
//!   variational equations integrated along (hand-written Dormand–Prince, [`crate::ode`],
//!   at `rtol = 1e-12`).
//! * [`heavy_elastica_finite_difference`] / [`heavy_elastica_richardson`]: second-order
//!   finite differences on a grid graded towards the clamp, Newton with a tridiagonal
//!   solve, trapezoid quadrature, and Richardson extrapolation of two grids.

use crate::ode::{self, OdeError, Options};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::FRAC_PI_2;

/// Smallest accepted load parameter `Γ` (below it the curve is `Γ/8` to 15 digits anyway).
pub const GAMMA_MIN: f64 = 1e-12;
/// Largest accepted load parameter `Γ`.
pub const GAMMA_MAX: f64 = 1e6;
/// Largest accepted finite-difference grid size `n` (memory stays below ~0.5 GB).
pub const MAX_GRID_SIZE: usize = 1 << 22;
/// Largest number of intervals [`HeavyElastica::shape`] returns.
pub const MAX_SHAPE_INTERVALS: usize = 1 << 24;

/// Relative tolerance of the ODE integration in the converged shooting solution.
const RTOL_FINAL: f64 = 1e-12;
/// Relative tolerance of the first Newton sweeps (tightened as Newton converges).
const RTOL_START: f64 = 1e-6;
/// Newton on the shooting unknowns stops once a step computed from an `RTOL_FINAL` sweep
/// is below this (scaled): the error left after that step is `O(step²)` ≲ 1e-14.
const SHOOTING_STEP_TOL: f64 = 1e-7;
/// Below this `Γ` the linear beam is a good enough first guess.
const GAMMA_LINEAR_GUESS: f64 = 2.0;
/// The FD solver reaches `Γ` by continuation from here (the linear guess is good there).
const GAMMA_FD_START: f64 = 1.0;

/// Why a master-curve point could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MasterCurveError {
    /// `Γ` is NaN, infinite, or outside `[GAMMA_MIN, GAMMA_MAX]`.
    #[error(
        "invalid gamma = {gamma}: the load parameter gamma = rho*A*g*L^3/(E*I) must be finite \
         and in [{GAMMA_MIN:e}, {GAMMA_MAX:e}]"
    )]
    InvalidGamma {
        /// The rejected value.
        gamma: f64,
    },
    /// The finite-difference grid size is outside `[min, max]`.
    #[error("invalid grid size n = {n}: must be in [{min}, {max}]")]
    InvalidGridSize {
        /// The rejected value.
        n: usize,
        /// Smallest accepted value.
        min: usize,
        /// Largest accepted value.
        max: usize,
    },
    /// Newton did not converge (or converged to a non-physical branch).
    #[error("{method} did not converge at gamma = {gamma}: {detail}")]
    NoConvergence {
        /// Which solver failed.
        method: &'static str,
        /// The load parameter.
        gamma: f64,
        /// What went wrong.
        detail: String,
    },
}

/// One point of the master curve: the equilibrium of the heavy cantilever at load `Γ`.
///
/// Lengths are in units of the rod length `L`, curvatures in units of `1/L`.
#[derive(Debug, Clone)]
pub struct HeavyElastica {
    /// Load parameter `Γ = ρAgL³/(EI)` (dimensionless).
    pub gamma: f64,
    /// Curvature at the clamp, `θ'(0)`, in units of `1/L` (equals the clamp moment in units
    /// of `EI/L`).
    pub clamp_curvature: f64,
    /// Tangent angle at the free end, `θ(1)`, in radians below the horizontal.
    pub tip_angle: f64,
    /// Horizontal distance from the clamp to the tip, `∫₀¹ cos θ dŝ`, in units of `L`.
    pub dx: f64,
    /// Vertical drop from the clamp to the tip, `∫₀¹ sin θ dŝ`, in units of `L` (positive).
    pub dy: f64,
    profile: Profile,
}

/// What [`HeavyElastica::shape`] evaluates.
#[derive(Debug, Clone)]
enum Profile {
    /// Converged multiple-shooting data: segment boundaries `ŝ_k` (`M + 1` of them),
    /// `(θ, θ')` and `(x, y)` at each of the `M` segment starts (`y` positive downward).
    Shooting {
        starts: Vec<f64>,
        z: Vec<[f64; 2]>,
        origins: Vec<[f64; 2]>,
    },
    /// Grid nodes `ŝ_i` and `(x, y)` there (`y` positive downward), linearly interpolated.
    Grid { s: Vec<f64>, xy: Vec<[f64; 2]> },
}

impl HeavyElastica {
    /// The master-curve value `Δy/Δx` (dimensionless, positive).
    pub fn ratio(&self) -> f64 {
        self.dy / self.dx
    }

    /// The centreline at `n + 1` equally spaced arc-length stations `ŝ = j/n`, from the
    /// clamp `(0, 0)` to the tip `(dx, −dy)`, as `(x, y)` in units of `L` with `y` negative
    /// downward.
    ///
    /// For the shooting solution the points are re-integrated from the converged segment
    /// starts (`rtol = 1e-12`); for the finite-difference solutions they are linearly
    /// interpolated between grid nodes. `n = 0` gives the clamp only; `n` is capped at
    /// [`MAX_SHAPE_INTERVALS`].
    pub fn shape(&self, n: usize) -> Vec<[f64; 2]> {
        let n = n.min(MAX_SHAPE_INTERVALS);
        if n == 0 {
            return vec![[0.0, 0.0]];
        }
        let stations = (0..=n).map(|j| j as f64 / n as f64);
        match &self.profile {
            Profile::Shooting { starts, z, origins } => {
                shooting_shape(self.gamma, starts, z, origins, stations)
            }
            Profile::Grid { s, xy } => {
                let mut i = 0;
                stations
                    .map(|t| {
                        while i + 2 < s.len() && s[i + 1] <= t {
                            i += 1;
                        }
                        let w = ((t - s[i]) / (s[i + 1] - s[i])).clamp(0.0, 1.0);
                        let x = xy[i][0] + w * (xy[i + 1][0] - xy[i][0]);
                        let y = xy[i][1] + w * (xy[i + 1][1] - xy[i][1]);
                        [x, -y]
                    })
                    .collect()
            }
        }
    }
}

/// The master-curve value `Δy/Δx` at load `Γ` (multiple shooting, see [`heavy_elastica`]).
pub fn master_ratio(gamma: f64) -> Result<f64, MasterCurveError> {
    heavy_elastica(gamma).map(|e| e.ratio())
}

fn check_gamma(gamma: f64) -> Result<(), MasterCurveError> {
    if gamma.is_finite() && (GAMMA_MIN..=GAMMA_MAX).contains(&gamma) {
        Ok(())
    } else {
        Err(MasterCurveError::InvalidGamma { gamma })
    }
}

// ---------------------------------------------------------------------------------------
// Multiple shooting
// ---------------------------------------------------------------------------------------

/// Solves the heavy elastica at load `Γ` by multiple shooting (the reference method).
///
/// Newton starts from the linear beam (`Γ ≤ 2`) or from the clamp boundary-layer solution
/// (larger `Γ`), with loose integrator tolerances that tighten to `1e-12` as it converges;
/// should it fail, the solution at `Γ/4` is used as the guess (continuation). The result is
/// checked to lie on the physical branch (`0 < θ ≤ π/2`, `θ' ≥ 0`).
///
/// `Δy/Δx` agrees with the Richardson-extrapolated finite differences to ~1e-13 relative
/// over `[1e-3, 1e5]`. Cost in release builds: ~0.1 ms at `Γ = 1`, ~2 ms at `Γ = 10⁴`,
/// ~9 ms at `Γ = 10⁵`.
pub fn heavy_elastica(gamma: f64) -> Result<HeavyElastica, MasterCurveError> {
    check_gamma(gamma)?;
    let sol = shooting_with_continuation(gamma, 0)?;
    let dx = sol.increments.iter().map(|d| d[0]).sum();
    let dy = sol.increments.iter().map(|d| d[1]).sum();
    let mut origins = Vec::with_capacity(sol.z.len());
    let mut acc = [0.0, 0.0];
    for inc in &sol.increments {
        origins.push(acc);
        acc = [acc[0] + inc[0], acc[1] + inc[1]];
    }
    Ok(HeavyElastica {
        gamma,
        clamp_curvature: sol.z[0][1],
        tip_angle: sol.tip_angle,
        dx,
        dy,
        profile: Profile::Shooting {
            starts: sol.starts,
            z: sol.z,
            origins,
        },
    })
}

/// A converged multiple-shooting solution.
struct ShootingSolution {
    /// Segment boundaries, `M + 1` values from 0 to 1.
    starts: Vec<f64>,
    /// `(θ, θ')` at the `M` segment starts.
    z: Vec<[f64; 2]>,
    /// `(Δx, Δy)` over each segment.
    increments: Vec<[f64; 2]>,
    /// `θ(1)`.
    tip_angle: f64,
}

/// Typical magnitudes of `θ` and `θ'` (only used to scale norms).
fn scales(gamma: f64) -> (f64, f64) {
    (
        (gamma / 6.0).min(FRAC_PI_2),
        (gamma / 2.0).min((2.0 * gamma).sqrt()),
    )
}

/// Segment boundaries: `M` segments of equal `∫√(1 − ŝ) dŝ`, so that each has a growth of
/// at most `exp(⅔√Γ / M) ≤ e²`.
fn segment_starts(gamma: f64) -> Vec<f64> {
    let growth = 2.0 / 3.0 * gamma.sqrt();
    let m = ((growth / 2.0).ceil() as usize).max(4);
    (0..=m)
        .map(|k| {
            if k == m {
                1.0
            } else {
                1.0 - (1.0 - k as f64 / m as f64).powf(2.0 / 3.0)
            }
        })
        .collect()
}

/// First guess of `(θ, θ')` at `ŝ` without any solve.
fn direct_guess(gamma: f64, s: f64) -> [f64; 2] {
    if gamma <= GAMMA_LINEAR_GUESS {
        // Small-deflection beam: θ' = Γ(1 − ŝ)²/2.
        let r = 1.0 - s;
        [gamma * (1.0 - r * r * r) / 6.0, gamma * r * r / 2.0]
    } else {
        // Clamp boundary layer of θ'' = −Γ cos θ with θ → π/2:
        // tan((π/2 − θ)/4) = tan(π/8) e^{−√Γ ŝ}, θ' = √(2Γ(1 − sin θ)).
        let t = (std::f64::consts::PI / 8.0).tan() * (-gamma.sqrt() * s).exp();
        let theta = FRAC_PI_2 - 4.0 * t.atan();
        [theta, (2.0 * gamma * (1.0 - theta.sin())).max(0.0).sqrt()]
    }
}

/// Integrator options for an interval of length `len`.
fn ode_options(gamma: f64, rtol: f64, len: f64) -> Options {
    Options {
        rtol,
        // Pure relative control in practice; the floor only matters for states that are
        // exactly zero, and it scales with the size of θ for tiny Γ.
        atol: rtol * 1e-3 * scales(gamma).0.min(1.0),
        max_steps: 1_000_000,
        // The generic starting-step heuristic is fooled by x, y starting at exactly zero
        // under that tiny atol; a fraction of the interval costs at most a rejection or two.
        initial_step: Some(len.abs() / 32.0),
    }
}

/// Number of states of [`rhs_variational`].
const NV: usize = 12;

/// The heavy elastica with the running `(x, y)` and the variational equations for both:
/// `[θ, θ', ∂θ/∂θ₀, ∂θ/∂θ'₀, ∂θ'/∂θ₀, ∂θ'/∂θ'₀, x, y, ∂x/∂θ₀, ∂x/∂θ'₀, ∂y/∂θ₀, ∂y/∂θ'₀]`
/// (`y` positive downward, `θ₀, θ'₀` the values at the segment start).
fn rhs_variational(gamma: f64, s: f64, u: &[f64; NV]) -> [f64; NV] {
    let (sin, cos) = u[0].sin_cos();
    let load = gamma * (1.0 - s);
    let k = load * sin;
    [
        u[1],
        -load * cos,
        u[4],
        u[5],
        k * u[2],
        k * u[3],
        cos,
        sin,
        -sin * u[2],
        -sin * u[3],
        cos * u[2],
        cos * u[3],
    ]
}

/// Integration of every segment from the current unknowns.
struct Sweep {
    /// Scaled-by-nothing residual of the `2M` matching conditions.
    residual: Vec<f64>,
    /// Transfer matrices `∂(θ, θ')_end / ∂(θ, θ')_start`, row-major.
    transfer: Vec<[f64; 4]>,
    /// `(θ, θ')` at the end of each segment.
    ends: Vec<[f64; 2]>,
    /// `(Δx, Δy)` over each segment.
    increments: Vec<[f64; 2]>,
    /// `∂(Δx, Δy)/∂(θ, θ')_start` of each segment, row-major.
    sensitivities: Vec<[f64; 4]>,
}

fn sweep(gamma: f64, starts: &[f64], z: &[[f64; 2]], rtol: f64) -> Result<Sweep, OdeError> {
    let m = z.len();
    let mut transfer = Vec::with_capacity(m);
    let mut ends = Vec::with_capacity(m);
    let mut increments = Vec::with_capacity(m);
    let mut sensitivities = Vec::with_capacity(m);
    for (k, zk) in z.iter().enumerate() {
        let mut u0 = [0.0; NV];
        u0[..6].copy_from_slice(&[zk[0], zk[1], 1.0, 0.0, 0.0, 1.0]);
        let sol = ode::integrate(
            |s, u: &[f64; NV]| rhs_variational(gamma, s, u),
            starts[k],
            u0,
            starts[k + 1],
            &ode_options(gamma, rtol, starts[k + 1] - starts[k]),
        )?;
        let u = sol.y;
        ends.push([u[0], u[1]]);
        transfer.push([u[2], u[3], u[4], u[5]]);
        increments.push([u[6], u[7]]);
        sensitivities.push([u[8], u[9], u[10], u[11]]);
    }
    // Conditions: θ(0) = 0; continuity of (θ, θ') at each interior boundary; θ'(1) = 0.
    let mut residual = Vec::with_capacity(2 * m);
    residual.push(z[0][0]);
    for k in 0..m - 1 {
        residual.push(ends[k][0] - z[k + 1][0]);
        residual.push(ends[k][1] - z[k + 1][1]);
    }
    residual.push(ends[m - 1][1]);
    Ok(Sweep {
        residual,
        transfer,
        ends,
        increments,
        sensitivities,
    })
}

/// The Newton step `J δ = −R` of the multiple-shooting system (unknowns ordered
/// `θ₀, θ'₀, θ₁, θ'₁, …`).
fn newton_step(sw: &Sweep) -> Option<Vec<f64>> {
    let m = sw.transfer.len();
    let n = 2 * m;
    let mut jac = DMatrix::<f64>::zeros(n, n);
    jac[(0, 0)] = 1.0;
    for k in 0..m - 1 {
        let t = &sw.transfer[k];
        let (r, c) = (1 + 2 * k, 2 * k);
        jac[(r, c)] = t[0];
        jac[(r, c + 1)] = t[1];
        jac[(r + 1, c)] = t[2];
        jac[(r + 1, c + 1)] = t[3];
        jac[(r, c + 2)] = -1.0;
        jac[(r + 1, c + 3)] = -1.0;
    }
    let t = &sw.transfer[m - 1];
    jac[(n - 1, n - 2)] = t[2];
    jac[(n - 1, n - 1)] = t[3];
    let rhs = DVector::from_iterator(n, sw.residual.iter().map(|r| -r));
    let delta = jac.lu().solve(&rhs)?;
    delta
        .iter()
        .all(|v| v.is_finite())
        .then(|| delta.iter().copied().collect())
}

/// Residual norm with θ-rows scaled by the typical θ and θ'-rows by the typical θ'.
fn residual_norm(gamma: f64, r: &[f64]) -> f64 {
    let (ts, ps) = scales(gamma);
    let n = r.len();
    r.iter()
        .enumerate()
        .map(|(i, v)| {
            // Row 0 is θ, then pairs (θ, θ'), the last row is θ'.
            let is_theta = i == 0 || (i < n - 1 && i % 2 == 1);
            (v / if is_theta { ts } else { ps }).abs()
        })
        .fold(0.0, f64::max)
}

/// Step norm with θ scaled by the typical θ and θ' by the typical θ'.
fn step_norm(gamma: f64, d: &[f64]) -> f64 {
    let (ts, ps) = scales(gamma);
    d.chunks(2)
        .map(|c| (c[0] / ts).abs().max((c[1] / ps).abs()))
        .fold(0.0, f64::max)
}

/// Damped Newton on the multiple-shooting system from the guess `z`.
fn shooting_newton(
    gamma: f64,
    starts: Vec<f64>,
    mut z: Vec<[f64; 2]>,
) -> Result<ShootingSolution, String> {
    const MAX_ITER: usize = 60;
    let mut rtol = RTOL_START;
    let mut sw = sweep(gamma, &starts, &z, rtol).map_err(|e| e.to_string())?;
    for _ in 0..MAX_ITER {
        let delta = newton_step(&sw).ok_or("singular multiple-shooting Jacobian")?;
        let d = step_norm(gamma, &delta);
        if rtol <= RTOL_FINAL && d <= SHOOTING_STEP_TOL {
            // Quadratic regime with an accurate Jacobian: take the last step and update the
            // outputs linearly (error O(d²)) instead of paying for another tight sweep.
            return finish_shooting(starts, z, sw, &delta);
        }
        // Integrate the trial point accurately enough for the next (quadratically smaller)
        // step; loose sweeps early on are what makes Newton cheap.
        let trial_rtol = (0.01 * d * d).clamp(RTOL_FINAL, RTOL_START).min(rtol);
        let r0 = residual_norm(gamma, &sw.residual);
        let mut lambda = 1.0;
        loop {
            let zt: Vec<[f64; 2]> = z
                .iter()
                .zip(delta.chunks(2))
                .map(|(zk, dk)| [zk[0] + lambda * dk[0], zk[1] + lambda * dk[1]])
                .collect();
            if let Ok(st) = sweep(gamma, &starts, &zt, trial_rtol) {
                let rt = residual_norm(gamma, &st.residual);
                if rt <= (1.0 - lambda / 4.0) * r0 || rt <= 1e-9 {
                    z = zt;
                    sw = st;
                    break;
                }
            }
            lambda /= 2.0;
            if lambda < 1.0 / 1024.0 {
                return Err("damped Newton step failed to reduce the residual".into());
            }
        }
        rtol = trial_rtol;
    }
    Err(format!("no convergence in {MAX_ITER} Newton iterations"))
}

/// Checks the physical branch and packages a converged solution.
///
/// On the physical branch `0 < θ < π/2` and `θ' > 0` on `(0, 1)`: `θ'` decreases while
/// `θ < π/2`, and once `θ` passed `π/2` with `θ' > 0`, `θ'` could never return to zero.
fn finish_shooting(
    starts: Vec<f64>,
    mut z: Vec<[f64; 2]>,
    sw: Sweep,
    delta: &[f64],
) -> Result<ShootingSolution, String> {
    let m = z.len();
    let mut increments = sw.increments;
    for (k, dk) in delta.chunks(2).enumerate() {
        let sk = &sw.sensitivities[k];
        increments[k][0] += sk[0] * dk[0] + sk[1] * dk[1];
        increments[k][1] += sk[2] * dk[0] + sk[3] * dk[1];
        z[k] = [z[k][0] + dk[0], z[k][1] + dk[1]];
    }
    let t = &sw.transfer[m - 1];
    let tip_angle = sw.ends[m - 1][0] + t[0] * delta[2 * m - 2] + t[1] * delta[2 * m - 1];
    let slack = 1e-8;
    let physical = z
        .iter()
        .skip(1)
        .all(|zk| zk[0] > 0.0 && zk[0] <= FRAC_PI_2 + slack && zk[1] >= -slack * z[0][1])
        && z[0][1] > 0.0
        && tip_angle <= FRAC_PI_2 + slack
        && z.windows(2).all(|w| w[1][0] >= w[0][0] - slack);
    if !physical {
        return Err("converged to a non-physical branch".into());
    }
    Ok(ShootingSolution {
        starts,
        z,
        increments,
        tip_angle,
    })
}

/// Newton from the direct guess; if that fails, continuation from `Γ/4`.
fn shooting_with_continuation(
    gamma: f64,
    depth: usize,
) -> Result<ShootingSolution, MasterCurveError> {
    let starts = segment_starts(gamma);
    let m = starts.len() - 1;
    let guess: Vec<[f64; 2]> = starts[..m]
        .iter()
        .map(|&s| direct_guess(gamma, s))
        .collect();
    let first = match shooting_newton(gamma, starts.clone(), guess) {
        Ok(sol) => return Ok(sol),
        Err(e) => e,
    };
    let fail = |detail: String| MasterCurveError::NoConvergence {
        method: "multiple shooting",
        gamma,
        detail,
    };
    if gamma <= GAMMA_LINEAR_GUESS || depth >= 40 {
        return Err(fail(first));
    }
    let coarse = shooting_with_continuation(gamma / 4.0, depth + 1)?;
    let guess =
        evaluate_theta(gamma / 4.0, &coarse, &starts[..m]).map_err(|e| fail(e.to_string()))?;
    shooting_newton(gamma, starts, guess).map_err(fail)
}

/// `(θ, θ')` of a converged solution (at its own `Γ`) at the sorted stations `at`.
fn evaluate_theta(
    gamma: f64,
    sol: &ShootingSolution,
    at: &[f64],
) -> Result<Vec<[f64; 2]>, OdeError> {
    let mut out = Vec::with_capacity(at.len());
    let mut k = 0;
    let m = sol.z.len();
    for &s in at {
        while k + 1 < m && sol.starts[k + 1] <= s {
            k += 1;
        }
        let u = ode::integrate(
            |t, u: &[f64; 2]| [u[1], -gamma * (1.0 - t) * u[0].cos()],
            sol.starts[k],
            sol.z[k],
            s,
            &ode_options(gamma, 1e-8, s - sol.starts[k]),
        )?;
        out.push(u.y);
    }
    Ok(out)
}

/// Re-integrates `(θ, θ', x, y)` from the converged segment starts to the stations.
fn shooting_shape(
    gamma: f64,
    starts: &[f64],
    z: &[[f64; 2]],
    origins: &[[f64; 2]],
    stations: impl Iterator<Item = f64>,
) -> Vec<[f64; 2]> {
    let m = z.len();
    let mut k = 0;
    let seg_state = |k: usize| [z[k][0], z[k][1], origins[k][0], origins[k][1]];
    let mut pos = starts[0];
    let mut state = seg_state(0);
    stations
        .map(|s| {
            while k + 1 < m && starts[k + 1] <= s {
                k += 1;
                pos = starts[k];
                state = seg_state(k);
            }
            match ode::integrate(
                |t, u: &[f64; 4]| {
                    let (sin, cos) = u[0].sin_cos();
                    [u[1], -gamma * (1.0 - t) * cos, cos, sin]
                },
                pos,
                state,
                s,
                &ode_options(gamma, RTOL_FINAL, s - pos),
            ) {
                Ok(sol) => {
                    pos = s;
                    state = sol.y;
                    [state[2], -state[3]]
                }
                // Cannot happen from converged data; NaN rather than a panic.
                Err(_) => [f64::NAN, f64::NAN],
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// Finite differences
// ---------------------------------------------------------------------------------------

/// Grid nodes `ŝ_i = g(i/n)`, `g(u) = (e^{βu} − 1)/(e^β − 1)`, `β = ½ ln Γ` (uniform for
/// `Γ ≤ 1`): a smooth map (so the error expansion stays in even powers of `1/n`) that puts
/// ~15 % of the nodes into the clamp boundary layer of width `1/√Γ`.
fn fd_grid(gamma: f64, n: usize) -> Vec<f64> {
    let beta = 0.5 * gamma.ln().max(0.0);
    (0..=n)
        .map(|i| {
            let u = i as f64 / n as f64;
            if i == n {
                1.0
            } else if beta < 1e-9 {
                u
            } else {
                (beta * u).exp_m1() / beta.exp_m1()
            }
        })
        .collect()
}

/// Newton on the FD equations at load `gamma` from `theta` (in place); `theta[0] = 0`.
///
/// Equation `i` (interior), multiplied by the half-cell width `w_i = (h_{i−1} + h_i)/2`:
/// `(θ_{i+1} − θ_i)/h_i − (θ_i − θ_{i−1})/h_{i−1} + w_i Γ(1 − ŝ_i) cos θ_i = 0`.
/// At the tip a mirrored ghost node for `θ'(1) = 0` gives
/// `2(θ_{N−1} − θ_N)/h_{N−1} + h_{N−1} Γ(1 − ŝ_N) cos θ_N = 0`; the load term vanishes
/// there, so any second-order closure of `θ'(1) = 0` reduces to the same `θ_N = θ_{N−1}`.
fn fd_newton(gamma: f64, s: &[f64], theta: &mut [f64]) -> Result<(), String> {
    const MAX_ITER: usize = 100;
    let n = s.len() - 1;
    let h: Vec<f64> = s.windows(2).map(|w| w[1] - w[0]).collect();
    let (ts, _) = scales(gamma);
    // Unknowns θ_1..θ_N, index j = i − 1.
    let mut sub = vec![0.0; n];
    let mut diag = vec![0.0; n];
    let mut sup = vec![0.0; n];
    let mut rhs = vec![0.0; n];
    let mut previous = f64::INFINITY;
    for _ in 0..MAX_ITER {
        for i in 1..=n {
            let (sin, cos) = theta[i].sin_cos();
            let load = gamma * (1.0 - s[i]);
            let j = i - 1;
            if i < n {
                let w = 0.5 * (h[i - 1] + h[i]);
                rhs[j] = -((theta[i + 1] - theta[i]) / h[i] - (theta[i] - theta[i - 1]) / h[i - 1]
                    + w * load * cos);
                sub[j] = 1.0 / h[i - 1];
                sup[j] = 1.0 / h[i];
                diag[j] = -1.0 / h[i] - 1.0 / h[i - 1] - w * load * sin;
            } else {
                let a = h[n - 1];
                rhs[j] = -(2.0 * (theta[n - 1] - theta[n]) / a + a * load * cos);
                sub[j] = 2.0 / a;
                sup[j] = 0.0;
                diag[j] = -2.0 / a - a * load * sin;
            }
        }
        solve_tridiagonal(&sub, &mut diag, &sup, &mut rhs)
            .ok_or("singular finite-difference Jacobian")?;
        let d = rhs.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if !d.is_finite() {
            return Err("non-finite Newton step".into());
        }
        // Keep steps moderate so the iteration stays on the physical branch.
        let lambda = (0.5 / d).min(1.0);
        for (t, dt) in theta[1..].iter_mut().zip(&rhs) {
            *t += lambda * dt;
        }
        if d <= 1e-13 * ts || (d <= 1e-9 * ts && d > 0.5 * previous) {
            return Ok(());
        }
        previous = d;
    }
    Err(format!("no convergence in {MAX_ITER} Newton iterations"))
}

/// Thomas algorithm (no pivoting: the FD Jacobian is diagonally dominant on the physical
/// branch, `0 ≤ θ ≤ π/2`). Overwrites `rhs` with the solution.
fn solve_tridiagonal(sub: &[f64], diag: &mut [f64], sup: &[f64], rhs: &mut [f64]) -> Option<()> {
    let n = diag.len();
    for j in 1..n {
        if diag[j - 1] == 0.0 {
            return None;
        }
        let f = sub[j] / diag[j - 1];
        diag[j] -= f * sup[j - 1];
        rhs[j] -= f * rhs[j - 1];
    }
    if diag[n - 1] == 0.0 {
        return None;
    }
    rhs[n - 1] /= diag[n - 1];
    for j in (0..n - 1).rev() {
        rhs[j] = (rhs[j] - sup[j] * rhs[j + 1]) / diag[j];
    }
    Some(())
}

/// A finite-difference solution with its trapezoid integrals.
struct FdSolution {
    s: Vec<f64>,
    xy: Vec<[f64; 2]>,
    clamp_curvature: f64,
    tip_angle: f64,
}

fn fd_solve(gamma: f64, n: usize) -> Result<FdSolution, MasterCurveError> {
    check_gamma(gamma)?;
    if !(2..=MAX_GRID_SIZE).contains(&n) {
        return Err(MasterCurveError::InvalidGridSize {
            n,
            min: 2,
            max: MAX_GRID_SIZE,
        });
    }
    let s = fd_grid(gamma, n);
    // Continuation in Γ by factors of 2 on the final grid, from the linear beam at Γ ≤ 1.
    let mut g = gamma.min(GAMMA_FD_START);
    let mut theta: Vec<f64> = s.iter().map(|&si| direct_guess(g, si)[0]).collect();
    loop {
        fd_newton(g, &s, &mut theta).map_err(|detail| MasterCurveError::NoConvergence {
            method: "finite differences",
            gamma: g,
            detail,
        })?;
        if g >= gamma {
            break;
        }
        g = (2.0 * g).min(gamma);
    }
    if theta.windows(2).any(|w| w[1] < w[0] - 1e-12) || theta[n] > FRAC_PI_2 + 1e-9 {
        return Err(MasterCurveError::NoConvergence {
            method: "finite differences",
            gamma,
            detail: "converged to a non-physical branch".into(),
        });
    }
    // Trapezoid rule for x, y and the clamp moment Γ∫(1 − ŝ) cos θ = θ'(0).
    let mut xy = Vec::with_capacity(n + 1);
    let mut acc = [0.0, 0.0];
    let mut moment = 0.0;
    xy.push(acc);
    for i in 0..n {
        let h = s[i + 1] - s[i];
        let (s0, c0) = theta[i].sin_cos();
        let (s1, c1) = theta[i + 1].sin_cos();
        acc = [acc[0] + 0.5 * h * (c0 + c1), acc[1] + 0.5 * h * (s0 + s1)];
        moment += 0.5 * h * ((1.0 - s[i]) * c0 + (1.0 - s[i + 1]) * c1);
        xy.push(acc);
    }
    Ok(FdSolution {
        s,
        xy,
        clamp_curvature: gamma * moment,
        tip_angle: theta[n],
    })
}

fn fd_to_elastica(gamma: f64, fd: FdSolution) -> HeavyElastica {
    let [dx, dy] = *fd.xy.last().unwrap_or(&[f64::NAN, f64::NAN]);
    HeavyElastica {
        gamma,
        clamp_curvature: fd.clamp_curvature,
        tip_angle: fd.tip_angle,
        dx,
        dy,
        profile: Profile::Grid { s: fd.s, xy: fd.xy },
    }
}

/// Solves the heavy elastica by second-order finite differences on `n` intervals (the
/// independent cross-check of [`heavy_elastica`]).
///
/// Three-point differences on the grid `ŝ = (e^{βu} − 1)/(e^β − 1)`, `u = i/n`,
/// `β = ½ ln Γ` (uniform for `Γ ≤ 1`), which resolves the clamp boundary layer; Newton with
/// a tridiagonal solve, reached by continuation in `Γ`; trapezoid quadrature for `Δx`, `Δy`
/// and the clamp moment `θ'(0) = Γ∫(1 − ŝ) cos θ dŝ`. The error is `O(n⁻²)`: 6e-8
/// relative in `Δy/Δx` at `n = 4000` for `Γ ≤ 1`, 2e-7 at `Γ = 10⁴`, 3e-7 at `Γ = 10⁵`.
/// `n` must be in `[2, MAX_GRID_SIZE]`.
pub fn heavy_elastica_finite_difference(
    gamma: f64,
    n: usize,
) -> Result<HeavyElastica, MasterCurveError> {
    Ok(fd_to_elastica(gamma, fd_solve(gamma, n)?))
}

/// Finite differences on `n` and `2n` intervals, Richardson-extrapolated
/// (`(4 Q₂ₙ − Qₙ)/3` for `Δx`, `Δy`, `θ(1)`, `θ'(0)` and the shape at the common nodes),
/// which removes the `O(n⁻²)` term (the scheme, the smooth grid map and the quadrature are
/// all symmetric, so the error expands in even powers of `1/n`). Already at `n = 1000` it
/// agrees with [`heavy_elastica`] to ~1e-12 relative. `n` must be in `[2, MAX_GRID_SIZE/2]`.
pub fn heavy_elastica_richardson(gamma: f64, n: usize) -> Result<HeavyElastica, MasterCurveError> {
    if n > MAX_GRID_SIZE / 2 {
        return Err(MasterCurveError::InvalidGridSize {
            n,
            min: 2,
            max: MAX_GRID_SIZE / 2,
        });
    }
    let coarse = fd_solve(gamma, n)?;
    let fine = fd_solve(gamma, 2 * n)?;
    let extrapolate = |c: f64, f: f64| (4.0 * f - c) / 3.0;
    // Node i of the coarse grid is node 2i of the fine one (same map, same β).
    let xy: Vec<[f64; 2]> = coarse
        .xy
        .iter()
        .zip(fine.xy.iter().step_by(2))
        .map(|(c, f)| [extrapolate(c[0], f[0]), extrapolate(c[1], f[1])])
        .collect();
    let [dx, dy] = *xy.last().unwrap_or(&[f64::NAN, f64::NAN]);
    Ok(HeavyElastica {
        gamma,
        clamp_curvature: extrapolate(coarse.clamp_curvature, fine.clamp_curvature),
        tip_angle: extrapolate(coarse.tip_angle, fine.tip_angle),
        dx,
        dy,
        profile: Profile::Grid { s: coarse.s, xy },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_limit_the_growth_to_e_squared() {
        for gamma in [GAMMA_MIN, 1.0, 61.3, 1e4, GAMMA_MAX] {
            let s = segment_starts(gamma);
            assert!(s.len() >= 5);
            assert_eq!((s[0], s[s.len() - 1]), (0.0, 1.0));
            for w in s.windows(2) {
                // ∫√(Γ(1 − ŝ)) dŝ over the segment.
                let growth =
                    2.0 / 3.0 * gamma.sqrt() * ((1.0 - w[0]).powf(1.5) - (1.0 - w[1]).powf(1.5));
                assert!(w[1] > w[0] && growth <= 2.0 + 1e-9, "Γ = {gamma}: {growth}");
            }
        }
    }

    /// The fallback of `shooting_with_continuation` (the direct guesses never needed it
    /// over `[GAMMA_MIN, GAMMA_MAX]` in a 500-point sweep, so exercise it here).
    #[test]
    fn continuation_from_a_quarter_of_the_load_converges() {
        for gamma in [10.0, 1e4] {
            let coarse = shooting_with_continuation(gamma / 4.0, 0).unwrap();
            let starts = segment_starts(gamma);
            let m = starts.len() - 1;
            let guess = evaluate_theta(gamma / 4.0, &coarse, &starts[..m]).unwrap();
            let sol = shooting_newton(gamma, starts, guess).unwrap();
            let direct = heavy_elastica(gamma).unwrap();
            let dx: f64 = sol.increments.iter().map(|d| d[0]).sum();
            assert!((sol.tip_angle - direct.tip_angle).abs() < 1e-11);
            assert!((dx / direct.dx - 1.0).abs() < 1e-11);
        }
    }

    /// From poor guesses Newton either fails (and the continuation takes over) or lands on
    /// the physical solution; it never returns another branch.
    #[test]
    fn poor_guesses_never_give_a_non_physical_branch() {
        for gamma in [10.0, 1e3, 1e4] {
            let reference = heavy_elastica(gamma).unwrap();
            let starts = segment_starts(gamma);
            let m = starts.len() - 1;
            let guesses: [Box<dyn Fn(f64) -> [f64; 2]>; 3] = [
                Box::new(|_| [0.0, 0.0]),
                Box::new(|s| direct_guess(1.0, s)),
                Box::new(|s| [3.0 * s, 3.0]),
            ];
            for guess in guesses {
                let z = starts[..m].iter().map(|&s| guess(s)).collect();
                if let Ok(sol) = shooting_newton(gamma, starts.clone(), z) {
                    assert!((sol.tip_angle - reference.tip_angle).abs() < 1e-10);
                }
            }
        }
    }
}
