//! The smallest eigenvalue of the Hessian in the mass metric: the stability margin.
//!
//! A clamped structure has no rigid-body null space, so an equilibrium is stable exactly when
//! the Hessian is positive definite. The inertia says *whether*; the smallest eigenvalue says
//! *how far*. Raw eigenvalues mix units (N/m for coordinates, N m for angles) and scale with
//! the mesh, so we solve H v = λ M v with the lumped mass matrix M: λ is the square of the
//! lowest natural frequency (1/s²), a physical and mesh-independent quantity.

use crate::linalg::{smallest_eigenpair, BandLdlt, FactorError, SymmetricBandMatrix};

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
pub fn lowest_mode<P: EquilibriumProblem>(
    problem: &P,
    hess: &SymmetricBandMatrix,
    scaled: &mut SymmetricBandMatrix,
    ldlt: &mut BandLdlt,
    rel_tol: f64,
) -> Result<LowestMode, FactorError> {
    let n = hess.dim();
    let bw = hess.half_bandwidth();
    if scaled.dim() != n || scaled.half_bandwidth() != bw {
        *scaled = SymmetricBandMatrix::new(n, bw);
    }
    scaled.set_zero();
    let inv_sqrt_m: Vec<f64> = (0..n)
        .map(|i| 1.0 / problem.inertia_metric(i).sqrt())
        .collect();
    for j in 0..n {
        for i in j..(j + bw + 1).min(n) {
            scaled.add(i, j, hess.get(i, j) * inv_sqrt_m[i] * inv_sqrt_m[j]);
        }
    }
    let est = smallest_eigenpair(scaled, ldlt, rel_tol)?;
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
