//! Self-weight: the consistent load of a uniform weight. The work of gravity on the surface
//! is ∫ρh g·r dA = Σ_c m_c g·P_c with m_c = ∫ρh N_c dA, so the control-point masses m_c give
//! the exact load (not a lumping approximation); they are also the mass metric's inertia.

use crate::geometry::Vec3;

/// Potential energy (J) of the weight at acceleration `g` (m/s²): −Σ m_c g·P_c.
pub fn gravity_energy(masses: &[f64], points: &[Vec3], g: &Vec3) -> f64 {
    -masses
        .iter()
        .zip(points)
        .map(|(m, x)| m * g.dot(x))
        .sum::<f64>()
}
