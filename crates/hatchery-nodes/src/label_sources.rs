//! The sources of `Labels` (segmented volumes, Hadwiger §2.1): `LabelFile` (a label map in any
//! volume format, names from a side table), `LabelsFromThreshold` (value intervals → ids) and
//! `LabelsFromMaps` (probability maps → ids by arg-max).

use crate::memory_inputs::{self, InputData};
use crate::value::Labels;
use crate::{Ctx, Value};
use hatchery_data::segmentation::{self, LabelData};
use hatchery_graph::{
    DataValue, FilePath, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType,
    executor::Node,
};
use std::collections::BTreeMap;
use std::sync::Arc;

fn labels_output() -> PortSpec {
    PortSpec::output(
        "labels",
        PortType::Labels,
        "object ids on the volume's grid, with names",
    )
}

fn finish(ctx: &mut Ctx, what: &str, data: LabelData) -> Result<Vec<Value>, NodeError> {
    finish_shared(ctx, what, Arc::new(data))
}

fn finish_shared(ctx: &mut Ctx, what: &str, data: Arc<LabelData>) -> Result<Vec<Value>, NodeError> {
    if data.objects.is_empty() {
        ctx.warn(format!(
            "{what}: no object (every voxel is background, id 0)"
        ));
    }
    tracing::info!(what, objects = data.objects.len(), "labels");
    Ok(vec![Value::Labels(Arc::new(Labels::shared(data)))])
}

hatchery_graph::node_params! {
    /// Parameters of `LabelFile`.
    pub struct LabelFileParams {
        /// the label map file, or a DICOM folder
        pub path: FilePath = "", reads(hatchery_graph::InputKind::Labels);
        /// the named data array to read (VTK); empty: the active scalars
        pub array: String = "";
        /// object names: CSV `id,name` or ITK-SNAP label file (optional)
        pub names: FilePath = "", reads(hatchery_graph::InputKind::Names);
    }
}

pub struct LabelFileNode;

impl Node<Value, Ctx> for LabelFileNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelFile",
            category: "Data",
            doc: "Reads a label map (object id per voxel, whole numbers 0–65535, 0 = background) \
                  from any volume format VolumeFile reads, placed in the world the same way. \
                  Object names come from `names` (a CSV/TSV table `id,name` or an ITK-SNAP label \
                  description file) or from the file itself (3D Slicer's segment names in a \
                  .seg.nrrd header); objects without a name are called \"object N\".",
            inputs: vec![],
            outputs: vec![labels_output()],
            params: LabelFileParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = LabelFileParams::read(p)?;
        let key = params.path.written.as_str();
        if memory_inputs::is_memory_key(key) {
            let mut data = match ctx.memory(key) {
                Some(InputData::Labels(l)) => l.clone(),
                Some(other) => return Err(memory_inputs::wrong_kind(key, "label map", other)),
                None => return Err(memory_inputs::missing(key)),
            };
            // Names given with the array win over a names table (which names the rest).
            let table = names_table(ctx, &params.names)?;
            if !table.is_empty() {
                let given = data.objects.clone();
                let labels = Arc::make_mut(&mut data);
                labels.name_objects(&table);
                labels.name_objects(&given_names(&given));
            }
            return finish_shared(ctx, "labels in memory", data);
        }
        let path = params.path.resolved.clone();
        if path.as_os_str().is_empty() {
            return Err(NodeError::new(
                "parameter `path` is empty: name a label map (.nii.gz, .vti, .nrrd, ...)",
            ));
        }
        let array = params.array.trim();
        let options = hatchery_data::volume_file::LoadOptions {
            array: (!array.is_empty()).then(|| array.to_owned()),
        };
        let volume = hatchery_data::volume_file::load_volume_with(&path, &options)
            .map_err(|e| NodeError::new(e.to_string()))?;
        if !volume.warnings.is_empty() {
            ctx.warn(format!(
                "{}: {}",
                path.display(),
                volume.warnings.join("; ")
            ));
        }
        let mut data = LabelData::from_volume(&volume)
            .map_err(|e| NodeError::new(format!("{}: {e}", path.display())))?;
        // 3D Slicer writes segment names into the NRRD header.
        let extension = path.to_string_lossy().to_ascii_lowercase();
        if extension.ends_with(".nrrd") || extension.ends_with(".nhdr") {
            let table = segmentation::nrrd_segment_names(&path)
                .map_err(|e| NodeError::new(e.to_string()))?;
            data.name_objects(&table);
        }
        data.name_objects(&names_table(ctx, &params.names)?);
        finish(ctx, &path.display().to_string(), data)
    }
}

/// The `names` table: from its file, or from memory (a `memory:` key); empty when not set.
fn names_table(ctx: &Ctx, names: &FilePath) -> Result<BTreeMap<u16, String>, NodeError> {
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
fn given_names(objects: &BTreeMap<u16, String>) -> BTreeMap<u16, String> {
    objects
        .iter()
        .filter(|(id, name)| **name != format!("object {id}"))
        .map(|(id, name)| (*id, name.clone()))
        .collect()
}

/// Parses "lo..hi: id; …" (intervals [lo, hi) in data units; a bound may be relative to
/// `volume`'s values, e.g. "otsu..percentile(99): 1").
pub fn parse_intervals(
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

hatchery_graph::node_params! {
    /// Parameters of `LabelsFromThreshold`.
    pub struct LabelsFromThresholdParams {
        /// "lo..hi: id; …" in data units; bounds may be "percentile(P)", "range(F)" or "otsu" of
        /// the volume
        pub intervals: String = "80..140: 1; 140..256: 2";
    }
}

pub struct LabelsFromThresholdNode;

impl Node<Value, Ctx> for LabelsFromThresholdNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelsFromThreshold",
            category: "Data",
            doc: "Object ids by value intervals: a voxel whose value lies in [lo, hi) of an \
                  interval gets its id (the first matching interval wins), others background.",
            inputs: vec![PortSpec::input(
                "volume",
                PortType::Volume,
                "the scalar field",
            )],
            outputs: vec![labels_output()],
            params: LabelsFromThresholdParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = LabelsFromThresholdParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let intervals = parse_intervals(&params.intervals, Some(&volume.data))
            .map_err(|e| NodeError::new(format!("parameter `intervals`: {e}")))?;
        finish(
            ctx,
            "LabelsFromThreshold",
            segmentation::threshold(&volume.data, &intervals),
        )
    }
}

hatchery_graph::node_params! {
    /// Parameters of `LabelsFromMaps`.
    pub struct LabelsFromMapsParams {
        /// smallest value that makes a voxel part of an object (data units of map a, or
        /// "percentile(P)", "range(F)", "otsu" of map a)
        pub floor: DataValue = 128.0, range(-1e12, 1e12);
        /// object names, "a name, b name, …" (optional)
        pub names: String = "";
    }
}

pub struct LabelsFromMapsNode;

impl Node<Value, Ctx> for LabelsFromMapsNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelsFromMaps",
            category: "Data",
            doc: "Object ids from probability maps on one grid (e.g. the MRI's grey- and \
                  white-matter maps): each voxel gets the id of the map with the largest value \
                  (a = 1, b = 2, c = 3) if that value is at least `floor`, else background.",
            inputs: vec![
                PortSpec::input("a", PortType::Volume, "map of object 1"),
                PortSpec::optional("b", PortType::Volume, "map of object 2"),
                PortSpec::optional("c", PortType::Volume, "map of object 3"),
            ],
            outputs: vec![labels_output()],
            params: LabelsFromMapsParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = LabelsFromMapsParams::read(p)?;
        let mut maps = vec![inputs.require("a")?.volume("a")?.clone()];
        for port in ["b", "c"] {
            if let Some(v) = inputs.get(port) {
                maps.push(v.volume(port)?.clone());
            }
        }
        let data: Vec<&hatchery_data::VolumeData> = maps.iter().map(|m| &*m.data).collect();
        let floor = crate::relative::data_value(ctx, "floor", params.floor, data[0])?;
        let mut labels =
            segmentation::from_maps(&data, floor).map_err(|e| NodeError::new(e.to_string()))?;
        let names: std::collections::BTreeMap<u16, String> = params
            .names
            .split(',')
            .map(str::trim)
            .enumerate()
            .filter(|(_, n)| !n.is_empty())
            .map(|(k, n)| (k as u16 + 1, n.to_string()))
            .collect();
        labels.name_objects(&names);
        finish(ctx, "LabelsFromMaps", labels)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(LabelFileNode)
        .node(LabelsFromThresholdNode)
        .node(LabelsFromMapsNode);
}
