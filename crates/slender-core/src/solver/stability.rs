//! Stability of an equilibrium: the one predicate, and the smallest Hessian eigenvalue in the
//! mass metric (the stability margin).
//!
//! A clamped structure has no rigid-body null space, so an equilibrium is stable exactly when
//! the Hessian is positive definite ([`is_stable`]). The inertia says *whether*; the smallest
//! eigenvalue says *how far*. Raw eigenvalues mix units (N/m for coordinates, N m for angles)
//! and scale with the mesh, so we solve H v = λ M v with the lumped mass matrix M: λ is the
//! square of the lowest natural frequency (1/s²), a physical and mesh-independent quantity.

use crate::linalg::eigen::smallest_eigenpair_near;
use crate::linalg::{FactorError, Inertia, SymmetricFactor, SymmetricMatrix};

use super::problem::{EquilibriumProblem, MassMetric};

/// The stability predicate: an equilibrium is stable iff its Hessian has no negative and no
/// (numerically) zero eigenvalue. Every "is this equilibrium stable?" in slender asks this.
pub fn is_stable(inertia: &Inertia) -> bool {
    inertia.negative == 0 && inertia.zero == 0
}

/// How many eigenvalues of H v = λ M v are clearly negative (unstable modes) and how many lie
/// within round-off of zero (null modes: symmetries that cost no energy, such as a round ring
/// rolling through itself, or a bifurcation point met exactly).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct ModeCounts {
    /// Eigenvalues below −τ.
    pub unstable: usize,
    /// Eigenvalues in [−τ, τ].
    pub null: usize,
}

/// Width of the band around zero in units of ε × max_i H_ii/M_ii (an upper bound of the
/// largest eigenvalue): the eigenvalues of a Hessian assembled in floating point are only
/// known to about ε times the largest.
const NULL_BAND: f64 = 1e4;

/// τ (1/s²): eigenvalues of H v = λ M v within [−τ, τ] are zero to round-off.
pub fn null_band<P: EquilibriumProblem>(problem: &P, hess: &P::Hessian) -> f64 {
    let scale = (0..hess.dim())
        .map(|i| hess.diagonal(i).abs() / problem.inertia_metric(i))
        .fold(0.0, f64::max);
    NULL_BAND * f64::EPSILON * scale
}

/// Counts the unstable and null modes of `hess` by the inertia of H ± τM (two factorizations
/// in `scratch` and `ldlt`); returns them with τ (1/s²). `None` if a factorization fails.
pub fn classify_modes<P: EquilibriumProblem>(
    problem: &P,
    hess: &P::Hessian,
    scratch: &mut P::Hessian,
    ldlt: &mut <P::Hessian as SymmetricMatrix>::Factor,
) -> Option<(ModeCounts, f64)> {
    let n = hess.dim();
    let tau = null_band(problem, hess);
    let mut count = |shift: f64| -> Option<usize> {
        scratch.clone_from(hess);
        for i in 0..n {
            scratch.add(i, i, shift * problem.inertia_metric(i));
        }
        let i = ldlt.factorize(scratch, 0.0).ok()?;
        Some(i.negative + i.zero)
    };
    let below_minus = count(tau)?;
    let below_plus = count(-tau)?;
    Some((
        ModeCounts {
            unstable: below_minus,
            null: below_plus.saturating_sub(below_minus),
        },
        tau,
    ))
}

/// Lowest eigenpair of H v = λ M v.
#[derive(Clone, Debug, PartialEq)]
pub struct LowestMode {
    /// λ (1/s²).
    pub value: f64,
    /// λ divided by the problem's eigenvalue scale (dimensionless).
    pub normalized: f64,
    /// Mode shape in the free DOFs (m or rad), M-normalized (vᵀ M v = 1).
    pub shape: Vec<f64>,
}

/// Buffers of [`lowest_mode_with`]: allocated once per problem size, so that warm re-solves
/// that only need inverse iteration allocate nothing.
#[derive(Clone, Debug, Default)]
pub struct EigenWorkspace {
    mass: Vec<f64>,
    inv_sqrt_m: Vec<f64>,
    v: [Vec<f64>; BLOCK],
    w: [Vec<f64>; BLOCK],
    /// True when `v` holds the Ritz vectors of the last converged inverse iteration of this
    /// size: a warm re-solve (an interactive drag) then starts from them and converges in two
    /// or three sweeps instead of a dozen.
    warm: bool,
}

impl EigenWorkspace {
    fn prepare<P: MassMetric>(&mut self, problem: &P, n: usize) {
        if self.mass.len() != n {
            self.warm = false;
        }
        self.mass.resize(n, 0.0);
        self.inv_sqrt_m.resize(n, 0.0);
        for i in 0..n {
            let m = problem.inertia_metric(i);
            self.mass[i] = m;
            self.inv_sqrt_m[i] = 1.0 / m.sqrt();
        }
        for k in 0..BLOCK {
            self.v[k].resize(n, 0.0);
            self.w[k].resize(n, 0.0);
        }
    }
}

/// Computes the lowest mode of `hess` (assembled by `problem`), using `scaled` and `ldlt` as
/// scratch. `rel_tol` is the relative accuracy requested of λ. Allocates its buffers; see
/// [`lowest_mode_with`] for the allocation-free variant.
///
/// If `positive_definite_factor` is true, `ldlt` must hold the LDLᵀ factorization of `hess`
/// (no shift) with no negative pivot: then inverse iteration (v ← H⁻¹ M v with the Rayleigh
/// quotient) reuses it and needs no new factorization — the common case of a stable
/// equilibrium. Otherwise (or if inverse iteration stalls) the mass-scaled matrix is
/// sliced by Sylvester's law.
pub fn lowest_mode<P: EquilibriumProblem>(
    problem: &P,
    hess: &P::Hessian,
    positive_definite_factor: bool,
    scaled: &mut P::Hessian,
    ldlt: &mut <P::Hessian as SymmetricMatrix>::Factor,
    rel_tol: f64,
) -> Result<LowestMode, FactorError> {
    let mut ws = EigenWorkspace::default();
    let mut mode = LowestMode {
        value: 0.0,
        normalized: 0.0,
        shape: Vec::new(),
    };
    lowest_mode_with(
        problem,
        hess,
        positive_definite_factor,
        scaled,
        ldlt,
        rel_tol,
        &mut ws,
        &mut mode,
    )?;
    Ok(mode)
}

/// As [`lowest_mode`], writing into `mode` (its shape buffer reused) with the buffers of `ws`.
#[allow(clippy::too_many_arguments)]
pub fn lowest_mode_with<P: EquilibriumProblem>(
    problem: &P,
    hess: &P::Hessian,
    positive_definite_factor: bool,
    scaled: &mut P::Hessian,
    ldlt: &mut <P::Hessian as SymmetricMatrix>::Factor,
    rel_tol: f64,
    ws: &mut EigenWorkspace,
    mode: &mut LowestMode,
) -> Result<(), FactorError> {
    let n = hess.dim();
    ws.prepare(problem, n);
    if positive_definite_factor && inverse_iteration(problem, n, ldlt, rel_tol, ws, mode) {
        return Ok(());
    }
    slice_lowest_mode(problem, hess, scaled, ldlt, rel_tol, ws, mode, false)
}

/// As [`lowest_mode_with`] without a positive definite factorization (spectrum slicing of the
/// mass-scaled Hessian); with `warm`, the mode already in `mode` (of a nearby Hessian of the
/// same problem) is the start of the slicing ([`smallest_eigenpair_near`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn slice_lowest_mode<P: EquilibriumProblem>(
    problem: &P,
    hess: &P::Hessian,
    scaled: &mut P::Hessian,
    ldlt: &mut <P::Hessian as SymmetricMatrix>::Factor,
    rel_tol: f64,
    ws: &mut EigenWorkspace,
    mode: &mut LowestMode,
    warm: bool,
) -> Result<(), FactorError> {
    let n = hess.dim();
    ws.prepare(problem, n);
    hess.congruence_scaled(&ws.inv_sqrt_m, scaled);
    let guess = if warm && mode.shape.len() == n {
        // The M-normalized shape in the scaled coordinates: M^{1/2} v.
        for i in 0..n {
            ws.w[0][i] = mode.shape[i] / ws.inv_sqrt_m[i];
        }
        Some(&ws.w[0][..])
    } else {
        None
    };
    let est = smallest_eigenpair_near::<P::Hessian>(scaled, ldlt, rel_tol, guess)?;
    mode.shape.clear();
    mode.shape
        .extend(est.vector.iter().zip(&ws.inv_sqrt_m).map(|(v, s)| v * s));
    mode.value = est.value;
    mode.normalized = est.value / problem.eigenvalue_scale();
    Ok(())
}

/// Block size of the subspace iteration: near-degenerate pairs (in-plane and out-of-plane
/// bending of a round rod) would make single-vector inverse iteration crawl; with a block of
/// three the convergence rate is λ₁/λ₄.
const BLOCK: usize = 3;

/// Subspace (block inverse) iteration with Rayleigh–Ritz for H v = λ M v, reusing an existing
/// factorization of a positive definite H. Returns false if it has not converged.
fn inverse_iteration<P: EquilibriumProblem>(
    problem: &P,
    n: usize,
    ldlt: &<P::Hessian as SymmetricMatrix>::Factor,
    rel_tol: f64,
    ws: &mut EigenWorkspace,
    mode: &mut LowestMode,
) -> bool {
    use nalgebra::{Matrix3, SymmetricEigen};
    if n < BLOCK {
        return false;
    }
    let EigenWorkspace {
        mass, v, w, warm, ..
    } = ws;
    // Deterministic starts with generic components (never orthogonal to a symmetric mode).
    // Warm: the two lowest Ritz vectors of the last call are kept, and the third slot gets the
    // generic start again, so that a mode that has become the lowest since is still present
    // in the block.
    let first_generic = if *warm { BLOCK - 1 } else { 0 };
    for (k, vk) in v.iter_mut().enumerate().skip(first_generic) {
        for (i, x) in vk.iter_mut().enumerate() {
            *x = 1.0 + ((i as f64 + 1.0) * (0.754_877_666 + 0.31 * k as f64)).fract();
        }
    }
    let m_dot = |a: &[f64], b: &[f64]| -> f64 { (0..n).map(|i| a[i] * mass[i] * b[i]).sum() };
    // Kept vectors scaled to the generic one's M-norm (a well-conditioned projected pencil).
    let target = m_dot(&v[BLOCK - 1], &v[BLOCK - 1]).sqrt();
    for k in 0..first_generic {
        let norm = m_dot(&v[k], &v[k]).sqrt();
        if norm > 0.0 && norm.is_finite() {
            v[k].iter_mut().for_each(|x| *x *= target / norm);
        }
    }
    *warm = false;
    let mut rho_old = f64::INFINITY;
    for _ in 0..60 {
        for k in 0..BLOCK {
            for i in 0..n {
                w[k][i] = mass[i] * v[k][i];
            }
        }
        let [w0, w1, w2] = w;
        ldlt.solve_block_in_place([&mut w0[..], &mut w1[..], &mut w2[..]]);
        // Projected pencil: A = Wᵀ H W = Wᵀ M V, B = Wᵀ M W. The 18 M-products in one pass
        // (each summed in index order as `m_dot` does): one pass per product would be 18
        // chains of n dependent additions.
        let (mut wmv, mut wmw) = ([[-0.0; BLOCK]; BLOCK], [[-0.0; BLOCK]; BLOCK]);
        for i in 0..n {
            for r in 0..BLOCK {
                let wm = w[r][i] * mass[i];
                for c in 0..BLOCK {
                    wmv[r][c] += wm * v[c][i];
                    wmw[r][c] += wm * w[c][i];
                }
            }
        }
        let a = Matrix3::from_fn(|r, c| 0.5 * (wmv[r][c] + wmv[c][r]));
        let b = Matrix3::from_fn(|r, c| wmw[r][c]);
        let Some(chol) = b.cholesky() else {
            return false;
        };
        let Some(l_inv) = chol.l().try_inverse() else {
            return false;
        };
        let eig = SymmetricEigen::new(l_inv * a * l_inv.transpose());
        let y = l_inv.transpose() * eig.eigenvectors;
        let (mut order, values) = ([0usize, 1, 2], eig.eigenvalues);
        order.sort_by(|&p, &q| values[p].total_cmp(&values[q]));
        for (slot, &k) in order.iter().enumerate() {
            for i in 0..n {
                v[slot][i] = (0..BLOCK).map(|j| w[j][i] * y[(j, k)]).sum();
            }
        }
        let rho = values[order[0]];
        if !rho.is_finite() || rho <= 0.0 {
            return false;
        }
        if (rho - rho_old).abs() <= rel_tol * rho {
            *warm = true;
            let norm = m_dot(&v[0], &v[0]).sqrt();
            mode.value = rho;
            mode.normalized = rho / problem.eigenvalue_scale();
            mode.shape.clear();
            mode.shape.extend(v[0].iter().map(|x| x / norm));
            return true;
        }
        rho_old = rho;
    }
    false
}
