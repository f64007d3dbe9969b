//! Gauss–Legendre nodes and weights on [0, 1], for the average of a force along a step.

/// Largest number of nodes available.
pub const MAX_QUADRATURE_POINTS: usize = 5;

/// The `q`-point Gauss–Legendre rule on [0, 1] (exact for polynomials of degree ≤ 2q − 1) as
/// (node, weight) pairs; `q` in 1..=[`MAX_QUADRATURE_POINTS`].
pub fn gauss_legendre_unit(q: usize) -> Vec<(f64, f64)> {
    // Nodes and weights on [−1, 1] (Abramowitz & Stegun, table 25.4), positive half.
    let half: &[(f64, f64)] = match q {
        1 => &[(0.0, 2.0)],
        2 => &[(0.577_350_269_189_625_8, 1.0)],
        3 => &[(0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)],
        4 => &[
            (0.339_981_043_584_856_3, 0.652_145_154_862_546_1),
            (0.861_136_311_594_052_6, 0.347_854_845_137_453_9),
        ],
        5 => &[
            (0.0, 128.0 / 225.0),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ],
        _ => panic!("Gauss–Legendre rule with {q} points: 1..={MAX_QUADRATURE_POINTS} available"),
    };
    let mut rule = Vec::with_capacity(q);
    for &(x, w) in half {
        rule.push((0.5 * (1.0 + x), 0.5 * w));
        if x != 0.0 {
            rule.push((0.5 * (1.0 - x), 0.5 * w));
        }
    }
    rule.sort_by(|a, b| a.0.total_cmp(&b.0));
    rule
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_integrate_polynomials_of_degree_2q_minus_1() {
        for q in 1..=MAX_QUADRATURE_POINTS {
            let rule = gauss_legendre_unit(q);
            assert_eq!(rule.len(), q);
            for p in 0..(2 * q) as i32 {
                let sum: f64 = rule.iter().map(|(s, w)| w * s.powi(p)).sum();
                assert!(
                    (sum - 1.0 / (p + 1) as f64).abs() < 1e-15,
                    "q {q} degree {p}"
                );
            }
        }
    }
}
