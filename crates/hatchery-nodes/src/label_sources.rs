//! What the sources of `Labels` (segmented volumes, Hadwiger §2.1) share: the output port, the
//! finishing checks and the object-name tables. The kinds: `LabelFile` (label_file.rs),
//! `LabelsFromThreshold` (labels_from_threshold.rs), `LabelsFromMaps` (labels_from_maps.rs).

use crate::memory_inputs::{self, InputData};
use crate::value::Labels;
use crate::{Ctx, Value};
use hatchery_data::segmentation::{self, LabelData};
use hatchery_graph::{FilePath, NodeError, PortSpec, PortType};
use std::collections::BTreeMap;
use std::sync::Arc;

pub(crate) fn labels_output() -> PortSpec {
    PortSpec::output(
        "labels",
        PortType::Labels,
        "object ids on the volume's grid, with names",
    )
}

pub(crate) fn finish(ctx: &mut Ctx, what: &str, data: LabelData) -> Result<Vec<Value>, NodeError> {
    finish_shared(ctx, what, Arc::new(data))
}

pub(crate) fn finish_shared(
    ctx: &mut Ctx,
    what: &str,
    data: Arc<LabelData>,
) -> Result<Vec<Value>, NodeError> {
    if data.objects.is_empty() {
        ctx.warn(format!(
            "{what}: no object (every voxel is background, id 0)"
        ));
    }
    tracing::info!(what, objects = data.objects.len(), "labels");
    Ok(vec![Value::Labels(Arc::new(Labels::shared(data)))])
}

/// The `names` table: from its file, or from memory (a `memory:` key); empty when not set.
pub(crate) fn names_table(ctx: &Ctx, names: &FilePath) -> Result<BTreeMap<u16, String>, NodeError> {
    let key = names.written.as_str();
    if memory_inputs::is_memory_key(key) {
        return match ctx.memory(key) {
            Some(InputData::Names(n)) => Ok(n.as_ref().clone()),
            Some(other) => Err(memory_inputs::wrong_kind(key, "names table", other)),
            None => Err(memory_inputs::missing(key)),
        };
    }
    if names.resolved.as_os_str().is_empty() {
        return Ok(BTreeMap::new());
    }
    segmentation::read_names(&names.resolved).map_err(|e| NodeError::new(e.to_string()))
}

/// The names an in-memory label map was given (not the "object N" placeholders).
pub(crate) fn given_names(objects: &BTreeMap<u16, String>) -> BTreeMap<u16, String> {
    objects
        .iter()
        .filter(|(id, name)| **name != format!("object {id}"))
        .map(|(id, name)| (*id, name.clone()))
        .collect()
}

/// Parses "lo..hi: id; …" (intervals [lo, hi) in data units; a bound may be relative to
/// `volume`'s values, e.g. "otsu..percentile(99): 1").
pub(crate) fn parse_intervals(
    text: &str,
    volume: Option<&hatchery_data::VolumeData>,
) -> Result<Vec<(f32, f32, u16)>, String> {
    let mut intervals = Vec::new();
    for (n, part) in text.split(';').map(str::trim).enumerate() {
        if part.is_empty() {
            continue;
        }
        let bad = || format!("interval {} `{part}`: expected `lo..hi: id`", n + 1);
        let (range, id) = part.split_once(':').ok_or_else(bad)?;
        let (lo, hi) = range.split_once("..").ok_or_else(bad)?;
        let number = |t: &str| {
            crate::relative::number_in_text(t, volume)
                .map_err(|e| format!("interval {} `{part}`: {e}", n + 1))
        };
        let (lo, hi) = (number(lo)?, number(hi)?);
        let id: u16 = id.trim().parse().map_err(|_| bad())?;
        if lo >= hi || lo.is_nan() || hi.is_nan() || id == 0 {
            return Err(format!(
                "interval {} `{part}`: needs lo < hi and an id from 1 to 65535",
                n + 1
            ));
        }
        intervals.push((lo, hi, id));
    }
    if intervals.is_empty() {
        return Err("no interval given: write `lo..hi: id; …`".into());
    }
    Ok(intervals)
}
