//! The one dense eigen-solve both Ritz methods need: the largest eigenvalue `θ` of the
//! symmetric-definite pencil `G c = θ K c` (`K` symmetric positive definite, `G` symmetric).
//!
//! A buckling problem `K c = Γ (−K_g) c` has its smallest positive load `Γ_c = 1/θ_max`
//! with `G = −K_g`. Reduced to a standard symmetric problem by the Cholesky factor
//! `K = L Lᵀ`: `(L⁻¹ G L⁻ᵀ) y = θ y`, then faer's dense self-adjoint eigen-solver.
//! Sequential (faer without rayon), so results are bitwise reproducible.

use faer::{Mat, Side};

/// Why the pencil could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PencilError {
    /// `K` is not (numerically) positive definite: the Ritz basis is degenerate.
    #[error("stiffness matrix is not positive definite (Ritz basis numerically dependent)")]
    NotPositiveDefinite,
    /// The symmetric eigen-solver did not converge.
    #[error("symmetric eigen-solver did not converge")]
    EigenSolver,
    /// `G` has no positive eigenvalue: the load never buckles the structure.
    #[error("the load matrix has no positive eigenvalue (no buckling under this load)")]
    NoPositiveEigenvalue,
}

/// Largest eigenvalue `θ` of `G c = θ K c`, required positive.
///
/// `k` and `g` are square, of equal size, symmetric (only the lower triangles are read
/// after the reduction is symmetrised).
pub fn largest_pencil_eigenvalue(k: &Mat<f64>, g: &Mat<f64>) -> Result<f64, PencilError> {
    debug_assert_eq!(k.nrows(), k.ncols());
    debug_assert_eq!((g.nrows(), g.ncols()), (k.nrows(), k.ncols()));
    // Jacobi scaling (eigenvalues unchanged): the Ritz bases are far from orthonormal, and
    // a unit diagonal keeps the Cholesky factor as well conditioned as the basis allows.
    let n = k.nrows();
    let mut d = vec![0.0; n];
    for (i, di) in d.iter_mut().enumerate() {
        let kii = k[(i, i)];
        if !(kii > 0.0 && kii.is_finite()) {
            return Err(PencilError::NotPositiveDefinite);
        }
        *di = 1.0 / kii.sqrt();
    }
    let k = Mat::from_fn(n, n, |i, j| d[i] * k[(i, j)] * d[j]);
    let g = Mat::from_fn(n, n, |i, j| d[i] * g[(i, j)] * d[j]);
    let llt = k
        .llt(Side::Lower)
        .map_err(|_| PencilError::NotPositiveDefinite)?;
    let l = llt.L();
    // X = L⁻¹ G, then M = L⁻¹ Xᵀ = L⁻¹ G L⁻ᵀ (G symmetric).
    let mut x = g;
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut m = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(m.as_mut());
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
    let eigenvalues = sym
        .self_adjoint_eigenvalues(Side::Lower)
        .map_err(|_| PencilError::EigenSolver)?;
    match eigenvalues.last() {
        Some(&theta) if theta > 0.0 && theta.is_finite() => Ok(theta),
        _ => Err(PencilError::NoPositiveEigenvalue),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_pencil_gives_the_largest_ratio() {
        // θ_i = g_i / k_i = {0.5, 3, −2} → 3.
        let k = Mat::from_fn(3, 3, |i, j| if i == j { [2.0, 1.0, 4.0][i] } else { 0.0 });
        let g = Mat::from_fn(3, 3, |i, j| if i == j { [1.0, 3.0, -8.0][i] } else { 0.0 });
        let theta = largest_pencil_eigenvalue(&k, &g).unwrap();
        assert!((theta - 3.0).abs() < 1e-14);
    }

    #[test]
    fn two_by_two_pencil_matches_the_characteristic_polynomial() {
        // det(G − θK) = 0 with K = [[2,1],[1,2]], G = [[1,0],[0,−1]]:
        // (1 − 2θ)(−1 − 2θ) − θ² = 3θ² − 1 = 0 → θ = 1/√3.
        let k = Mat::from_fn(2, 2, |i, j| if i == j { 2.0 } else { 1.0 });
        let g = Mat::from_fn(2, 2, |i, j| match (i, j) {
            (0, 0) => 1.0,
            (1, 1) => -1.0,
            _ => 0.0,
        });
        let theta = largest_pencil_eigenvalue(&k, &g).unwrap();
        assert!((theta - 1.0 / 3f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn indefinite_stiffness_is_reported() {
        let k = Mat::from_fn(2, 2, |i, j| if i == j { [1.0, -1.0][i] } else { 0.0 });
        let g = Mat::<f64>::identity(2, 2);
        assert_eq!(
            largest_pencil_eigenvalue(&k, &g),
            Err(PencilError::NotPositiveDefinite)
        );
    }
}
