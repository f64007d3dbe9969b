//! Self-weight: the consistent load of a uniform weight. The work of gravity on the surface
//! is ∫ρh g·r dA = Σ_c m_c g·P_c with m_c = ∫ρh N_c dA, so the control-point masses m_c give
//! the exact load (not a lumping approximation); they are also the mass metric's inertia.

use crate::assembly::Assembler;
use crate::geometry::Vec3;
use crate::linalg::SymmetricMatrix;

/// Adds the weight of control points with masses `masses` (kg) at `points` (rest positions
/// `rest`, m) under gravity `g` (m/s²) to `asm`; `dof(k, c)` is the free DOF of coordinate c
/// of control point k.
pub fn add_gravity<M: SymmetricMatrix>(
    asm: &mut Assembler<'_, M>,
    masses: &[f64],
    points: &[Vec3],
    rest: &[Vec3],
    g: &Vec3,
    dof: impl Fn(usize, usize) -> Option<usize>,
) {
    for (k, m) in masses.iter().enumerate() {
        // One potential per control point, so that the round-off scale of the energy is
        // Σ|m g·x| (the terms of a strip hanging about z = 0 cancel in the sum).
        let force = g * *m;
        asm.external_energy(-force.dot(&points[k]), force.dot(&(points[k] - rest[k])));
        for c in 0..3 {
            let Some(i) = dof(k, c) else { continue };
            asm.external_force(force[c].abs());
            asm.generalized_force(i, force[c]);
        }
    }
}
