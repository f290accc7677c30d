//! `hatchery.nodes()`: the node catalogue (what `hatchery nodes` prints) as Python data.

use hatchery_graph::{NodeSchema, ParamKind, ParamSpec, PortSpec};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// Every node kind: a list of dicts `{kind, category, doc, inputs, outputs, params,
/// frame_dependent, sink}`; ports are `{name, type, required, doc}`, parameters `{name, kind,
/// default, doc, min, max, choices, relative, reads}` (min/max for numbers, choices for choice
/// parameters, else None; `reads` names the graph-input kind a path parameter reads).
#[pyfunction]
pub fn nodes(py: Python<'_>) -> PyResult<Bound<'_, PyList>> {
    let registry = hatchery_nodes::registry();
    let mut schemas: Vec<&NodeSchema> = registry.schemas().collect();
    schemas.sort_by_key(|s| (s.category, s.kind));
    let list = PyList::empty(py);
    for schema in schemas {
        list.append(schema_dict(py, schema)?)?;
    }
    Ok(list)
}

pub fn schema_dict<'py>(py: Python<'py>, schema: &NodeSchema) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", schema.kind)?;
    d.set_item("category", schema.category)?;
    d.set_item("doc", schema.doc)?;
    let ports = |specs: &[PortSpec]| -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for p in specs {
            let port = PyDict::new(py);
            port.set_item("name", p.name)?;
            port.set_item("type", p.ty.to_string())?;
            port.set_item("required", p.required)?;
            port.set_item("doc", p.doc)?;
            list.append(port)?;
        }
        Ok(list)
    };
    d.set_item("inputs", ports(&schema.inputs)?)?;
    d.set_item("outputs", ports(&schema.outputs)?)?;
    let params = PyList::empty(py);
    for p in &schema.params {
        params.append(param_dict(py, p)?)?;
    }
    d.set_item("params", params)?;
    d.set_item("frame_dependent", schema.frame_dependent)?;
    d.set_item("sink", schema.sink)?;
    Ok(d)
}

fn param_dict<'py>(py: Python<'py>, p: &ParamSpec) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", p.name)?;
    let (kind, min, max, choices): (&str, Option<f64>, Option<f64>, Option<Vec<&str>>) =
        match &p.kind {
            ParamKind::Float { min, max } => ("float", Some(*min), Some(*max), None),
            ParamKind::Int { min, max } => ("int", Some(*min as f64), Some(*max as f64), None),
            ParamKind::Bool => ("bool", None, None, None),
            ParamKind::Choice(names) => ("choice", None, None, Some(names.to_vec())),
            ParamKind::Color => ("color", None, None, None),
            ParamKind::Vec3 => ("vec3", None, None, None),
            ParamKind::Path => ("path", None, None, None),
            ParamKind::Text => ("text", None, None, None),
        };
    d.set_item("kind", kind)?;
    d.set_item("default", crate::params::to_python(py, &p.default)?)?;
    d.set_item("doc", p.doc)?;
    if let ParamKind::Int { min, max } = &p.kind {
        d.set_item("min", *min)?;
        d.set_item("max", *max)?;
    } else {
        d.set_item("min", min)?;
        d.set_item("max", max)?;
    }
    d.set_item("choices", choices)?;
    d.set_item("relative", p.relative)?;
    d.set_item("reads", p.reads.map(|k| k.to_string()))?;
    Ok(d)
}
