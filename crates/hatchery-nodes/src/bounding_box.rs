//! `BoundingBox`: the world boxes of the ghost and/or the selection (VolumeShop §6.3). The geometry is in [`crate::visual_conventions`] (shared with SaveSvg).

use crate::overlay::{Canvas, pixels};
use crate::visual_conventions::{draw, inputs_of, output, ports, box_edges};
use crate::{Ctx, Value};
use hatchery_graph::{NodeError, NodeInputs, NodeSchema, Params, executor::Node};

hatchery_graph::param_choice! {
    /// Whose box to draw.
    pub enum Which { Ghost = "ghost", Selection = "selection", Both = "both" }
}

hatchery_graph::node_params! {
    /// Parameters of `BoundingBox`.
    pub struct BoundingBoxParams {
        /// whose box to draw
        pub which: Which = Which::Selection;
        /// colour of the box's edges
        pub color: [f32; 4] = [0.1, 0.4, 0.9, 1.0];
        /// edge width, pixels
        pub width: f32 = 1.0, range(0.1, 32.0), unit(pixels);
    }
}

pub struct BoundingBoxNode;

impl Node<Value, Ctx> for BoundingBoxNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "BoundingBox",
            category: "Annotation",
            doc: "The 12 edges of the ghost's (anchor 0) and/or the selection's (anchor 1) world \
                  box projected with the camera, VolumeShop §6.3 \"Boxes\": cues on an object's \
                  position and orientation while arranging an illustration. Edges are clipped at \
                  the near plane; all edges are drawn (no occlusion).",
            inputs: ports("anchor 0 = ghost, anchor 1 = selection, with world boxes as bounds"),
            outputs: output(),
            params: BoundingBoxParams::specs(),
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
        let params = BoundingBoxParams::read(p)?;
        let (image, annotations, camera) = inputs_of(inputs)?;
        let which: &[usize] = match params.which {
            Which::Ghost => &[0],
            Which::Both => &[0, 1],
            Which::Selection => &[1],
        };
        let width = pixels("width", params.width)?;
        let color = params.color;
        let (w, h) = (image.texture.width(), image.texture.height());
        let mut canvas = Canvas::new(w, h);
        for [u, v] in box_edges(&annotations, &camera, (w, h), which)? {
            canvas.line(u, v, width, color);
        }
        draw(ctx, canvas, &image)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(BoundingBoxNode);
}
