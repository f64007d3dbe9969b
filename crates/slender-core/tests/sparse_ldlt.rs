//! Sparse LDLᵀ through faer (fixed pattern, one symbolic analysis): inertia, solves and the
//! smallest eigenpair, checked against faer's dense symmetric eigensolver and a dense
//! product on deterministic random sparse matrices (definite and indefinite).

use faer::{Mat, Side};
use slender_core::linalg::{
    smallest_eigenpair, FactorError, SparseLdlt, SparseSymmetricMatrix, SymmetricFactor,
    SymmetricMatrix,
};

struct XorShift(u64);
impl XorShift {
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn uniform(&mut self) -> f64 {
        2.0 * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
}

/// A random symmetric matrix with about `per_row` off-diagonal entries per row, scattered
/// (no band), with the given diagonal offset.
fn random_sparse(rng: &mut XorShift, n: usize, per_row: usize) -> SparseSymmetricMatrix {
    let mut pairs = Vec::new();
    for i in 0..n {
        for _ in 0..per_row {
            let j = (rng.next_u64() % n as u64) as usize;
            pairs.push((i, j));
        }
    }
    let mut a = SparseSymmetricMatrix::from_pattern(n, pairs.iter().copied());
    for &(i, j) in &pairs {
        a.add(i, j, rng.uniform());
    }
    for i in 0..n {
        a.add(i, i, rng.uniform());
    }
    a
}

fn dense(a: &SparseSymmetricMatrix) -> Mat<f64> {
    Mat::from_fn(a.dim(), a.dim(), |i, j| a.get(i, j))
}

fn eigenvalues(a: &SparseSymmetricMatrix) -> Vec<f64> {
    dense(a)
        .self_adjoint_eigenvalues(Side::Lower)
        .expect("dense eigensolver")
}

#[test]
fn inertia_matches_dense_eigenvalues_and_symbolic_analysis_is_reused() {
    let mut rng = XorShift(0x2545_F491_4F6C_DD1D);
    for &n in &[1usize, 2, 5, 17, 60, 150] {
        let a = random_sparse(&mut rng, n, 3);
        let eigs = eigenvalues(&a);
        let mut ldlt = SparseLdlt::new();
        for shift in [0.0, 0.7, -0.4, 3.0] {
            match ldlt.factorize(&a, shift) {
                Ok(inertia) => {
                    let negative = eigs.iter().filter(|l| **l + shift < 0.0).count();
                    assert_eq!(inertia.negative + inertia.zero + inertia.positive, n);
                    assert_eq!(inertia.negative, negative, "n = {n}, shift = {shift}");
                }
                // No pivoting: an exactly zero pivot may occur for indefinite matrices.
                Err(FactorError::ZeroPivot { .. }) => {}
                Err(e) => panic!("{e}"),
            }
        }
        assert_eq!(ldlt.symbolic_analyses(), 1, "one analysis per pattern");
    }
}

/// Both of faer's variants give the inertia: a sparse pattern is factored simplicially, a
/// dense-ish one supernodally (D read from the supernodes' diagonal blocks).
#[test]
fn inertia_from_both_simplicial_and_supernodal_factors() {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    for (n, per_row, supernodal) in [(120usize, 1usize, false), (240, 25, true)] {
        let a = random_sparse(&mut rng, n, per_row);
        let eigs = eigenvalues(&a);
        let mut ldlt = SparseLdlt::new();
        for shift in [0.0, 1.5, -2.0] {
            let inertia = ldlt.factorize(&a, shift).expect("nonzero pivots");
            let negative = eigs.iter().filter(|l| **l + shift < 0.0).count();
            assert_eq!(inertia.negative, negative, "n = {n}, shift = {shift}");
            assert_eq!(inertia.negative + inertia.positive, n);
        }
        assert_eq!(ldlt.is_supernodal(), Some(supernodal), "n = {n}");
    }
}

#[test]
fn solves_positive_definite_and_indefinite_systems() {
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    for &n in &[3usize, 40, 200] {
        for shift in [0.0, 10.0] {
            let a = random_sparse(&mut rng, n, 4);
            let mut ldlt = SparseLdlt::new();
            if ldlt.factorize(&a, shift).is_err() {
                continue;
            }
            let x: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
            let mut b = vec![0.0; n];
            a.mul_vec(&x, &mut b);
            for (bi, xi) in b.iter_mut().zip(&x) {
                *bi += shift * xi;
            }
            ldlt.try_solve_in_place(&mut b).expect("factored");
            let err = b
                .iter()
                .zip(&x)
                .map(|(u, v)| (u - v).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-8, "n = {n}, shift = {shift}: error {err}");
        }
    }
}

#[test]
fn smallest_eigenpair_matches_dense() {
    let mut rng = XorShift(0xDEAD_BEEF_CAFE_F00D);
    for &n in &[4usize, 30, 120] {
        let a = random_sparse(&mut rng, n, 3);
        let eigs = eigenvalues(&a);
        let mut ldlt = SparseLdlt::new();
        let est = smallest_eigenpair(&a, &mut ldlt, 1e-10).expect("eigenpair");
        assert!(
            (est.value - eigs[0]).abs() <= 1e-8 * eigs[0].abs().max(1.0),
            "n = {n}: {} vs {}",
            est.value,
            eigs[0]
        );
    }
}

#[test]
fn errors_instead_of_panics() {
    let mut a = SparseSymmetricMatrix::from_pattern(2, [(0, 1)]);
    let mut ldlt = SparseLdlt::new();
    assert_eq!(
        ldlt.try_solve_in_place(&mut [1.0, 2.0]),
        Err(FactorError::NotFactored)
    );
    // [[0, 1], [1, 0]] has a zero first pivot without pivoting.
    a.add(0, 1, 1.0);
    assert!(matches!(
        ldlt.factorize(&a, 0.0),
        Err(FactorError::ZeroPivot { .. })
    ));
    a.add(0, 0, f64::NAN);
    assert!(matches!(
        ldlt.factorize(&a, 0.0),
        Err(FactorError::NonFinite { .. })
    ));
    let mut b = SparseSymmetricMatrix::from_pattern(2, []);
    b.add(0, 0, 2.0);
    b.add(1, 1, 4.0);
    ldlt.factorize(&b, 0.0).expect("diagonal");
    assert!(matches!(
        ldlt.try_solve_in_place(&mut [1.0]),
        Err(FactorError::DimensionMismatch { .. })
    ));
}
