//! Bounds on the magnitudes of a scene's numbers, so that the products the solver forms
//! (stiffness / element length, …) stay finite.

use super::error::SceneError;
use super::spec::{Centerline, RodSpec, SectionSpec};

/// Magnitudes outside this range are rejected: no cable needs them, and products of such
/// numbers (stiffness / element length, …) would overflow the solver's arithmetic.
pub const MAGNITUDE_LIMIT: f64 = 1e30;
/// Smallest positive physical parameter accepted (1/[`MAGNITUDE_LIMIT`]).
pub const MAGNITUDE_FLOOR: f64 = 1e-30;

/// Checks that every number of a rod's specification is finite and within
/// ±[`MAGNITUDE_LIMIT`] (positive physical parameters also ≥ 1/MAGNITUDE_LIMIT); the rest of
/// the validation then works on numbers whose products stay finite.
pub fn check_magnitudes(path: &str, spec: &RodSpec) -> Result<(), SceneError> {
    let bounded = |p: String, v: f64| -> Result<(), SceneError> {
        if v.is_finite() && v.abs() <= MAGNITUDE_LIMIT {
            Ok(())
        } else {
            Err(SceneError::new(
                p,
                format!("{v:?}: must be finite with magnitude <= {MAGNITUDE_LIMIT:e}"),
            ))
        }
    };
    let positive = |p: String, v: f64| -> Result<(), SceneError> {
        if v.is_finite() && (MAGNITUDE_FLOOR..=MAGNITUDE_LIMIT).contains(&v) {
            Ok(())
        } else {
            Err(SceneError::new(
                p,
                format!("{v:?}: must be finite and in [{MAGNITUDE_FLOOR:e}, {MAGNITUDE_LIMIT:e}]"),
            ))
        }
    };
    let vec3 = |p: String, v: &[f64; 3]| -> Result<(), SceneError> {
        for (k, c) in v.iter().enumerate() {
            bounded(format!("{p}[{k}]"), *c)?;
        }
        Ok(())
    };
    let c = format!("{path}.centerline");
    match &spec.centerline {
        Centerline::Straight {
            start,
            direction,
            length,
        } => {
            vec3(format!("{c}.start"), start)?;
            vec3(format!("{c}.direction"), direction)?;
            positive(format!("{c}.length"), *length)?;
        }
        Centerline::Circle {
            start,
            tangent,
            normal,
            radius,
            length,
        } => {
            vec3(format!("{c}.start"), start)?;
            vec3(format!("{c}.tangent"), tangent)?;
            vec3(format!("{c}.normal"), normal)?;
            positive(format!("{c}.radius"), *radius)?;
            positive(format!("{c}.length"), *length)?;
        }
        Centerline::Helix {
            start,
            axis,
            normal,
            radius,
            pitch,
            length,
        } => {
            vec3(format!("{c}.start"), start)?;
            vec3(format!("{c}.axis"), axis)?;
            vec3(format!("{c}.normal"), normal)?;
            positive(format!("{c}.radius"), *radius)?;
            bounded(format!("{c}.pitch"), *pitch)?;
            positive(format!("{c}.length"), *length)?;
        }
        Centerline::Polyline { points } => {
            for (k, p) in points.iter().enumerate() {
                vec3(format!("{c}.points[{k}]"), p)?;
            }
        }
    }
    let sp = format!("{path}.section");
    match spec.section {
        SectionSpec::Circle { diameter } => positive(format!("{sp}.diameter"), diameter)?,
        SectionSpec::Rectangle { width, height } => {
            positive(format!("{sp}.width"), width)?;
            positive(format!("{sp}.height"), height)?;
        }
        SectionSpec::Stiffness {
            ea,
            ei1,
            ei2,
            gj,
            linear_density,
            display_radius,
        } => {
            positive(format!("{sp}.ea"), ea)?;
            positive(format!("{sp}.ei1"), ei1)?;
            positive(format!("{sp}.ei2"), ei2)?;
            positive(format!("{sp}.gj"), gj)?;
            positive(format!("{sp}.linear_density"), linear_density)?;
            if let Some(r) = display_radius {
                positive(format!("{sp}.display_radius"), r)?;
            }
        }
    }
    if let Some(m) = &spec.material {
        let mp = format!("{path}.material");
        positive(format!("{mp}.young"), m.young)?;
        positive(format!("{mp}.density"), m.density)?;
        if let Some(g) = m.shear_modulus {
            positive(format!("{mp}.shear_modulus"), g)?;
        }
        if let Some(nu) = m.poisson {
            bounded(format!("{mp}.poisson"), nu)?;
        }
    }
    if let Some(d) = &spec.first_director {
        vec3(format!("{path}.first_director"), d)?;
    }
    for (k, f) in spec.forces.iter().enumerate() {
        vec3(format!("{path}.forces[{k}].force"), &f.force)?;
    }
    for (k, m) in spec.moments.iter().enumerate() {
        vec3(format!("{path}.moments[{k}].moment"), &m.moment)?;
    }
    Ok(())
}
