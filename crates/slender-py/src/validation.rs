//! The benchmarks' master curves and cases, callable from Python; results as plain records
//! (dicts of numbers and lists).

use pyo3::prelude::*;
use pyo3::types::PyDict;
use slender_core::solver::SolverParams;
use slender_validation::cantilever::case::{CantileverCase, MeshKind};
use slender_validation::cantilever::master_curve::heavy_elastica as heavy_elastica_core;
use slender_validation::cantilever::sweep::run_case;
use slender_validation::lateral_buckling::{critical_gamma, MasterCurve};
use slender_validation::materials::ROD_SETS;

use crate::errors::{guarded, scene_error};

/// The heavy elastica (the rod cantilever's master curve) at Γ = ρAgL³/EI, by multiple
/// shooting: a dict with `gamma`, `clamp_curvature` (1/L), `tip_angle` (rad), `dx`, `dy`
/// (units of L), `ratio` = dy/dx and `shape`, n + 1 points (x, y) in units of L (y down
/// negative) at equal arc-length stations.
#[pyfunction]
#[pyo3(signature = (gamma, n = 100))]
fn heavy_elastica<'py>(py: Python<'py>, gamma: f64, n: usize) -> PyResult<Bound<'py, PyDict>> {
    let e = py
        .detach(|| guarded(|| heavy_elastica_core(gamma)))?
        .map_err(|e| scene_error(py, "gamma", &e.to_string()))?;
    let d = PyDict::new(py);
    d.set_item("gamma", e.gamma)?;
    d.set_item("clamp_curvature", e.clamp_curvature)?;
    d.set_item("tip_angle", e.tip_angle)?;
    d.set_item("dx", e.dx)?;
    d.set_item("dy", e.dy)?;
    d.set_item("ratio", e.ratio())?;
    d.set_item("shape", e.shape(n))?;
    Ok(d)
}

/// One case of the rod cantilever benchmark (seed §3): the clamped rod of material set
/// `material` ("rod" | "bundle", seed Table 1) under its own weight at Γ, meshed with
/// `n_elements` elements (`mesh` "uniform" | "graded"), solved by slender's discrete elastic
/// rod and scored against the heavy elastica. A dict of the benchmark's record fields.
#[pyfunction]
#[pyo3(signature = (gamma, n_elements = 20, material = "rod", mesh = "graded"))]
fn cantilever_case<'py>(
    py: Python<'py>,
    gamma: f64,
    n_elements: usize,
    material: &str,
    mesh: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let Some(set) = ROD_SETS.iter().find(|s| s.name == material) else {
        let names: Vec<&str> = ROD_SETS.iter().map(|s| s.name).collect();
        return Err(scene_error(
            py,
            "material",
            &format!("{material:?}: must be one of {names:?}"),
        ));
    };
    let Some(mesh_kind) = MeshKind::from_name(mesh) else {
        return Err(scene_error(
            py,
            "mesh",
            &format!("{mesh:?}: must be \"uniform\", \"quadratic\" or \"graded\""),
        ));
    };
    if n_elements == 0 {
        return Err(scene_error(py, "n_elements", "0: must be >= 1"));
    }
    let case = CantileverCase {
        material: *set,
        mesh: mesh_kind,
        n_elements,
        gamma,
    };
    let record = py
        .detach(|| guarded(|| run_case(&case, &SolverParams::default())))?
        .map_err(|e| scene_error(py, "gamma", &e.to_string()))?;
    let text = serde_json::to_string(&record).expect("a record serializes");
    let json = py.import("json")?;
    Ok(json.call_method1("loads", (text,))?.cast_into::<PyDict>()?)
}

/// Γ_c = ρhgL³/D of the lateral-buckling benchmark (a strip clamped with its width along
/// gravity) at width ratio w/L and Poisson's ratio ν, from the master curve `curve`:
/// "kirchhoff_plate" (default), "vlasov_beam" (B = E w h³/12) or "vlasov_plate" (B = D w).
#[pyfunction]
#[pyo3(signature = (w_over_l, nu, curve = "kirchhoff_plate"))]
fn lateral_buckling_critical_gamma(
    py: Python<'_>,
    w_over_l: f64,
    nu: f64,
    curve: &str,
) -> PyResult<f64> {
    let c = match curve {
        "kirchhoff_plate" => MasterCurve::KirchhoffPlate,
        "vlasov_beam" => MasterCurve::VlasovBeamStiffness,
        "vlasov_plate" => MasterCurve::VlasovPlateStiffness,
        other => {
            return Err(scene_error(
                py,
                "curve",
                &format!(
                    "{other:?}: must be \"kirchhoff_plate\", \"vlasov_beam\" or \"vlasov_plate\""
                ),
            ))
        }
    };
    py.detach(|| guarded(|| critical_gamma(w_over_l, nu, c)))?
        .map_err(|e| scene_error(py, "w_over_l", &e.to_string()))
}

/// Adds the functions to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(heavy_elastica, m)?)?;
    m.add_function(wrap_pyfunction!(cantilever_case, m)?)?;
    m.add_function(wrap_pyfunction!(lateral_buckling_critical_gamma, m)?)?;
    Ok(())
}
