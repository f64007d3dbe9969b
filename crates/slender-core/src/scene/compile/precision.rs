//! The check that double precision resolves a rod's bending. A stretching (or shear) stiffness
//! absurdly large against the bending and twisting stiffnesses, on the rod's mesh and at its
//! coordinates, rounds every edge's stretching force by more than the forces that bend the
//! rod: no solve could tell an equilibrium from round-off, and a structure moved only by its
//! supports (no loads to measure the residual against) could even be reported converged.
//! Such a section is refused at compile time, naming the valid range.

use crate::framed::ShearStiffness;
use crate::geometry::Vec3;
use crate::rod::RodProperties;

use super::super::error::SceneError;
use super::super::spec::{RodSpec, SectionSpec};

/// Largest accepted ratio of an edge's stretching-force round-off, k·ε·|x|ₘₐₓ/ℓₘᵢₙ, to the
/// bending force scale min(EI₁, EI₂, GJ)/L². Measured on cantilevers of 20 and 100 elements,
/// 1 m long, GJ = 0.04 N m², at the origin and 100 m from it, EA from 1e6 to 1e30 N: hanging
/// ones at a ratio ≤ 0.56 converged with their midpoints within 3.3e-7 m of the EA = 1e6 N
/// ones (the residual's round-off lies along the stiff stretching, which it hardly moves); at
/// 11 one converged and one did not, at 55 neither. Cables moved only by their supports were
/// reported converged at relative residuals of 1.2 to 2 from a ratio of about 1e15 on. A
/// 6 mm cable of 1 m in 100 elements sits at 1e-8.
pub const PRECISION_LIMIT: f64 = 1.0;

/// Refuses a rod whose bending double precision cannot resolve (see the module's text).
/// `positions` are the rod's rest vertices (m), `length` its rest length (m).
pub(super) fn check_bending_resolved(
    path: &str,
    spec: &RodSpec,
    properties: &RodProperties,
    shear: Option<ShearStiffness>,
    positions: &[Vec3],
    length: f64,
) -> Result<(), SceneError> {
    let s = &properties.stiffness;
    let (shear_max, shear_is_max) = match shear {
        Some(g) => (g.ga1.max(g.ga2), g.ga1.max(g.ga2) > s.ea),
        None => (0.0, false),
    };
    let axial = s.ea.max(shear_max);
    let bending = s.ei1.min(s.ei2).min(s.gj);
    let shortest = positions
        .windows(2)
        .map(|w| (w[1] - w[0]).norm())
        .fold(f64::INFINITY, f64::min);
    // The rounding of a coordinate is ε·|x| (half of it at best): what one edge's length,
    // hence its strain times its length, is known to.
    let reach = positions.iter().map(|p| p.amax()).fold(0.0, f64::max);
    let round_off = axial * f64::EPSILON * reach / shortest;
    let bending_scale = bending / (length * length);
    let ratio = round_off / bending_scale;
    if ratio <= PRECISION_LIMIT {
        return Ok(());
    }
    let largest = PRECISION_LIMIT * bending_scale * shortest / (f64::EPSILON * reach);
    let field = match (&spec.section, shear_is_max) {
        (_, true) => format!("{path}.shear_stiffness"),
        (SectionSpec::Stiffness { .. }, false) => format!("{path}.section.ea"),
        _ => format!("{path}.section"),
    };
    let what = if shear_is_max {
        "shear stiffness"
    } else {
        "axial stiffness EA"
    };
    Err(SceneError::new(
        field,
        format!(
            "the {what} {axial:.3e} N is beyond double precision against the bending stiffness \
             min(EI1, EI2, GJ) = {bending:.3e} N m² on this mesh: the rounding of one edge's \
             stretching force (stiffness × ε × {reach:.3e} m / shortest edge {shortest:.3e} m = \
             {round_off:.2e} N) exceeds the force that bends the rod (min EI / L² = \
             {bending_scale:.2e} N), so no equilibrium could be told from round-off; valid \
             here: {what} <= {largest:.3e} N (or a larger bending stiffness, longer elements, \
             coordinates nearer the origin)"
        ),
    ))
}
