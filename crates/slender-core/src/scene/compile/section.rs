//! A rod's section and material from the scene file: stiffnesses, mass per length and the
//! radius drawn in shape files; and the name check shared by rods and shells.

use crate::error::ModelError;
use crate::framed::ShearStiffness;
use crate::rod::{CrossSection, Material, RodProperties, SectionStiffness};

use super::super::error::SceneError;
use super::super::spec::{MaterialSpec, RodModelSpec, RodSpec, SectionSpec};

pub(super) fn material(path: &str, m: &MaterialSpec) -> Result<Material, SceneError> {
    let poisson = match (m.poisson, m.shear_modulus) {
        (Some(nu), None) => nu,
        (None, Some(g)) => {
            if !(g.is_finite() && g > 0.0) {
                return Err(SceneError::new(
                    format!("{path}.shear_modulus"),
                    format!("{g}: must be finite and > 0"),
                ));
            }
            let nu = m.young / (2.0 * g) - 1.0;
            if !(nu > -1.0 && nu <= 0.5) {
                return Err(SceneError::new(
                    format!("{path}.shear_modulus"),
                    format!(
                        "{g}: with young = {} the implied Poisson ratio {nu} is outside (-1, 0.5]; valid: shear_modulus >= young/3",
                        m.young
                    ),
                ));
            }
            nu
        }
        _ => {
            return Err(SceneError::new(
                path,
                "give exactly one of `poisson` or `shear_modulus`",
            ))
        }
    };
    Ok(Material {
        young: m.young,
        poisson,
        density: m.density,
    })
}

/// Stiffnesses, mass per length and drawn radius of a rod's section.
pub(super) fn section(
    path: &str,
    spec: &RodSpec,
    length: f64,
) -> Result<(RodProperties, f64), SceneError> {
    let geometric = |shape: CrossSection, radius: f64| {
        let m = spec.material.as_ref().ok_or_else(|| {
            SceneError::new(
                format!("{path}.material"),
                "missing: a circle or rectangle section needs `material` (young, poisson or shear_modulus, density)",
            )
        })?;
        let mat = material(&format!("{path}.material"), m)?;
        let props = shape.properties(&mat).map_err(|e| {
            // Name the table the offending field is in.
            let field = match &e {
                ModelError::InvalidParameter { field, .. }
                | ModelError::InvalidStructure { field, .. } => field.as_str(),
            };
            let table = if ["young", "poisson", "density"].contains(&field) {
                "material"
            } else {
                "section"
            };
            SceneError::model(format!("{path}.{table}"), e)
        })?;
        Ok((props, radius))
    };
    match spec.section {
        SectionSpec::Circle { diameter } => {
            geometric(CrossSection::Circle { diameter }, 0.5 * diameter)
        }
        SectionSpec::Rectangle { width, height } => geometric(
            CrossSection::Rectangle { width, height },
            (width * height / std::f64::consts::PI).sqrt(),
        ),
        SectionSpec::Stiffness {
            ea,
            ei1,
            ei2,
            gj,
            linear_density,
            display_radius,
        } => {
            if spec.material.is_some() {
                return Err(SceneError::new(
                    format!("{path}.material"),
                    "not allowed with section shape = \"stiffness\" (the stiffnesses and linear_density say it all)",
                ));
            }
            let props = RodProperties {
                stiffness: SectionStiffness { ea, ei1, ei2, gj },
                linear_density,
            };
            props
                .validate()
                .map_err(|e| SceneError::model(format!("{path}.section"), e))?;
            let radius = display_radius.unwrap_or(0.01 * length);
            if !(radius.is_finite() && radius > 0.0) {
                return Err(SceneError::new(
                    format!("{path}.section.display_radius"),
                    format!("{radius}: must be finite and > 0"),
                ));
            }
            Ok((props, radius))
        }
    }
}

/// The shear stiffnesses of a Cosserat rod or SE(3) beam: `shear_stiffness` if given, else
/// κGA of the geometric section with Timoshenko's coefficient (solid circle
/// κ = 6(1+ν)/(7+6ν), solid rectangle κ = 10(1+ν)/(12+11ν)). `None` for the discrete
/// elastic rod, which has no shear (and may not be given one).
pub(super) fn shear(path: &str, spec: &RodSpec) -> Result<Option<ShearStiffness>, SceneError> {
    let field = format!("{path}.shear_stiffness");
    if spec.model == RodModelSpec::Der {
        return match spec.shear_stiffness {
            Some(_) => Err(SceneError::new(
                field,
                "only the shearable models (model = \"cosserat\", \"cosserat_tan\" or \"se3\") take a shear stiffness; the discrete elastic rod has none",
            )),
            None => Ok(None),
        };
    }
    if let Some([ga1, ga2]) = spec.shear_stiffness {
        for (k, v) in [ga1, ga2].iter().enumerate() {
            if !(v.is_finite() && *v > 0.0) {
                return Err(SceneError::new(
                    format!("{field}[{k}]"),
                    format!("{v}: must be finite and > 0 (N); a rod with no shear stiffness has no equilibrium"),
                ));
            }
        }
        return Ok(Some(ShearStiffness { ga1, ga2 }));
    }
    let (area, kappa_of): (f64, fn(f64) -> f64) = match spec.section {
        SectionSpec::Circle { diameter } => (
            std::f64::consts::FRAC_PI_4 * diameter * diameter,
            |nu| 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu),
        ),
        SectionSpec::Rectangle { width, height } => (width * height, |nu| {
            10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)
        }),
        SectionSpec::Stiffness { .. } => {
            return Err(SceneError::new(
                field,
                format!(
                    "missing: model = \"{}\" with section shape = \"stiffness\" needs the shear stiffnesses [κGA₁, κGA₂] (N)",
                    spec.model.name()
                ),
            ))
        }
    };
    // The section's own checks (diameter, material) ran in `section`.
    let m = spec.material.as_ref().expect("checked with the section");
    let mat = material(&format!("{path}.material"), m)?;
    let g = mat.young / (2.0 * (1.0 + mat.poisson));
    Ok(Some(ShearStiffness::isotropic(
        kappa_of(mat.poisson) * g * area,
    )))
}

/// Name check: safe as a file-name stem.
pub(crate) fn check_name(path: &str, name: &str) -> Result<(), SceneError> {
    let ok = !name.is_empty()
        && name.len() <= 64
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_');
    if ok {
        Ok(())
    } else {
        Err(SceneError::new(
            path,
            format!("{name:?}: must be 1 to 64 characters among letters, digits, '-' and '_'"),
        ))
    }
}
