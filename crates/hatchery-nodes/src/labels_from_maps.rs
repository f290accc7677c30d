//! `LabelsFromMaps`: object ids from probability maps on one grid.

use crate::label_sources::finish;
use crate::label_sources::labels_output;
use crate::{Ctx, Value};
use hatchery_data::segmentation::{self};
use hatchery_graph::{
    DataValue, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType,
    executor::Node,
};

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
    k.node(LabelsFromMapsNode);
}
