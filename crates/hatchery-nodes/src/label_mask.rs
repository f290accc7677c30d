//! `LabelMask`: one or more objects of a label volume (a hard segmentation) as a smooth 0–1
//! field, ready for marching cubes at iso 0.5.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::labels;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct LabelMaskNode;

impl Node<Value, Ctx> for LabelMaskNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelMask",
            category: "Geometry",
            doc: "1 where a voxel's label (its value rounded to an integer) is in `labels`, else 0, then \
                  blurred by a Gaussian of `smooth` voxels so that MarchingCubes at iso 0.5 gives a \
                  smooth surface instead of voxel stairs. Labels not present are an error that lists \
                  the labels the volume has.",
            inputs: vec![PortSpec::input(
                "volume",
                PortType::Volume,
                "a label volume (e.g. the segmented frog)",
            )],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Volume,
                "the selected objects, values in [0, 1]",
            )],
            params: vec![
                ParamSpec::text(
                    "labels",
                    "1",
                    "labels to select: \"3\", \"3, 7\", \"1-29\", \"2-4, 9\"",
                ),
                ParamSpec::float(
                    "smooth",
                    1.0,
                    0.0,
                    8.0,
                    "Gaussian sigma in voxels (0 = hard mask)",
                ),
            ],
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        _ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let volume = inputs.require("volume")?.volume("volume")?;
        let wanted = labels::parse_label_list(p.text("labels"))
            .map_err(|e| NodeError::new(format!("parameter `labels`: {e}")))?;
        let counts = labels::label_counts(&volume.data);
        if !wanted.iter().any(|l| counts.contains_key(l)) {
            let present: Vec<String> = counts.keys().map(|l| l.to_string()).collect();
            return Err(NodeError::new(format!(
                "none of the labels {:?} occurs in the volume (it has labels {})",
                wanted,
                present.join(", ")
            )));
        }
        let mask = labels::label_mask(&volume.data, &wanted, p.f32("smooth"))
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Volume(Arc::new(Volume::new(mask)))])
    }
}
