//! `LabelsFromThreshold`: object ids from intervals of a volume's values.

use crate::label_sources::finish;
use crate::label_sources::labels_output;
use crate::label_sources::parse_intervals;
use crate::{Ctx, Value};
use hatchery_data::segmentation::{self};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType,
    executor::Node,
};

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

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(LabelsFromThresholdNode);
}
