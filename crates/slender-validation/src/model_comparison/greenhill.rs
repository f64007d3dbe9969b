//! Greenhill's heavy column by inertia, for any rod model: the smallest Γ at which an upright
//! column clamped at its foot has a negative Hessian eigenvalue (bisection on the inertia).

use slender_core::geometry::Vec3;
use slender_core::rod::{Grading, RestCurve};
use slender_core::solver::{EquilibriumSolver, SolverParams};
use slender_core::ModelError;

use crate::materials::RodMaterialSet;
use crate::rod_model::{BenchmarkRod, RodModel, RodSpec};

/// The critical ρAgL³/EI of the heavy column clamped at its foot (Greenhill 1881).
pub const GREENHILL: f64 = 7.837_347;

/// Relative width of the final bisection bracket.
const BRACKET: f64 = 1e-5;

fn column(material: RodMaterialSet, n: usize, gamma: f64) -> RodSpec {
    RodSpec {
        curve: RestCurve::Straight {
            start: [0.0; 3],
            direction: [0.0, 0.0, 1.0],
            length: material.length,
        },
        properties: material.properties,
        shear: material.shear(),
        elements: n,
        grading: Grading::Uniform,
        first_director: Vec3::x(),
        gravity: Vec3::new(0.0, 0.0, -material.gravity_for_gamma(gamma)),
        preload_gravity: Vec3::zeros(),
        planar_axis: None,
        darboux: Default::default(),
    }
}

fn stable<P: BenchmarkRod>(spec: &RodSpec, params: &SolverParams) -> Result<bool, ModelError> {
    let rod = P::from_spec(spec)?;
    let sol = EquilibriumSolver::new(&rod, rod.rest(), *params).solve(&rod, rod.rest(), 0.0, 1.0);
    sol.report.stable().ok_or_else(|| {
        ModelError::structure(
            "greenhill",
            format!(
                "the upright column did not converge: {:?}",
                sol.report.status
            ),
        )
    })
}

/// Γ_c of `model` with `n` uniform elements, by bisection on the inertia between 6 and 10.
pub fn greenhill_threshold(
    model: RodModel,
    material: RodMaterialSet,
    n: usize,
    params: &SolverParams,
) -> Result<f64, ModelError> {
    let params = SolverParams {
        compute_lambda_min: false,
        ..*params
    };
    let is_stable = |gamma: f64| -> Result<bool, ModelError> {
        let spec = column(material, n, gamma).for_model(model);
        crate::with_rod_model!(model, P => stable::<P>(&spec, &params))
    };
    let (mut lo, mut hi) = (6.0, 10.0);
    if !is_stable(lo)? || is_stable(hi)? {
        return Err(ModelError::structure(
            "greenhill",
            "the stability change is not between Γ = 6 and 10",
        ));
    }
    while hi - lo > BRACKET * lo {
        let mid = 0.5 * (lo + hi);
        if is_stable(mid)? {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}
