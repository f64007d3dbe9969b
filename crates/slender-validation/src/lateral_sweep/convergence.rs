//! Mesh convergence of the shell's critical Γ_c and its extrapolation to the converged value,
//! which is compared with the plate master curve (see `acceptance.rs` for the targets); the
//! observed order of convergence comes from three meshes (Richardson).

use serde::{Deserialize, Serialize};

use std::convert::Infallible;

use crate::numerics::{bisect, Bisection, Side};
use crate::shell_model::ShellModel;

/// Γ_c of one aspect ratio on a sequence of meshes and its extrapolation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CriticalConvergence {
    /// Shell discretization.
    pub model: ShellModel,
    /// w/L.
    pub width_ratio: f64,
    /// Elements along the length, ascending.
    pub n_lengths: Vec<usize>,
    /// Γ_c from the inertia on each mesh (NaN where the bisection failed).
    pub gamma_c: Vec<f64>,
    /// Extrapolation from the three finest meshes (None with fewer than three finite values).
    pub extrapolation: Option<Extrapolation>,
    /// Γ_c of the plate master curve (NaN if unavailable).
    pub master: f64,
}

/// Richardson extrapolation Γ(n) ≈ Γ_∞ + C·n^(−p) through three meshes.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Extrapolation {
    /// Γ_∞.
    pub value: f64,
    /// The observed order p; `assumed_order` says whether it was observed or assumed.
    pub order: f64,
    /// True when the three values were not monotone (or gave p outside [0.5, 6]) and the
    /// model's nominal order ([`nominal_order`]) was assumed with the two finest meshes.
    pub assumed_order: bool,
}

/// The order assumed when the observed one is not usable: 2 for the mid-edge shell (O(h²)
/// elements), 4 for the cubic B-spline shell (eigenvalues converge as h^(2(p−1))).
pub fn nominal_order(model: ShellModel) -> f64 {
    match model {
        ShellModel::Midedge => 2.0,
        ShellModel::Bspline => 4.0,
    }
}

/// Extrapolates Γ(n) from the three values of the finest meshes `n` (ascending, distinct),
/// falling back to the order `assumed` when the observed one is not usable: p from (Γ₁ − Γ₂)/(Γ₂ − Γ₃) = (n₁^−p − n₂^−p)/(n₂^−p − n₃^−p) (bisection: the right side is
/// monotone in p), then Γ_∞ = Γ₃ − (Γ₂ − Γ₃)·n₃^−p/(n₂^−p − n₃^−p).
pub fn richardson(n: [usize; 3], gamma: [f64; 3], assumed: f64) -> Option<Extrapolation> {
    if gamma.iter().any(|g| !g.is_finite()) || !(n[0] < n[1] && n[1] < n[2]) {
        return None;
    }
    let h = |p: f64, k: usize| (n[k] as f64).powf(-p);
    let extrapolate = |p: f64, assumed_order: bool| Extrapolation {
        value: gamma[2] - (gamma[1] - gamma[2]) * h(p, 2) / (h(p, 1) - h(p, 2)),
        order: p,
        assumed_order,
    };
    let (d1, d2) = (gamma[0] - gamma[1], gamma[1] - gamma[2]);
    let ratio = |p: f64| (h(p, 0) - h(p, 1)) / (h(p, 1) - h(p, 2));
    let (lo, hi) = (0.5, 6.0);
    if d2 == 0.0 || d1 / d2 <= 0.0 {
        return Some(extrapolate(assumed, true));
    }
    let target = d1 / d2;
    if !(ratio(lo) <= target && target <= ratio(hi)) {
        return Some(extrapolate(assumed, true));
    }
    // 100 halvings of [0.5, 6] reach f64 resolution.
    let side = |p: f64| {
        Ok::<_, Infallible>(if ratio(p) < target {
            Side::Low
        } else {
            Side::High
        })
    };
    let p = bisect(side, lo, hi, Bisection::linear(0.0).with_max_halvings(100)).ok()?;
    Some(extrapolate(p, false))
}

impl CriticalConvergence {
    /// Builds the record from Γ_c per mesh (`n_lengths` ascending) and the master value.
    pub fn new(
        model: ShellModel,
        width_ratio: f64,
        n_lengths: Vec<usize>,
        gamma_c: Vec<f64>,
        master: f64,
    ) -> Self {
        let k = n_lengths.len();
        let extrapolation = (k >= 3)
            .then(|| {
                richardson(
                    [n_lengths[k - 3], n_lengths[k - 2], n_lengths[k - 1]],
                    [gamma_c[k - 3], gamma_c[k - 2], gamma_c[k - 1]],
                    nominal_order(model),
                )
            })
            .flatten();
        Self {
            model,
            width_ratio,
            n_lengths,
            gamma_c,
            extrapolation,
            master,
        }
    }

    /// Γ_c on the mesh with `n` elements along the length, if computed.
    pub fn at(&self, n: usize) -> Option<f64> {
        self.n_lengths
            .iter()
            .position(|&k| k == n)
            .map(|i| self.gamma_c[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_power_law_exactly() {
        for p in [1.0, 2.0, 3.3] {
            let g = |n: f64| 17.0 + 5.0 * n.powf(-p);
            let e = richardson([8, 15, 30], [g(8.0), g(15.0), g(30.0)], 2.0).unwrap();
            assert!(!e.assumed_order);
            assert!((e.order - p).abs() < 1e-9, "p = {p}: {}", e.order);
            assert!((e.value - 17.0).abs() < 1e-9, "p = {p}: {}", e.value);
        }
    }

    #[test]
    fn oscillating_values_fall_back_to_second_order() {
        let e = richardson([8, 15, 30], [10.0, 11.0, 10.5], 2.0).unwrap();
        assert!(e.assumed_order);
        assert_eq!(e.order, 2.0);
        // Γ₃ − (Γ₂ − Γ₃)·30⁻²/(15⁻² − 30⁻²) = 10.5 − 0.5/3.
        assert!((e.value - (10.5 - 0.5 / 3.0)).abs() < 1e-12);
    }

    #[test]
    fn rejects_unusable_input() {
        assert!(richardson([8, 15, 30], [1.0, f64::NAN, 2.0], 2.0).is_none());
        assert!(richardson([15, 8, 30], [1.0, 2.0, 3.0], 2.0).is_none());
    }
}
