//! The seed's geometric measures of out-of-plane deformation (seed §4.1):
//! Ξ₁[ξ] = ∫₀ᴸ |ξ| ds for ξ_y = y-coordinate and ξ_τ = Frenet torsion of the centerline.

use serde::{Deserialize, Serialize};
use slender_core::geometry::{signed_angle, Vec3};

/// Both measures of one shape.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ShapeMeasures {
    /// Ξ₁[ξ_y] / L² = ∫|y| ds / L² (dimensionless).
    pub xi_y: f64,
    /// Ξ₁[ξ_τ] = ∫|τ| ds (rad).
    pub xi_tau: f64,
    /// max |y| / L.
    pub max_y: f64,
}

/// Curvature below which the binormal (and so the torsion) of a vertex is undefined: turning
/// angles this small are round-off in a straight segment.
const MIN_TURN: f64 = 1e-9;

/// Measures of the polyline `positions` with rest edge lengths `rest_lengths` (m) and rod
/// length `length` (m).
///
/// ∫|y| ds uses the trapezoid rule on rest arc length. The discrete Frenet torsion of edge j is
/// the angle between the binormals of its two end vertices about the edge, taken between the
/// binormal *lines* (in (−π/2, π/2]) so that a planar inflection, where the Frenet binormal
/// flips sign, adds no torsion; ∫|τ| ds is the sum of those angles.
pub fn shape_measures(positions: &[Vec3], rest_lengths: &[f64], length: f64) -> ShapeMeasures {
    let n = rest_lengths.len();
    let mut xi_y = 0.0;
    let mut max_y: f64 = 0.0;
    for j in 0..n {
        xi_y += 0.5 * rest_lengths[j] * (positions[j].y.abs() + positions[j + 1].y.abs());
        max_y = max_y.max(positions[j].y.abs());
    }
    max_y = max_y.max(positions[n].y.abs());
    let tangents: Vec<Vec3> = positions
        .windows(2)
        .map(|w| (w[1] - w[0]).normalize())
        .collect();
    let binormal = |i: usize| -> Option<Vec3> {
        let b = tangents[i - 1].cross(&tangents[i]);
        (b.norm() > MIN_TURN).then(|| b.normalize())
    };
    let mut xi_tau = 0.0;
    // Edges 1 … n − 2 of the n: each between two hinges.
    for (j, &t) in tangents
        .iter()
        .enumerate()
        .take(n.saturating_sub(1))
        .skip(1)
    {
        if let (Some(b0), Some(b1)) = (binormal(j), binormal(j + 1)) {
            let mut psi = signed_angle(&(b0 - t * t.dot(&b0)), &(b1 - t * t.dot(&b1)), &t);
            if psi > std::f64::consts::FRAC_PI_2 {
                psi -= std::f64::consts::PI;
            } else if psi < -std::f64::consts::FRAC_PI_2 {
                psi += std::f64::consts::PI;
            }
            xi_tau += psi.abs();
        }
    }
    ShapeMeasures {
        xi_y: xi_y / (length * length),
        xi_tau,
        max_y: max_y / length,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planar_curves_have_no_torsion_even_with_inflections() {
        // An S-curve in the xz-plane.
        let pts: Vec<Vec3> = (0..=100)
            .map(|k| {
                let s = k as f64 / 100.0;
                Vec3::new(s, 0.0, (6.0 * s).sin() * 0.2)
            })
            .collect();
        let m = shape_measures(&pts, &vec![0.01; 100], 1.0);
        assert_eq!(m.xi_y, 0.0);
        assert!(m.xi_tau < 1e-12, "{}", m.xi_tau);
    }

    #[test]
    fn helix_torsion_integrates_to_tau_times_length() {
        // Helix of radius a, pitch 2πc: τ = c/(a² + c²), curvature a/(a² + c²).
        let (a, c) = (0.3_f64, 0.1_f64);
        let speed = (a * a + c * c).sqrt();
        let length = 4.0;
        let n = 4000;
        let pts: Vec<Vec3> = (0..=n)
            .map(|k| {
                let phi = length * k as f64 / n as f64 / speed;
                Vec3::new(a * phi.cos(), a * phi.sin(), c * phi)
            })
            .collect();
        let rest: Vec<f64> = pts.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
        let m = shape_measures(&pts, &rest, length);
        let exact = c / (a * a + c * c) * length;
        assert!(
            (m.xi_tau / exact - 1.0).abs() < 1e-3,
            "{} vs {exact}",
            m.xi_tau
        );
        assert!(m.xi_y > 0.0);
    }
}
