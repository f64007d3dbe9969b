//! How failures cross into Python: bad input is a `SceneError` (a `ValueError` naming the
//! field), a panic inside the solver is a `SolverPanic` (a `RuntimeError`) with its message.

use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    _slender,
    SceneError,
    PyValueError,
    "Bad input: the message starts with the path of the offending field (e.g. \
     `rods[0].material.young`), also in the `field` attribute."
);
pyo3::create_exception!(
    _slender,
    SolverPanic,
    PyRuntimeError,
    "An internal error (a Rust panic) inside slender; the session that raised it must not be \
     used further. Please report it with the scene."
);

/// A `SceneError` whose message is `field: message` and whose `field` attribute is `field`.
pub fn scene_error(py: Python<'_>, field: &str, message: &str) -> PyErr {
    let text = if field.is_empty() {
        message.to_string()
    } else {
        format!("{field}: {message}")
    };
    let err = SceneError::new_err(text);
    // Setting an attribute on a fresh exception object cannot fail in practice; if it did,
    // the message still names the field.
    let _ = err.value(py).setattr("field", field);
    err
}

/// The core's scene error as a Python exception.
pub fn from_scene_error(py: Python<'_>, e: &slender_core::scene::SceneError) -> PyErr {
    scene_error(py, &e.path, &e.message)
}

/// Runs `f`, turning a panic into `SolverPanic` with the panic's message.
pub fn guarded<T>(f: impl FnOnce() -> T) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| {
        let msg = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_string());
        SolverPanic::new_err(format!("internal error in slender: {msg}"))
    })
}

/// Panics inside the guard with `message`: the test suite's way to check that a panic in
/// the solver reaches Python as `SolverPanic` (never an abort, never a `PanicException`).
#[pyfunction]
pub fn _panic_for_test(message: &str) -> PyResult<()> {
    guarded(|| panic!("{message}"))
}
