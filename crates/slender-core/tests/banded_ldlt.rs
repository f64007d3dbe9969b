//! Banded LDLᵀ, inertia and smallest eigenpair, checked against faer's dense symmetric
//! eigensolver on deterministic random matrices.

use faer::{Mat, Side};
use slender_core::linalg::banded::{
    smallest_eigenpair, BandLdlt, EigenEstimate, FactorError, Inertia, SymmetricBandMatrix,
};
use slender_core::linalg::{smallest_eigenpair_near, SymmetricFactor, SymmetricMatrix};

/// Deterministic xorshift64 generator (no RNG crate, reproducible failures).
struct XorShift(u64);

impl XorShift {
    fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// Uniform in [-1, 1).
    fn uniform(&mut self) -> f64 {
        2.0 * ((self.next_u64() >> 11) as f64 / (1u64 << 53) as f64) - 1.0
    }
}

const SIZES: [usize; 12] = [1, 2, 3, 4, 7, 10, 11, 12, 25, 64, 127, 200];
/// 1 and 3 take the general kernels; 6, 10, 11 and 12 (the rod models' widths) the kernels
/// with a compile-time width.
const BANDWIDTHS: [usize; 6] = [1, 3, 6, 10, 11, 12];

/// Random symmetric band matrix with entries uniform in [-1, 1) (indefinite in general).
fn random_band(rng: &mut XorShift, n: usize, bw: usize) -> SymmetricBandMatrix {
    let mut a = SymmetricBandMatrix::new(n, bw);
    for i in 0..n {
        for j in i.saturating_sub(bw)..=i {
            a.add(i, j, rng.uniform());
        }
    }
    a
}

/// `a` shifted to be positive definite with λ_min = margin exactly (up to rounding).
fn make_pd(a: &mut SymmetricBandMatrix, margin: f64) {
    let lmin = eigenvalues(a)[0];
    for i in 0..a.dim() {
        a.add(i, i, margin - lmin);
    }
}

fn dense(a: &SymmetricBandMatrix) -> Mat<f64> {
    Mat::from_fn(a.dim(), a.dim(), |i, j| a.get(i, j))
}

/// Eigenvalues in nondecreasing order, from faer's dense solver.
fn eigenvalues(a: &SymmetricBandMatrix) -> Vec<f64> {
    dense(a)
        .self_adjoint_eigenvalues(Side::Lower)
        .expect("dense eigensolver converges")
}

fn norm(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn spectral_radius(eigs: &[f64]) -> f64 {
    eigs.iter().fold(0.0_f64, |m, l| m.max(l.abs()))
}

/// ‖A v − λ v‖ for a dense-checked product.
fn eig_residual(a: &SymmetricBandMatrix, est: &EigenEstimate) -> f64 {
    let mut av = vec![0.0; a.dim()];
    a.mul_vec(&est.vector, &mut av);
    let r: Vec<f64> = av
        .iter()
        .zip(&est.vector)
        .map(|(y, x)| y - est.value * x)
        .collect();
    norm(&r)
}

#[test]
#[allow(clippy::needless_range_loop)] // explicit (i, j) loops mirror the matrix definition
fn storage_add_get_and_mul_vec_match_dense() {
    let mut rng = XorShift::new(1);
    for &n in &[1, 5, 30] {
        // 6, 10, 11, 12: the widths with fixed-size loops.
        for &bw in &[0, 1, 3, 6, 10, 11, 12] {
            let mut a = SymmetricBandMatrix::new(n, bw);
            assert_eq!((a.dim(), a.half_bandwidth()), (n, bw));
            let mut reference = vec![vec![0.0; n]; n];
            for i in 0..n {
                for j in i.saturating_sub(bw)..=i {
                    // Add half from each side: both must land in the same entry.
                    let v = rng.uniform();
                    a.add(i, j, 0.5 * v);
                    a.add(j, i, 0.5 * v);
                    reference[i][j] += v;
                    reference[j][i] = reference[i][j];
                }
            }
            let d = a.to_dense();
            for i in 0..n {
                for j in 0..n {
                    let expected = if i.abs_diff(j) > bw {
                        0.0
                    } else {
                        reference[i][j]
                    };
                    assert_eq!(d[i][j], expected, "entry ({i},{j}), n={n} bw={bw}");
                    assert_eq!(a.get(i, j), a.get(j, i));
                }
            }
            let x: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
            let mut y = vec![f64::NAN; n];
            a.mul_vec(&x, &mut y);
            for i in 0..n {
                let yi: f64 = (0..n).map(|j| d[i][j] * x[j]).sum();
                assert!((y[i] - yi).abs() <= 1e-14 * (1.0 + yi.abs()), "row {i}");
            }
            let max_diag = (0..n).fold(0.0_f64, |m, i| m.max(d[i][i].abs()));
            assert_eq!(a.max_abs_diagonal(), max_diag);
            let gershgorin = (0..n)
                .map(|i| {
                    d[i][i]
                        - (0..n)
                            .filter(|&j| j != i)
                            .map(|j| d[i][j].abs())
                            .sum::<f64>()
                })
                .fold(f64::INFINITY, f64::min);
            assert!((a.gershgorin_lower_bound() - gershgorin).abs() <= 1e-12);
            assert!(a.gershgorin_lower_bound() <= eigenvalues(&a)[0] + 1e-12);
            a.set_zero();
            assert!(a.to_dense().iter().flatten().all(|&v| v == 0.0));
        }
    }
}

#[test]
fn diagonal_add_counts_once() {
    let mut a = SymmetricBandMatrix::new(3, 1);
    a.add(1, 1, 2.0);
    a.add(2, 1, 3.0);
    assert_eq!(a.get(1, 1), 2.0);
    assert_eq!(a.get(1, 2), 3.0);
    assert_eq!(a.get(2, 1), 3.0);
    assert_eq!(a.get(0, 2), 0.0);
}

#[test]
fn inertia_matches_dense_eigenvalue_counts() {
    let mut ws = BandLdlt::new();
    let mut checked = 0;
    for &bw in &BANDWIDTHS {
        for &n in &SIZES {
            for seed in 0..3 {
                let mut rng = XorShift::new(1000 * n as u64 + 10 * bw as u64 + seed);
                let a = random_band(&mut rng, n, bw);
                let eigs = eigenvalues(&a);
                let s = spectral_radius(&eigs).max(1.0);
                // Shifts between consecutive eigenvalues (and beyond both ends): A − σI has
                // exactly k negative eigenvalues, and σ keeps a distance from the spectrum.
                let mut sigmas = vec![(eigs[0] - 0.5, 0), (eigs[n - 1] + 0.5, n)];
                let step = (n / 8).max(1);
                for k in (1..n).step_by(step) {
                    if eigs[k] - eigs[k - 1] > 1e-6 * s {
                        sigmas.push((0.5 * (eigs[k - 1] + eigs[k]), k));
                    }
                }
                for (sigma, k) in sigmas {
                    let inertia = ws
                        .factorize(&a, -sigma)
                        .unwrap_or_else(|e| panic!("n={n} bw={bw} σ={sigma}: {e}"));
                    assert_eq!(
                        inertia,
                        Inertia {
                            negative: k,
                            zero: 0,
                            positive: n - k
                        },
                        "n={n} bw={bw} seed={seed} σ={sigma}"
                    );
                    assert_eq!(ws.inertia(), inertia);
                    let negative_pivots = ws.pivots().iter().filter(|&&d| d < 0.0).count();
                    assert_eq!(negative_pivots, k);
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 300, "only {checked} shifts checked");
}

#[test]
fn solve_has_small_relative_residual() {
    let mut ws = BandLdlt::new();
    for &bw in &BANDWIDTHS {
        for &n in &SIZES {
            let mut rng = XorShift::new(7 + 31 * n as u64 + bw as u64);
            let mut a = random_band(&mut rng, n, bw);
            let eigs = eigenvalues(&a);
            // Indefinite, with the shift placed mid-gap so that A + shift·I is well conditioned
            // relative to its gap; then a positive definite variant.
            let k = n / 2;
            let shift = if n > 1 {
                -0.5 * (eigs[k - 1] + eigs[k])
            } else {
                1.0
            };
            for (label, shift) in [("indefinite", shift), ("pd", 0.0)] {
                if label == "pd" {
                    make_pd(&mut a, 0.5);
                }
                ws.factorize(&a, shift)
                    .unwrap_or_else(|e| panic!("{label} n={n} bw={bw}: {e}"));
                let b: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
                let mut x = b.clone();
                ws.solve_in_place(&mut x);
                let mut ax = vec![0.0; n];
                a.mul_vec(&x, &mut ax);
                let r: Vec<f64> = (0..n).map(|i| ax[i] + shift * x[i] - b[i]).collect();
                let rel = norm(&r) / norm(&b);
                assert!(
                    rel <= 1e-10,
                    "{label} n={n} bw={bw}: relative residual {rel:e}"
                );
            }
        }
    }
}

#[test]
fn smallest_eigenpair_matches_dense_pd_and_indefinite() {
    let mut ws = BandLdlt::new();
    let mut iterations_pd = Vec::new();
    for &bw in &BANDWIDTHS {
        for &n in &SIZES {
            for (kind, seed) in [("indefinite", 0), ("indefinite", 1), ("pd", 2), ("pd", 3)] {
                let mut rng = XorShift::new(5000 + 1000 * n as u64 + 10 * bw as u64 + seed);
                let mut a = random_band(&mut rng, n, bw);
                if kind == "pd" {
                    // λ_min between 0.01 and 1 on a spectrum of width ~ bw.
                    make_pd(&mut a, 0.01 + 0.99 * rng.uniform().abs());
                }
                let eigs = eigenvalues(&a);
                let s = spectral_radius(&eigs);
                let lambda = eigs[0];
                let est = smallest_eigenpair(&a, &mut ws, 1e-11)
                    .unwrap_or_else(|e| panic!("{kind} n={n} bw={bw}: {e}"));
                let ctx = format!(
                    "{kind} n={n} bw={bw} seed={seed}: λ={lambda}, est={}",
                    est.value
                );
                let err = (est.value - lambda).abs();
                assert!(
                    err <= 1e-9 * lambda.abs().max(1e-14 * s),
                    "{ctx}, err={err:e}"
                );
                assert_eq!(est.vector.len(), n);
                assert!((norm(&est.vector) - 1.0).abs() <= 1e-12, "{ctx}");
                let res = eig_residual(&a, &est);
                assert!(res <= 1e-9 * s.max(1e-300), "{ctx}: residual {res:e}");
                if kind == "pd" {
                    iterations_pd.push(est.iterations);
                }
            }
        }
    }
    // Positive definite matrices should take the cheap inverse-iteration route, not ~50 bisection
    // steps.
    let worst = iterations_pd.iter().max().copied().unwrap_or(0);
    let mean = iterations_pd.iter().sum::<usize>() as f64 / iterations_pd.len() as f64;
    assert!(mean <= 8.0, "mean factorizations for PD: {mean}");
    assert!(worst <= 25, "worst factorizations for PD: {worst}");
}

/// Documented accuracy: |λ̂ − λ| ≤ max(rel_tol·|λ|, 64·ε·s) plus rounding in the counts.
/// The warm start (a guessed eigenvector) keeps the accuracy of the cold solve, whatever the
/// guess: the eigenvector of a perturbed matrix (the Newton use), an arbitrary vector, or one
/// of the wrong length (ignored); and a good guess needs fewer factorizations.
#[test]
fn smallest_eigenpair_near_matches_dense_for_any_guess() {
    let mut ws = BandLdlt::new();
    let (mut cold_total, mut warm_total) = (0, 0);
    for &bw in &BANDWIDTHS {
        for &n in &[10usize, 64, 200] {
            for seed in 0..2u64 {
                let mut rng = XorShift::new(9000 + 1000 * n as u64 + 10 * bw as u64 + seed);
                let a = random_band(&mut rng, n, bw);
                // The previous iterate's matrix: `a` perturbed by 1 %.
                let mut b = a.clone();
                for i in 0..n {
                    for j in i.saturating_sub(bw)..=i {
                        b.add(i, j, 0.01 * rng.uniform());
                    }
                }
                let previous = smallest_eigenpair(&b, &mut ws, 1e-11).expect("previous");
                let eigs = eigenvalues(&a);
                let s = spectral_radius(&eigs);
                let lambda = eigs[0];
                let arbitrary: Vec<f64> = (0..n).map(|_| rng.uniform()).collect();
                let cold = smallest_eigenpair(&a, &mut ws, 1e-11).expect("cold");
                for (name, guess) in [
                    ("previous", &previous.vector[..]),
                    ("arbitrary", &arbitrary[..]),
                    ("wrong length", &arbitrary[1..]),
                ] {
                    let est = smallest_eigenpair_near(&a, &mut ws, 1e-11, Some(guess))
                        .unwrap_or_else(|e| panic!("{name} n={n} bw={bw}: {e}"));
                    let ctx = format!("{name} n={n} bw={bw} seed={seed}: λ={lambda}");
                    let err = (est.value - lambda).abs();
                    assert!(
                        err <= 1e-9 * lambda.abs().max(1e-14 * s),
                        "{ctx}, est={}, err={err:e}",
                        est.value
                    );
                    let res = eig_residual(&a, &est);
                    assert!(res <= 1e-9 * s, "{ctx}: residual {res:e}");
                    if name == "previous" {
                        cold_total += cold.iterations;
                        warm_total += est.iterations;
                    }
                }
            }
        }
    }
    assert!(
        warm_total < cold_total,
        "factorizations: warm {warm_total}, cold {cold_total}"
    );
}

fn documented_bound(lambda: f64, rel_tol: f64, s: f64, bw: usize) -> f64 {
    (rel_tol * lambda.abs()).max(64.0 * f64::EPSILON * s)
        + 4.0 * (bw as f64 + 1.0) * f64::EPSILON * s
}

/// Tridiagonal (−1, 2, −1) stored with half-bandwidth `bw` ≥ 1; eigenvalues are
/// 2 − 2 cos(kπ/(n+1)), k = 1..n.
fn laplacian(n: usize, bw: usize, sign: f64) -> SymmetricBandMatrix {
    let mut a = SymmetricBandMatrix::new(n, bw);
    for i in 0..n {
        a.add(i, i, 2.0 * sign);
        if i > 0 {
            a.add(i, i - 1, -sign);
        }
    }
    a
}

#[test]
fn laplacian_smallest_eigenvalues_match_closed_form() {
    let mut ws = BandLdlt::new();
    for &n in &[10, 200, 1000, 100_000] {
        let theta = std::f64::consts::PI / (n as f64 + 1.0);
        // +L: tiny, well separated λ_min (ratio λ1/λ2 ≈ 1/4) — inverse iteration territory.
        let a = laplacian(n, 10, 1.0);
        let lambda = 2.0 - 2.0 * theta.cos();
        let est = smallest_eigenpair(&a, &mut ws, 1e-10).expect("laplacian");
        let bound = documented_bound(lambda, 1e-10, 4.0, 10);
        assert!(
            (est.value - lambda).abs() <= bound,
            "+L n={n}: {} vs {lambda}",
            est.value
        );
        assert!(eig_residual(&a, &est) <= 1e-8, "+L n={n}");
        // −L: λ_min = −2 − 2cos θ with λ2 − λ1 ~ 3θ², a tight cluster — bisection territory.
        let a = laplacian(n, 1, -1.0);
        let lambda = -2.0 - 2.0 * theta.cos();
        let est = smallest_eigenpair(&a, &mut ws, 1e-12).expect("-laplacian");
        let bound = documented_bound(lambda, 1e-12, 4.0, 1);
        assert!(
            (est.value - lambda).abs() <= bound,
            "−L n={n}: {} vs {lambda}",
            est.value
        );
        // The residual is bounded by the cluster width: the vector may mix close modes.
        let gap = 2.0 * theta.cos() - 2.0 * (2.0 * theta).cos();
        assert!(eig_residual(&a, &est) <= 1e-8 + gap, "−L n={n}");
    }
}

#[test]
fn diagonal_and_repeated_eigenvalues() {
    let mut ws = BandLdlt::new();
    // Diagonal: λ_min equals the Gershgorin bound, so A − λ_min·I is exactly singular.
    for bw in [0, 2] {
        let mut a = SymmetricBandMatrix::new(6, bw);
        for (i, d) in [3.0, -1.5, 2.0, -1.5, 7.0, 0.0].iter().enumerate() {
            a.add(i, i, *d);
        }
        let est = smallest_eigenpair(&a, &mut ws, 1e-12).expect("diagonal");
        assert!((est.value + 1.5).abs() <= 1e-12, "bw={bw}: {}", est.value);
        assert!(eig_residual(&a, &est) <= 1e-10, "bw={bw}");
    }
    // Two identical decoupled blocks: every eigenvalue is double.
    let mut rng = XorShift::new(99);
    let block = random_band(&mut rng, 20, 3);
    let mut a = SymmetricBandMatrix::new(40, 3);
    for i in 0..20_usize {
        for j in i.saturating_sub(3)..=i {
            a.add(i, j, block.get(i, j));
            a.add(20 + i, 20 + j, block.get(i, j));
        }
    }
    let lambda = eigenvalues(&block)[0];
    let est = smallest_eigenpair(&a, &mut ws, 1e-12).expect("double eigenvalue");
    assert!(
        (est.value - lambda).abs() <= 1e-10 * lambda.abs(),
        "{} vs {lambda}",
        est.value
    );
    assert!(eig_residual(&a, &est) <= 1e-9);
    // All-ones 3×3 (eigenvalues 0, 0, 3): the first slicing shift, 0, is exactly singular.
    let mut a = SymmetricBandMatrix::new(3, 2);
    for i in 0..3_usize {
        for j in i.saturating_sub(2)..=i {
            a.add(i, j, 1.0);
        }
    }
    let est = smallest_eigenpair(&a, &mut ws, 1e-12).expect("singular");
    assert!(est.value.abs() <= 1e-13, "{}", est.value);
    assert!(eig_residual(&a, &est) <= 1e-12);
    // Multiple of the identity: any vector is an eigenvector.
    let mut a = SymmetricBandMatrix::new(5, 2);
    (0..5).for_each(|i| a.add(i, i, 2.5));
    let est = smallest_eigenpair(&a, &mut ws, 1e-12).expect("identity");
    assert!((est.value - 2.5).abs() <= 1e-13);
}

#[test]
fn smallest_eigenpair_is_deterministic() {
    let mut rng = XorShift::new(4242);
    let a = random_band(&mut rng, 150, 10);
    let first = smallest_eigenpair(&a, &mut BandLdlt::new(), 1e-10).expect("first");
    // A workspace that has seen other matrices must not change the answer.
    let mut ws = BandLdlt::new();
    ws.factorize(&laplacian(300, 4, 1.0), 0.3).expect("other");
    let second = smallest_eigenpair(&a, &mut ws, 1e-10).expect("second");
    assert_eq!(first, second);
}

#[test]
fn zero_pivots_are_errors_not_panics() {
    let mut ws = BandLdlt::new();
    let zero = SymmetricBandMatrix::new(4, 2);
    assert_eq!(
        ws.factorize(&zero, 0.0),
        Err(FactorError::ZeroPivot { index: 0 })
    );
    assert!(!ws.is_factored());
    assert_eq!(ws.inertia(), Inertia::default());
    let mut b = vec![1.0; 4];
    assert_eq!(ws.try_solve_in_place(&mut b), Err(FactorError::NotFactored));
    assert_eq!(b, vec![1.0; 4], "b untouched on error");
    assert_eq!(ws.min_abs_pivot(), None);

    // [[1, 1], [1, 1]]: singular, breaks down at the second pivot.
    let mut ones = SymmetricBandMatrix::new(2, 1);
    ones.add(0, 0, 1.0);
    ones.add(1, 0, 1.0);
    ones.add(1, 1, 1.0);
    assert_eq!(
        ws.factorize(&ones, 0.0),
        Err(FactorError::ZeroPivot { index: 1 })
    );
    // [[0, 1], [1, 0]]: nonsingular but needs pivoting.
    let mut swap = SymmetricBandMatrix::new(2, 1);
    swap.add(1, 0, 1.0);
    assert_eq!(
        ws.factorize(&swap, 0.0),
        Err(FactorError::ZeroPivot { index: 0 })
    );
    // A shift repairs it: [[s, 1], [1, s]] has eigenvalues s ± 1.
    assert_eq!(
        ws.factorize(&swap, 0.5),
        Ok(Inertia {
            negative: 1,
            zero: 0,
            positive: 1
        })
    );
}

#[test]
fn tiny_pivot_counts_as_zero() {
    // [[1, 1], [1, 1 + ε]]: second pivot ε, below the rounding level of the factorization.
    let mut a = SymmetricBandMatrix::new(2, 1);
    a.add(0, 0, 1.0);
    a.add(1, 0, 1.0);
    a.add(1, 1, 1.0 + f64::EPSILON);
    let mut ws = BandLdlt::new();
    let inertia = ws.factorize(&a, 0.0).expect("nonzero pivots");
    assert_eq!(
        inertia,
        Inertia {
            negative: 0,
            zero: 1,
            positive: 1
        }
    );
    assert!(!inertia.is_positive_definite());
    assert_eq!(ws.min_abs_pivot(), Some(f64::EPSILON));
    assert_eq!(ws.max_abs_pivot(), Some(1.0));
}

#[test]
fn non_finite_and_dimension_errors() {
    let mut ws = BandLdlt::new();
    let mut a = laplacian(5, 1, 1.0);
    assert_eq!(
        ws.factorize(&a, f64::NAN),
        Err(FactorError::NonFinite { index: 0 })
    );
    ws.factorize(&a, 0.0).expect("laplacian is PD");
    let mut short = vec![1.0; 4];
    assert_eq!(
        ws.try_solve_in_place(&mut short),
        Err(FactorError::DimensionMismatch {
            expected: 5,
            found: 4
        })
    );
    a.add(3, 2, f64::NAN);
    assert_eq!(
        ws.factorize(&a, 0.0),
        Err(FactorError::NonFinite { index: 3 })
    );
    assert_eq!(
        smallest_eigenpair(&a, &mut ws, 1e-10).map(|e| e.value),
        Err(FactorError::NonFinite { index: 3 })
    );
    assert_eq!(
        smallest_eigenpair(&SymmetricBandMatrix::new(0, 3), &mut ws, 1e-10).map(|e| e.value),
        Err(FactorError::EmptyMatrix)
    );
    // The zero matrix has λ_min = 0 even though it cannot be factored.
    let est =
        smallest_eigenpair(&SymmetricBandMatrix::new(3, 1), &mut ws, 1e-10).expect("zero matrix");
    assert_eq!(est.value, 0.0);
    assert!((norm(&est.vector) - 1.0).abs() < 1e-15);
}

#[test]
fn solve_without_factorization_is_loud() {
    let ws = BandLdlt::new();
    let outcome = std::panic::catch_unwind(|| {
        let mut b = vec![1.0; 3];
        ws.solve_in_place(&mut b);
        b
    });
    // Debug builds panic; release builds poison the vector. Either way nothing passes silently.
    if let Ok(b) = outcome {
        assert!(b.iter().all(|v| v.is_nan()));
    }
}

#[test]
fn out_of_band_add_is_loud() {
    let outcome = std::panic::catch_unwind(|| {
        let mut a = laplacian(6, 1, 1.0);
        a.add(4, 1, 1.0);
        a
    });
    // Debug builds panic; release builds poison the matrix so that factorization fails.
    if let Ok(a) = outcome {
        let mut ws = BandLdlt::new();
        assert!(matches!(
            ws.factorize(&a, 0.0),
            Err(FactorError::NonFinite { .. })
        ));
    }
}

#[test]
fn refactorization_reuses_buffers() {
    let mut ws = BandLdlt::new();
    let big = laplacian(500, 10, 1.0);
    let small = laplacian(100, 10, 1.0);
    ws.factorize(&big, 0.0).expect("big");
    let ptr = ws.pivots().as_ptr();
    ws.factorize(&small, 0.0).expect("small");
    assert_eq!(ws.pivots().len(), 100);
    ws.factorize(&big, 1.0).expect("big again");
    assert_eq!(ws.pivots().as_ptr(), ptr, "pivot buffer was reallocated");
    assert_eq!(ws.pivots().len(), 500);
    // Laplacian + I: pivots of a PD tridiagonal matrix are all > 1.
    assert!(ws.min_abs_pivot().is_some_and(|d| d > 1.0));
}

#[test]
fn block_solves_equal_single_solves_bit_for_bit() {
    let mut ws = BandLdlt::new();
    for &bw in &[0, 3, 6, 10, 11, 12] {
        for &n in &[1, 5, 12, 13, 40] {
            let mut rng = XorShift::new(911 + 17 * n as u64 + bw as u64);
            let mut a = random_band(&mut rng, n, bw);
            make_pd(&mut a, 0.3);
            ws.factorize(&a, 0.0).expect("positive definite");
            let rhs: Vec<Vec<f64>> = (0..3)
                .map(|_| (0..n).map(|_| rng.uniform()).collect())
                .collect();
            let single: Vec<Vec<f64>> = rhs
                .iter()
                .map(|b| {
                    let mut x = b.clone();
                    ws.solve_in_place(&mut x);
                    x
                })
                .collect();
            let [mut x0, mut x1, mut x2] = [rhs[0].clone(), rhs[1].clone(), rhs[2].clone()];
            ws.solve_block_in_place([&mut x0[..], &mut x1[..], &mut x2[..]]);
            for (k, x) in [x0, x1, x2].iter().enumerate() {
                let same = x
                    .iter()
                    .zip(&single[k])
                    .all(|(p, q)| p.to_bits() == q.to_bits());
                assert!(
                    same,
                    "n={n} bw={bw} vector {k}: block and single solves differ"
                );
                // And the solve itself is right: A x = b.
                let mut ax = vec![0.0; n];
                a.mul_vec(x, &mut ax);
                let r: Vec<f64> = ax.iter().zip(&rhs[k]).map(|(p, q)| p - q).collect();
                assert!(norm(&r) <= 1e-10 * (1.0 + norm(&rhs[k])), "n={n} bw={bw}");
            }
        }
    }
}

#[test]
fn contiguous_block_scatter_equals_entrywise_adds() {
    // An 11-DOF stencil on consecutive DOFs (an interior rod hinge), one with a fixed slot,
    // and one with a repeated DOF: the block scatter must add exactly what `add` adds.
    let fixed = slender_core::assembly::FIXED;
    let consecutive: [usize; 11] = std::array::from_fn(|a| 7 + a);
    let mut with_fixed = consecutive;
    with_fixed[0] = fixed;
    let mut repeated = consecutive;
    repeated[10] = 12;
    for dofs in [consecutive, with_fixed, repeated] {
        let mut rng = XorShift::new(5);
        let h: Vec<f64> = (0..121).map(|_| rng.uniform()).collect();
        let value = |a: usize, b: usize| h[11 * a.max(b) + a.min(b)];
        let mut block = SymmetricBandMatrix::new(30, 10);
        let mut entrywise = SymmetricBandMatrix::new(30, 10);
        for pass in 0..2 {
            block.add_lower_block(&dofs, value);
            for a in 0..11 {
                for b in 0..=a {
                    let (i, j) = (dofs[a], dofs[b]);
                    if i == fixed || j == fixed {
                        continue;
                    }
                    let v = value(a, b);
                    entrywise.add(i, j, if i == j && a != b { 2.0 * v } else { v });
                }
            }
            let same = (0..30).all(|i| {
                (0..30).all(|j| block.get(i, j).to_bits() == entrywise.get(i, j).to_bits())
            });
            assert!(same, "pass {pass}, dofs {dofs:?}");
        }
    }
}
