//! Scene text (TOML or JSON, the format of `slender solve`) into [`Scene`], with errors that
//! name the field.
//!
//! TOML is parsed by `toml::from_str` exactly as the `slender` binary does, so a scene gives
//! the same `Scene` (and the same bits) in both. When a scene does not deserialize, the text
//! is parsed again into a generic value and deserialized through `serde_path_to_error`, which
//! yields the path of the offending field (`rods[0].material.young`) for the message.

use pyo3::prelude::*;
use slender_core::scene::Scene;

use crate::errors::scene_error;

/// Scene text syntax.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Syntax {
    /// TOML.
    Toml,
    /// JSON.
    Json,
}

/// The dotted path of a `serde_path_to_error` path (`.rods[0].material`) without the
/// leading dot.
fn field_of(path: &serde_path_to_error::Path) -> String {
    let p = path.to_string();
    if p == "." {
        String::new()
    } else {
        p.trim_start_matches('.').to_string()
    }
}

/// The field path and message of a scene value that does not deserialize.
fn located(value: serde_json::Value) -> Option<(String, String)> {
    match serde_path_to_error::deserialize::<_, Scene>(value) {
        Ok(_) => None,
        Err(e) => Some((field_of(e.path()), e.inner().to_string())),
    }
}

/// 1-based (line, column) of byte offset `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Parses scene text; `name` (a file name, or `"scene"`) starts syntax messages.
pub fn parse(py: Python<'_>, text: &str, syntax: Syntax, name: &str) -> PyResult<Scene> {
    match syntax {
        Syntax::Toml => toml::from_str::<Scene>(text).map_err(|e| {
            let place = match e.span() {
                Some(span) => {
                    let (l, c) = line_col(text, span.start);
                    format!("{name}:{l}:{c}")
                }
                None => name.to_string(),
            };
            let generic = toml::from_str::<toml::Value>(text)
                .ok()
                .and_then(|v| serde_json::to_value(v).ok())
                .and_then(located);
            match generic {
                Some((field, msg)) => scene_error(py, &field, &format!("{msg} ({place})")),
                None => scene_error(py, "", &format!("{place}: {}", e.message().trim_end())),
            }
        }),
        Syntax::Json => {
            let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
                scene_error(py, "", &format!("{name}:{}:{}: {e}", e.line(), e.column()))
            })?;
            serde_path_to_error::deserialize::<_, Scene>(value)
                .map_err(|e| scene_error(py, &field_of(e.path()), &e.inner().to_string()))
        }
    }
}

/// Parses scene text (`syntax` "toml" or "json") and returns it as JSON text with every
/// default filled in, or raises `SceneError` naming the field.
#[pyfunction]
#[pyo3(signature = (text, syntax = "toml", name = "scene"))]
pub fn normalize_scene(py: Python<'_>, text: &str, syntax: &str, name: &str) -> PyResult<String> {
    let syntax = match syntax {
        "toml" => Syntax::Toml,
        "json" => Syntax::Json,
        other => {
            return Err(scene_error(
                py,
                "syntax",
                &format!("{other:?}: must be \"toml\" or \"json\""),
            ))
        }
    };
    let scene = parse(py, text, syntax, name)?;
    serde_json::to_string(&scene).map_err(|e| scene_error(py, "", &e.to_string()))
}

/// A Python object of plain data (dict with string keys, list, tuple, str, bool, int, float,
/// None) as a JSON value. Floats are carried exactly (no text round trip).
pub fn to_value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<serde_json::Value> {
    use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
    use serde_json::Value;
    let py = obj.py();
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(Value::from(i));
        }
        if let Ok(u) = obj.extract::<u64>() {
            return Ok(Value::from(u));
        }
        return Err(scene_error(py, path, "integer out of range"));
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        let x = f.value();
        // JSON has no NaN or infinity: name the field rather than pass null.
        return serde_json::Number::from_f64(x)
            .map(Value::Number)
            .ok_or_else(|| scene_error(py, path, &format!("{x}: must be a finite number")));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.to_cow()?.into_owned()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut map = serde_json::Map::new();
        for (k, v) in d.iter() {
            let Ok(key) = k.extract::<String>() else {
                return Err(scene_error(py, path, "dictionary keys must be strings"));
            };
            let sub = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            map.insert(key, to_value(&v, &sub)?);
        }
        return Ok(Value::Object(map));
    }
    let items: Option<Vec<Bound<'_, PyAny>>> = if let Ok(l) = obj.cast::<PyList>() {
        Some(l.iter().collect())
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        Some(t.iter().collect())
    } else {
        None
    };
    if let Some(items) = items {
        return items
            .iter()
            .enumerate()
            .map(|(i, v)| to_value(v, &format!("{path}[{i}]")))
            .collect::<PyResult<Vec<_>>>()
            .map(Value::Array);
    }
    let type_name = obj.get_type().name()?.to_string();
    Err(scene_error(
        py,
        path,
        &format!(
            "a value of type {type_name} is not scene data (use dict, list, str, int, float, bool)"
        ),
    ))
}

/// A scene from a Python dict (exact floats), errors naming the field.
pub fn from_object(obj: &Bound<'_, PyAny>) -> PyResult<Scene> {
    let value = to_value(obj, "")?;
    serde_path_to_error::deserialize::<_, Scene>(value)
        .map_err(|e| scene_error(obj.py(), &field_of(e.path()), &e.inner().to_string()))
}
