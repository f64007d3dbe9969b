//! The smallest eigenvalue of the Hessian in the mass metric: the stability margin.
//!
//! A clamped structure has no rigid-body null space, so an equilibrium is stable exactly when
//! the Hessian is positive definite. The inertia says *whether*; the smallest eigenvalue says
//! *how far*. Raw eigenvalues mix units (N/m for coordinates, N m for angles) and scale with
//! the mesh, so we solve H v = λ M v with the lumped mass matrix M: λ is the square of the
//! lowest natural frequency (1/s²), a physical and mesh-independent quantity.

use crate::linalg::{smallest_eigenpair, FactorError, SymmetricFactor, SymmetricMatrix};

use super::problem::EquilibriumProblem;

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

/// Computes the lowest mode of `hess` (assembled by `problem`), using `scaled` and `ldlt` as
/// scratch. `rel_tol` is the relative accuracy requested of λ.
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
    if positive_definite_factor {
        if let Some(mode) = inverse_iteration(problem, hess.dim(), ldlt, rel_tol) {
            return Ok(mode);
        }
    }
    let n = hess.dim();
    let inv_sqrt_m: Vec<f64> = (0..n)
        .map(|i| 1.0 / problem.inertia_metric(i).sqrt())
        .collect();
    hess.congruence_scaled(&inv_sqrt_m, scaled);
    let est = smallest_eigenpair::<P::Hessian>(scaled, ldlt, rel_tol)?;
    let shape = est
        .vector
        .iter()
        .zip(&inv_sqrt_m)
        .map(|(v, s)| v * s)
        .collect();
    Ok(LowestMode {
        value: est.value,
        normalized: est.value / problem.eigenvalue_scale(),
        shape,
    })
}

/// Block size of the subspace iteration: near-degenerate pairs (in-plane and out-of-plane
/// bending of a round rod) would make single-vector inverse iteration crawl; with a block of
/// three the convergence rate is λ₁/λ₄.
const BLOCK: usize = 3;

/// Subspace (block inverse) iteration with Rayleigh–Ritz for H v = λ M v, reusing an existing
/// factorization of a positive definite H. Returns `None` if it has not converged.
fn inverse_iteration<P: EquilibriumProblem>(
    problem: &P,
    n: usize,
    ldlt: &<P::Hessian as SymmetricMatrix>::Factor,
    rel_tol: f64,
) -> Option<LowestMode> {
    use nalgebra::{Matrix3, SymmetricEigen};
    if n < BLOCK {
        return None;
    }
    let mass: Vec<f64> = (0..n).map(|i| problem.inertia_metric(i)).collect();
    // Deterministic starts with generic components (never orthogonal to a symmetric mode).
    let mut v: [Vec<f64>; BLOCK] = std::array::from_fn(|k| {
        (0..n)
            .map(|i| 1.0 + ((i as f64 + 1.0) * (0.754_877_666 + 0.31 * k as f64)).fract())
            .collect()
    });
    let mut w: [Vec<f64>; BLOCK] = std::array::from_fn(|_| vec![0.0; n]);
    let m_dot = |a: &[f64], b: &[f64]| -> f64 { (0..n).map(|i| a[i] * mass[i] * b[i]).sum() };
    let mut rho_old = f64::INFINITY;
    for _ in 0..60 {
        for k in 0..BLOCK {
            for i in 0..n {
                w[k][i] = mass[i] * v[k][i];
            }
            ldlt.solve_in_place(&mut w[k]);
        }
        // Projected pencil: A = Wᵀ H W = Wᵀ M V, B = Wᵀ M W.
        let a = Matrix3::from_fn(|r, c| 0.5 * (m_dot(&w[r], &v[c]) + m_dot(&w[c], &v[r])));
        let b = Matrix3::from_fn(|r, c| m_dot(&w[r], &w[c]));
        let chol = b.cholesky()?;
        let l_inv = chol.l().try_inverse()?;
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
            return None;
        }
        if (rho - rho_old).abs() <= rel_tol * rho {
            let norm = m_dot(&v[0], &v[0]).sqrt();
            return Some(LowestMode {
                value: rho,
                normalized: rho / problem.eigenvalue_scale(),
                shape: v[0].iter().map(|x| x / norm).collect(),
            });
        }
        rho_old = rho;
    }
    None
}
