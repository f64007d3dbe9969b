//! The contact barrier: an energy of the gap g that is zero beyond the activation distance ĝ,
//! grows without bound as g → 0⁺, and is C² everywhere on g > 0 (Li et al., Incremental
//! Potential Contact, 2020): b(g) = −(g − ĝ)² ln(g/ĝ) for 0 < g < ĝ, 0 for g ≥ ĝ.
//!
//! Because b → ∞ at g = 0, a minimization that never accepts an infinite energy (the line
//! search) and never steps through the surface (the step caps) keeps every gap positive: the
//! structure does not penetrate, and its contacts sit within ĝ of the surface — ĝ is the
//! stated tolerance of the contact position.

/// Value, first and second derivative of the barrier at gap `g` (m) with activation distance
/// `activation` (m): (b in m², b′ in m, b″ dimensionless). b = +∞ for g ≤ 0.
pub fn barrier(g: f64, activation: f64) -> (f64, f64, f64) {
    if g >= activation {
        return (0.0, 0.0, 0.0);
    }
    if !(g > 0.0) {
        return (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY);
    }
    let d = g - activation;
    let log = (g / activation).ln();
    let value = -d * d * log;
    let first = -2.0 * d * log - d * d / g;
    let second = -2.0 * log - 4.0 * d / g + d * d / (g * g);
    (value, first, second)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_central_differences() {
        let a = 1e-3;
        for g in [1e-6, 1e-5, 1e-4, 3e-4, 7e-4, 9.9e-4] {
            let (_, d1, d2) = barrier(g, a);
            let h = g * 1e-5;
            let fd1 = (barrier(g + h, a).0 - barrier(g - h, a).0) / (2.0 * h);
            let fd2 = (barrier(g + h, a).1 - barrier(g - h, a).1) / (2.0 * h);
            assert!(
                (fd1 - d1).abs() <= 1e-6 * d1.abs().max(1e-12),
                "g {g}: {fd1} vs {d1}"
            );
            assert!(
                (fd2 - d2).abs() <= 1e-6 * d2.abs().max(1e-9),
                "g {g}: {fd2} vs {d2}"
            );
        }
    }

    #[test]
    fn smooth_at_activation_and_infinite_at_contact() {
        let a = 2.0;
        // C²: value, slope and curvature all vanish as g → ĝ⁻ (curvature like 2(ĝ−g)/ĝ... → 0).
        let (v, d1, d2) = barrier(a * (1.0 - 1e-9), a);
        assert!(
            v.abs() < 1e-17 && d1.abs() < 1e-17 && d2.abs() < 1e-8,
            "{v} {d1} {d2}"
        );
        assert_eq!(barrier(a, a), (0.0, 0.0, 0.0));
        assert_eq!(barrier(0.0, a).0, f64::INFINITY);
        assert_eq!(barrier(-1.0, a).0, f64::INFINITY);
        assert!(barrier(1e-12, a).0 > barrier(1e-6, a).0);
        // Repulsive (b′ < 0) and convex (b″ > 0) inside the activation distance.
        for g in [1e-6, 0.5, 1.9] {
            let (_, d1, d2) = barrier(g, a);
            assert!(d1 < 0.0 && d2 > 0.0, "g {g}: {d1} {d2}");
        }
    }
}
