//! `PaintLabels`: a selection painted onto the data with a 3-D brush (the tutorial's VolumeShop
//! §6.1, "intuitive feature classification via 3D painting"). The brush dabs are the node's
//! `strokes` parameter, so the painting is saved in the graph file, undone with the editor's undo
//! and read by any node that takes labels (SelectionRender, ImportanceCompositing,
//! TwoLevelRaycast). In the editor, the viewport's paint tool adds dabs where the pointer meets
//! the first visible surface (docs/painting.md).

use crate::label_sources::{finish, labels_output};
use crate::{Ctx, Value};
use hatchery_data::paint;
use hatchery_data::segmentation::LabelData;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

hatchery_graph::node_params! {
    /// Parameters of `PaintLabels`.
    pub struct PaintLabelsParams {
        /// the brush dabs, in order: "x y z r id; …" — a ball of radius r (world units, mm)
        /// around (x, y, z) filled with object id (0 erases); the editor's paint tool writes them
        pub strokes: String = "";
        /// the radius (world units, mm) of the dabs the editor's paint tool adds
        pub radius: f32 = 4.0, range(0.1, 500.0);
        /// the object id the editor's paint tool paints (0: the tool erases)
        pub id: u32 = 1, range(0, 65535);
        /// the name of painted objects the labels do not name yet
        pub name: String = "selection";
    }
}

pub struct PaintLabelsNode;

impl Node<Value, Ctx> for PaintLabelsNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "PaintLabels",
            category: "Data",
            doc: "Volume painting (VolumeShop §6.1): object ids painted onto a volume's grid with \
                  a spherical brush — every voxel whose centre lies within a dab's radius (world \
                  units) gets its id, in the order of the dabs — on top of `labels` where \
                  connected, else on an empty map of `volume`'s grid. In the editor, select the \
                  node and turn on the viewport's paint tool: a drag paints where the pointer \
                  meets the first visible surface.",
            inputs: vec![
                PortSpec::optional(
                    "volume",
                    PortType::Volume,
                    "the grid to paint on when no labels are connected",
                ),
                PortSpec::optional(
                    "labels",
                    PortType::Labels,
                    "a segmentation to paint over (its grid is used)",
                ),
            ],
            outputs: vec![labels_output()],
            params: PaintLabelsParams::specs(),
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
        let params = PaintLabelsParams::read(p)?;
        let dabs = paint::parse_dabs(&params.strokes)
            .map_err(|e| NodeError::new(format!("parameter `strokes`: {e}")))?;
        let mut labels: LabelData = match (inputs.get("labels"), inputs.get("volume")) {
            (Some(labels), _) => labels.labels("labels")?.data.as_ref().clone(),
            (None, Some(volume)) => {
                let v = &volume.volume("volume")?.data;
                LabelData::new(v.dims, v.geometry, vec![0; v.voxel_count()])
            }
            (None, None) => {
                return Err(NodeError::at_port(
                    "volume",
                    "connect a volume (the grid to paint on) or labels (to paint over)",
                ));
            }
        };
        paint::paint(&mut labels, &dabs, &params.name)
            .map_err(|e| NodeError::new(e.to_string()))?;
        finish(ctx, "PaintLabels", labels)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(PaintLabelsNode);
}
