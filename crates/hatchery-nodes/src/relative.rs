//! Data values given relative to a node's volume (issue 25): a percentile of its finite
//! values, a fraction of its range, or Otsu's threshold, resolved when the node runs. The
//! resolved number is recorded on the context so the editor can show it next to the parameter.

use crate::Ctx;
use hatchery_data::{VolumeData, value_stats};
use hatchery_graph::{DataValue, NodeError, ParamError, RelativeValue};

/// Resolves `r` against `volume`'s values. Errors: a volume with no finite value, or a constant
/// one for Otsu (there are no two classes to separate).
pub fn resolve(r: RelativeValue, volume: &VolumeData) -> Result<f32, ParamError> {
    match r {
        RelativeValue::Percentile(p) => value_stats::percentile(volume, p)
            .ok_or_else(|| ParamError(format!("{r}: the volume holds no finite value"))),
        RelativeValue::Range(f) if volume.has_finite_values() => {
            Ok(value_stats::range_fraction(volume, f))
        }
        RelativeValue::Range(_) => Err(format!("{r}: the volume holds no finite value").into()),
        RelativeValue::Otsu => value_stats::otsu(volume).ok_or_else(|| {
            let [lo, hi] = volume.value_range;
            ParamError(format!(
                "otsu: the volume's values do not form two classes (range [{lo}, {hi}])"
            ))
        }),
    }
}

/// The number of data-value parameter `name` (see [`hatchery_graph::ParamSpec::relative`])
/// whose value is `value`, resolved against `volume` when it is given relatively (and recorded
/// on `ctx`).
pub fn data_value(
    ctx: &mut Ctx,
    name: &str,
    value: DataValue,
    volume: &VolumeData,
) -> Result<f32, NodeError> {
    match value {
        DataValue::Number(v) => Ok(v as f32),
        DataValue::Relative(r) => {
            let v = resolve(r, volume)
                .map_err(|e| NodeError::new(format!("parameter `{name}`: {e}")))?;
            tracing::info!("{name} = {r} = {v}");
            ctx.note_resolved(name, format!("{r} = {v}"));
            Ok(v)
        }
    }
}

/// One number inside a text parameter ("80..140: 1", "percentile(5): 0 0 0 0"): a plain number,
/// or a relative value resolved against `volume` (an error without one).
pub fn number_in_text(text: &str, volume: Option<&VolumeData>) -> Result<f32, ParamError> {
    let text = text.trim();
    if let Ok(v) = text.parse::<f32>() {
        return Ok(v);
    }
    let r = RelativeValue::parse(text).map_err(|_| format!("`{text}` is not a number"))?;
    match volume {
        Some(volume) => resolve(r, volume),
        None => Err(format!("`{text}` is relative to the data: connect a volume").into()),
    }
}

/// Control points "value: …; value: …" with each value that is relative to the data replaced by
/// its number (the rest of each entry is kept as written).
pub fn resolve_point_values(text: &str, volume: Option<&VolumeData>) -> Result<String, ParamError> {
    let mut out = Vec::new();
    for (n, entry) in text.split(';').enumerate() {
        match entry.split_once(':') {
            Some((value, rest)) if value.trim().parse::<f32>().is_err() => {
                let v =
                    number_in_text(value, volume).map_err(|e| format!("point {}: {e}", n + 1))?;
                out.push(format!("{v}:{rest}"));
            }
            _ => out.push(entry.to_owned()),
        }
    }
    Ok(out.join(";"))
}
