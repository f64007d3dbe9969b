//! `slender._slender`: the Python extension module of slender (PyO3, stable ABI ≥ 3.9).
//!
//! A thin layer over `slender-core` and `slender-validation`: scenes are parsed here (TOML or
//! JSON text, the format of `slender solve`), solved and edited through
//! [`slender_core::scene::Session`], and results are handed to Python as JSON text (the same
//! serializer as `slender solve`'s `result.json`, so the numbers are the same bits) that the
//! pure-Python package `slender` turns into NumPy arrays. Every solve runs with the GIL
//! released; a Rust panic becomes `slender.SolverPanic`, never an abort; a bad scene becomes
//! `slender.SceneError` (a `ValueError`) whose message starts with the field's path.

mod errors;
mod internal_loads;
mod scene_text;
mod session;
mod validation;

use pyo3::prelude::*;

/// The extension module.
#[pymodule]
fn _slender(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<errors::SceneError>())?;
    m.add("SolverPanic", py.get_type::<errors::SolverPanic>())?;
    m.add_class::<session::PySession>()?;
    m.add_class::<session::PyEditReport>()?;
    m.add_function(wrap_pyfunction!(scene_text::normalize_scene, m)?)?;
    m.add_function(wrap_pyfunction!(errors::_panic_for_test, m)?)?;
    validation::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
