//! `DistanceToObject`: the Euclidean distance of every voxel to chosen objects of a label map,
//! as a volume — the field behind colouring structures by their distance to a risk structure
//! (the tutorial's Preim/Tietjen neck dissection planning, §4.3: a discrete colour scale at 2 and
//! 5 mm). Drawn by giving it to `TwoLevelRaycast` as its `volume`, with transfer functions over
//! millimetres (docs/distance.md).

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::distance;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `DistanceToObject`.
    pub struct DistanceToObjectParams {
        /// the objects distances are measured to: ids or names of the labels, separated by commas
        /// (e.g. "liver" or "10, 14")
        pub objects: String = "1";
        /// negative inside the objects (minus the distance to the nearest voxel outside them)
        /// instead of 0 there
        pub signed: bool = false;
    }
}

pub struct DistanceToObjectNode;

impl Node<Value, Ctx> for DistanceToObjectNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "DistanceToObject",
            category: "Data",
            doc: "Distance to a risk structure (Preim/Tietjen, neck dissection planning §4.3): per \
                  voxel of the label map, the Euclidean distance in world units (mm) from its \
                  centre to the nearest voxel centre of `objects` — exact, with each axis's \
                  spacing and the grid's placement in the world. Feed it to TwoLevelRaycast's \
                  `volume` with the same labels and give the structures a transfer function over \
                  millimetres (e.g. red to 2 mm, yellow to 5 mm) to colour them by their distance \
                  to the objects.",
            inputs: vec![PortSpec::input(
                "labels",
                PortType::Labels,
                "the segmentation (object ids and names)",
            )],
            outputs: vec![PortSpec::output(
                "volume",
                PortType::Volume,
                "distance in world units (mm) on the labels' grid",
            )],
            params: DistanceToObjectParams::specs(),
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
        let params = DistanceToObjectParams::read(p)?;
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        let ids = object_ids(&params.objects, &labels.data.objects)?;
        let measured = distance::distance_to(&labels.data, &ids, params.signed)
            .map_err(|e| NodeError::at_port("labels", e.to_string()))?;
        if let Some(warning) = measured.warning {
            ctx.warn(warning);
        }
        Ok(vec![Value::Volume(Arc::new(Volume::new(measured.volume)))])
    }
}

/// The ids of "10, liver, 14" (names matched as the labels name their objects).
fn object_ids(
    text: &str,
    names: &std::collections::BTreeMap<u16, String>,
) -> Result<Vec<u16>, NodeError> {
    let bad = |e: String| NodeError::new(format!("parameter `objects`: {e}"));
    let text = hatchery_data::segmentation::ids_for_names(text, ',', None, names)
        .map_err(|e| bad(e.to_string()))?;
    let mut ids = Vec::new();
    for word in text.split(',').map(str::trim).filter(|w| !w.is_empty()) {
        let id: u16 = word
            .parse()
            .ok()
            .filter(|&id| id > 0)
            .ok_or_else(|| bad(format!("`{word}` is not an object id (1–65535) or name")))?;
        ids.push(id);
    }
    if ids.is_empty() {
        return Err(bad("no object given".into()));
    }
    Ok(ids)
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(DistanceToObjectNode);
}
