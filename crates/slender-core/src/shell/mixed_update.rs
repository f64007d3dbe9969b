//! The mixed-integration-point (MIP) Newton update of the membrane (Magisano, Leonetti &
//! Garcea, CMAME 313, 2017), the cure for Newton steps that a thin shell's membrane limits to
//! about a thickness (design.md §3.3).
//!
//! Why the plain Newton step fails: a linearized step moves a bending strip normal to itself
//! and, at second order, stretches it. For a step of size δ the spurious membrane energy is
//! about 3(δ/h)² times the bending energy it buys, so the line search cuts every large rotation
//! down to a thickness, and at the next iterate the spurious membrane tension enters the
//! geometric stiffness and spoils the step again (≈ 700 Newton iterations per lateral-buckling
//! protocol run on Ω_shell, n_L = 30, measured).
//!
//! The MIP method keeps the displacement discretization — hence the equilibria, which solve
//! the ordinary gradient = 0 — and changes only the iteration: it treats the membrane stress
//! as an independent field, condensed face by face. After condensation the Newton system has
//! the ordinary right-hand side; the difference is that the stress in the geometric stiffness
//! is the one of the *linearly* updated strain, a(q) − r, where r is the second-order part of
//! the last step's change of the first fundamental form (for a face with edge steps Δe₁,
//! Δe₂: r = (Δe₁·Δe₁, Δe₁·Δe₂, Δe₂·Δe₂)). The line search measures a trial point by the
//! Hellinger–Reissner functional at the updated stress, which is the energy minus the
//! membrane energy of r alone ([`remainder_energy`]); both equal the energy and its
//! derivatives when r = 0, and r → 0 as Newton converges, so the converged state's Hessian —
//! and the inertia that decides stability — is the exact one.
//!
//! The remainder lives in the state ([`ShellState::membrane_remainder`]
//! (super::ShellState::membrane_remainder)): `displace` writes it, everything else that
//! builds or moves a state leaves it empty (r = 0, the exact Hessian).

use nalgebra::Vector3;

use crate::geometry::Vec3;

use super::membrane::{quadratic_form, FaceRest};

/// Second-order part of the change of each face's first fundamental form from `before` to
/// `after` (vertex positions, m): (Δe₁·Δe₁, Δe₁·Δe₂, Δe₂·Δe₂) (m²), into `out` (one per face).
pub fn membrane_remainders(
    faces: &[[usize; 3]],
    before: &[Vec3],
    after: &[Vec3],
    out: &mut Vec<Vector3<f64>>,
) {
    out.clear();
    out.extend(faces.iter().map(|t| {
        let d = |k: usize| after[t[k]] - before[t[k]];
        let (d0, d1, d2) = (d(0), d(1), d(2));
        let (e1, e2) = (d1 - d0, d2 - d0);
        Vector3::new(e1.dot(&e1), e1.dot(&e2), e2.dot(&e2))
    }));
}

/// Membrane energy (J) of a change `r` of the first fundamental form alone (the quantity the
/// MIP merit leaves out), for a face with rest data `rest`, thickness `h` (m) and 2-D Lamé
/// constants `lambda`, `mu` (Pa).
pub fn remainder_energy(rest: &FaceRest, h: f64, lambda: f64, mu: f64, r: &Vector3<f64>) -> f64 {
    let k = quadratic_form(&rest.abar_inv, lambda, mu, rest.area * h / 4.0);
    0.5 * r.dot(&(k * r))
}
