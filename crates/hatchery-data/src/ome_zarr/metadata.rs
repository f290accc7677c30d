//! The OME-NGFF metadata of a multiscale image: axes, units and coordinate transformations.

use std::path::Path;

use serde_json::{Map, Value};

use super::Axis;
use crate::DataError;

/// Millimetres per unit, for the spatial units of OME-NGFF (UDUNITS-2 names) and their common
/// abbreviations.
pub(super) fn unit_mm(unit: &str) -> Option<f64> {
    Some(match unit.trim().to_ascii_lowercase().as_str() {
        "angstrom" | "å" => 1e-7,
        "picometer" | "pm" => 1e-9,
        "nanometer" | "nm" => 1e-6,
        "micrometer" | "micron" | "um" | "µm" | "μm" => 1e-3,
        "millimeter" | "mm" => 1.0,
        "centimeter" | "cm" => 10.0,
        "decimeter" | "dm" => 100.0,
        "meter" | "m" => 1000.0,
        "inch" | "in" => 25.4,
        "foot" | "ft" => 304.8,
        _ => return None,
    })
}

/// The OME metadata of a group's attributes: 0.5 nests it under `ome`.
pub(super) fn ome_attributes(attributes: &Map<String, Value>) -> &Map<String, Value> {
    match attributes.get("ome") {
        Some(Value::Object(ome)) => ome,
        _ => attributes,
    }
}

/// Reads the axes: objects (0.4+), names (0.3) or none (0.1/0.2: `t, c, z, y, x`).
pub(super) fn parse_axes(
    path: &Path,
    ms: &Map<String, Value>,
    rank: usize,
) -> Result<Vec<Axis>, DataError> {
    let axis = |name: &str, kind: &str| Axis {
        name: name.into(),
        kind: kind.into(),
        unit: None,
    };
    let Some(list) = ms.get("axes") else {
        let all = ["t", "c", "z", "y", "x"];
        if rank > all.len() {
            return Err(DataError::format(
                path,
                format!("{rank}-D arrays without `axes`"),
            ));
        }
        return Ok(all[all.len() - rank..]
            .iter()
            .map(|&n| axis(n, if "zyx".contains(n) { "space" } else { "" }))
            .collect());
    };
    let Value::Array(list) = list else {
        return Err(DataError::format(path, "multiscales `axes` is not a list"));
    };
    list.iter()
        .map(|a| match a {
            Value::String(name) => Ok(axis(
                name,
                if ["x", "y", "z"].contains(&name.as_str()) {
                    "space"
                } else {
                    ""
                },
            )),
            Value::Object(o) => Ok(Axis {
                name: o.get("name").and_then(Value::as_str).unwrap_or("").into(),
                kind: o.get("type").and_then(Value::as_str).unwrap_or("").into(),
                unit: o.get("unit").and_then(Value::as_str).map(str::to_owned),
            }),
            other => Err(DataError::format(path, format!("malformed axis {other}"))),
        })
        .collect()
}

/// Composes a list of `coordinateTransformations` into per-axis scale and translation.
pub(super) fn compose(
    path: &Path,
    transforms: Option<&Value>,
    scale: &mut [f64],
    shift: &mut [f64],
) -> Result<(), DataError> {
    let Some(transforms) = transforms else {
        return Ok(());
    };
    let list = transforms
        .as_array()
        .ok_or_else(|| DataError::format(path, "`coordinateTransformations` is not a list"))?;
    let rank = scale.len();
    let numbers = |t: &Map<String, Value>, key: &str| -> Result<Vec<f64>, DataError> {
        if t.contains_key("path") {
            return Err(DataError::unsupported(
                path,
                format!("a {key} stored in a separate file (`path`) is not read"),
            ));
        }
        let v: Option<Vec<f64>> = t
            .get(key)
            .and_then(Value::as_array)
            .map(|a| a.iter().map(Value::as_f64).collect::<Option<_>>())
            .unwrap_or(None);
        match v {
            Some(v) if v.len() == rank && v.iter().all(|x| x.is_finite()) => Ok(v),
            _ => Err(DataError::format(
                path,
                format!("`{key}` must hold {rank} finite numbers (one per axis)"),
            )),
        }
    };
    for t in list {
        let t = t.as_object().ok_or_else(|| {
            DataError::format(path, "a coordinate transformation is not an object")
        })?;
        match t.get("type").and_then(Value::as_str) {
            Some("scale") => {
                for (a, s) in numbers(t, "scale")?.into_iter().enumerate() {
                    scale[a] *= s;
                    shift[a] *= s;
                }
            }
            Some("translation") => {
                for (a, d) in numbers(t, "translation")?.into_iter().enumerate() {
                    shift[a] += d;
                }
            }
            Some("identity") => {}
            other => {
                return Err(DataError::unsupported(
                    path,
                    format!(
                        "coordinate transformation {other:?} (hatchery reads scale and translation)"
                    ),
                ));
            }
        }
    }
    Ok(())
}

pub(super) fn dataset_path(path: &Path, dataset: &Value) -> Result<String, DataError> {
    dataset
        .get("path")
        .and_then(Value::as_str)
        .filter(|p| !p.is_empty() && !p.split('/').any(|c| c == ".."))
        .map(|p| p.trim_matches('/').to_owned())
        .ok_or_else(|| DataError::format(path, "a multiscales dataset without a usable `path`"))
}
