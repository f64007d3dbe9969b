//! Legendre polynomials with their first two derivatives, and Gauss–Legendre quadrature:
//! the building blocks of the Ritz bases in [`super::plate_buckling`] and of the element
//! quadrature in [`super::vlasov`].

/// Values `P_k(t)`, `P_k'(t)`, `P_k''(t)` for `k = 0..n` at one point `t ∈ [−1, 1]`.
///
/// Three-term recurrence `(k+1) P_{k+1} = (2k+1) t P_k − k P_{k−1}` and, for the
/// derivatives, `P'_{k+1} = P'_{k−1} + (2k+1) P_k` (differentiated once more for `P''`);
/// both are stable on `[−1, 1]` including the end points.
pub fn legendre_with_derivatives(n: usize, t: f64) -> [Vec<f64>; 3] {
    let mut p = vec![0.0; n];
    let mut dp = vec![0.0; n];
    let mut ddp = vec![0.0; n];
    for k in 0..n {
        match k {
            0 => p[0] = 1.0,
            1 => {
                p[1] = t;
                dp[1] = 1.0;
            }
            _ => {
                let j = (k - 1) as f64; // recurrence index: P_{j+1} from P_j, P_{j−1}
                p[k] = ((2.0 * j + 1.0) * t * p[k - 1] - j * p[k - 2]) / (j + 1.0);
                dp[k] = dp[k - 2] + (2.0 * j + 1.0) * p[k - 1];
                ddp[k] = ddp[k - 2] + (2.0 * j + 1.0) * dp[k - 1];
            }
        }
    }
    [p, dp, ddp]
}

/// `P_n(t)` and `P_n'(t)` for one degree `n ≥ 1`.
fn legendre_and_derivative(n: usize, t: f64) -> (f64, f64) {
    let (mut p_prev, mut p) = (1.0, t);
    for k in 1..n {
        let kf = k as f64;
        let next = ((2.0 * kf + 1.0) * t * p - kf * p_prev) / (kf + 1.0);
        p_prev = p;
        p = next;
    }
    // P_n' = n (t P_n − P_{n−1}) / (t² − 1); the nodes are interior, so t² ≠ 1.
    let dp = n as f64 * (t * p - p_prev) / (t * t - 1.0);
    (p, dp)
}

/// The `n`-point Gauss–Legendre rule on `[−1, 1]` as `(nodes, weights)`, nodes ascending.
///
/// Exact for polynomials of degree `≤ 2n − 1`. Nodes by Newton's method on `P_n` from
/// Tricomi's asymptotic guess `cos(π(i − ¼)/(n + ½))`, weights `2/((1 − t²) P_n'(t)²)`.
/// `n = 0` gives an empty rule.
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    if n == 1 {
        return (vec![0.0], vec![2.0]);
    }
    for i in 0..n.div_ceil(2) {
        let mut t = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (p, dp) = legendre_and_derivative(n, t);
            let dt = p / dp;
            t -= dt;
            if dt.abs() <= 1e-16 * t.abs().max(1e-3) {
                break;
            }
        }
        let (_, dp) = legendre_and_derivative(n, t);
        let w = 2.0 / ((1.0 - t * t) * dp * dp);
        // Symmetric pairs: node i counts down from +1, its mirror up from −1.
        nodes[n - 1 - i] = t;
        nodes[i] = -t;
        weights[n - 1 - i] = w;
        weights[i] = w;
    }
    if n % 2 == 1 {
        nodes[n / 2] = 0.0;
    }
    (nodes, weights)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_rule_integrates_monomials_exactly_up_to_degree_2n_minus_1() {
        for n in [1, 2, 3, 7, 20, 61, 150] {
            let (t, w) = gauss_legendre(n);
            for d in 0..(2 * n).min(40) {
                let q: f64 = t.iter().zip(&w).map(|(t, w)| w * t.powi(d as i32)).sum();
                let exact = if d % 2 == 1 {
                    0.0
                } else {
                    2.0 / (d as f64 + 1.0)
                };
                assert!(
                    (q - exact).abs() < 1e-13,
                    "n = {n}, degree {d}: {q} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn legendre_values_and_derivatives_match_closed_forms() {
        for t in [-1.0, -0.3, 0.0, 0.45, 1.0] {
            let [p, dp, ddp] = legendre_with_derivatives(5, t);
            // P_3 = (5t³ − 3t)/2, P_4 = (35t⁴ − 30t² + 3)/8.
            assert!((p[3] - (5.0 * t * t * t - 3.0 * t) / 2.0).abs() < 1e-14);
            assert!((dp[3] - (15.0 * t * t - 3.0) / 2.0).abs() < 1e-14);
            assert!((ddp[3] - 15.0 * t).abs() < 1e-14);
            assert!((p[4] - (35.0 * t.powi(4) - 30.0 * t * t + 3.0) / 8.0).abs() < 1e-14);
            assert!((dp[4] - (140.0 * t.powi(3) - 60.0 * t) / 8.0).abs() < 1e-13);
            assert!((ddp[4] - (420.0 * t * t - 60.0) / 8.0).abs() < 1e-13);
        }
    }
}
