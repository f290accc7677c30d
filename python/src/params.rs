//! Parameter values between Python and the graph: Python values are written as the text
//! `--set node.param=value` takes and parsed by the same code, so a value means the same from
//! Python as on the command line and its errors read the same.

use hatchery_graph::ParamValue;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyList, PyString, PyTuple};

use crate::errors::ParamError;

/// A parameter value as a Python object: float, int, bool, str (choices, paths, text,
/// data-relative values as written: "percentile(60)"), tuples for colours and vectors.
pub fn to_python<'py>(py: Python<'py>, value: &ParamValue) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        ParamValue::Float(v) => v.into_pyobject(py)?.into_any(),
        ParamValue::Int(v) => v.into_pyobject(py)?.into_any(),
        ParamValue::Bool(v) => PyBool::new(py, *v).to_owned().into_any(),
        ParamValue::Color(c) => PyTuple::new(py, c)?.into_any(),
        ParamValue::Vec3(v) => PyTuple::new(py, v)?.into_any(),
        ParamValue::Choice(t) | ParamValue::Path(t) | ParamValue::Text(t) => {
            PyString::new(py, t).into_any()
        }
        ParamValue::Relative(_, text) => PyString::new(py, text).into_any(),
    })
}

/// The command-line text of a Python value: str as it is, bool as true/false, numbers by
/// Python's `repr` (exact for floats), tuples and lists as `[a, b, c]`, `os.PathLike` by its
/// path. Errors (ParamError): any other type.
pub fn to_text(value: &Bound<'_, PyAny>, what: &str) -> PyResult<String> {
    if let Ok(s) = value.cast::<PyString>() {
        return Ok(s.to_cow()?.into_owned());
    }
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(if b.is_true() { "true" } else { "false" }.into());
    }
    if value.is_instance_of::<PyTuple>() || value.is_instance_of::<PyList>() {
        let mut parts = Vec::new();
        for item in value.try_iter()? {
            parts.push(number_text(&item?, what)?);
        }
        return Ok(format!("[{}]", parts.join(", ")));
    }
    if value.hasattr("__fspath__")? {
        return value.call_method0("__fspath__")?.extract::<String>();
    }
    number_text(value, what)
}

fn number_text(value: &Bound<'_, PyAny>, what: &str) -> PyResult<String> {
    // numpy scalars and other numbers convert through __index__ / __float__.
    if let Ok(i) = value.extract::<i64>() {
        return Ok(i.to_string());
    }
    if let Ok(f) = value.extract::<f64>() {
        return Ok(value_repr(f));
    }
    let ty = value.get_type().name()?.to_string();
    Err(ParamError::new_err(format!(
        "{what}: cannot take a {ty} (give a number, bool, str, or a tuple of numbers)"
    )))
}

/// Shortest text that reads back as the same f64 (Rust's `{:?}` of f64 is round-trip exact).
fn value_repr(f: f64) -> String {
    format!("{f:?}")
}
