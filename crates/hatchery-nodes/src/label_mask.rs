//! `LabelMask`: one or more objects of a label volume (a hard segmentation) as a smooth 0–1
//! field, ready for marching cubes at iso 0.5.

use crate::value::Volume;
use crate::{Ctx, Value};
use hatchery_data::labels;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// The parameters of `LabelMask`.
    pub struct LabelMaskParams {
        /// labels to select: "3", "3, 7", "1-29", "2-4, 9"
        pub labels: String = "1";
        /// Gaussian sigma in voxels (0 = hard mask)
        pub smooth: f32 = 1.0, range(0.0, 8.0);
    }
}

pub struct LabelMaskNode;

impl Node<Value, Ctx> for LabelMaskNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "LabelMask",
            category: "Geometry",
            doc: "1 where a voxel's label is in `labels`, else 0, then blurred by a Gaussian of \
                  `smooth` voxels so that MarchingCubes at iso 0.5 gives a smooth surface instead \
                  of voxel stairs. The labels come from `objects` (a segmented volume: LabelFile, \
                  LabelsFromThreshold, …) or, as in graphs made before labels had their own type, \
                  from `volume` (values rounded to integers); connect one of the two. Labels not \
                  present are an error that lists the labels the volume has.",
            inputs: vec![
                PortSpec::optional(
                    "objects",
                    PortType::Labels,
                    "a segmented volume (e.g. LabelFile of the frog)",
                ),
                PortSpec::optional(
                    "volume",
                    PortType::Volume,
                    "or a label volume read as numbers",
                ),
            ],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Volume,
                "the selected objects, values in [0, 1]",
            )],
            params: LabelMaskParams::specs(),
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
        let params = LabelMaskParams::read(p)?;
        let from_labels;
        let mut names = std::collections::BTreeMap::new();
        let data = match (inputs.get("objects"), inputs.get("volume")) {
            (Some(objects), None) => {
                let l = &objects.labels("objects")?.data;
                names = l.objects.clone();
                from_labels = hatchery_data::VolumeData::from_voxels(
                    l.dims,
                    l.geometry,
                    hatchery_data::voxels::Voxels::U16(l.ids.clone()),
                )
                .map_err(|e| NodeError::at_port("objects", e.to_string()))?;
                &from_labels
            }
            (None, Some(volume)) => &*volume.volume("volume")?.data,
            (Some(_), Some(_)) => {
                return Err(NodeError::new(
                    "both `objects` and `volume` are connected: connect one",
                ));
            }
            (None, None) => {
                return Err(NodeError::new(
                    "connect a segmented volume to `objects` (or a label volume to `volume`)",
                ));
            }
        };
        // Objects may be named where the labels name them ("liver, 13").
        let text = hatchery_data::segmentation::ids_for_names(&params.labels, ',', None, &names)
            .map_err(|e| NodeError::new(format!("parameter `labels`: {e}")))?;
        let wanted = labels::parse_label_list(&text)
            .map_err(|e| NodeError::new(format!("parameter `labels`: {e}")))?;
        let counts = labels::label_counts(data);
        if !wanted.iter().any(|l| counts.contains_key(l)) {
            let present: Vec<String> = counts.keys().map(|l| l.to_string()).collect();
            return Err(NodeError::new(format!(
                "none of the labels {:?} occurs in the volume (it has labels {})",
                wanted,
                present.join(", ")
            )));
        }
        let mask = labels::label_mask(data, &wanted, params.smooth)
            .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Volume(Arc::new(Volume::new(mask)))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(LabelMaskNode);
}
