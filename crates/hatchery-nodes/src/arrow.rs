//! `Arrow`: an arrow from the ghost to the selection (VolumeShop §6.3's visual conventions). The geometry is in [`crate::visual_conventions`] (shared with SaveSvg).

use crate::overlay::{Canvas, pixels};
use crate::visual_conventions::{draw, inputs_of, output, ports, arrow_shape};
use crate::{Ctx, Value};
use hatchery_graph::{NodeError, NodeInputs, NodeSchema, Params, executor::Node};

hatchery_graph::node_params! {
    /// Parameters of `Arrow`.
    pub struct ArrowParams {
        /// colour of the arrow's shaft and head
        pub color: [f32; 4] = [0.8, 0.1, 0.1, 1.0];
        /// shaft width, pixels
        pub width: f32 = 2.0, range(0.1, 32.0), unit(pixels);
        /// greatest distance from the chord per pixel of depth difference
        pub curvature: f32 = 0.5, range(0.0, 4.0);
    }
}

pub struct ArrowNode;

impl Node<Value, Ctx> for ArrowNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Arrow",
            category: "Annotation",
            doc: "A curved arrow from the ghost (anchor 0) to the selection (anchor 1), VolumeShop \
                  §6.3 \"Arrows\": the head at the selection. The screen-space depth difference \
                  bends it, so ghost and selection that project close together still get a \
                  readable arrow: the selection's view-space depth minus the ghost's (world \
                  units, positive = nearer the viewer) times the pixels per world unit at their \
                  midpoint gives Δ pixels; the curve's greatest distance from the straight chord \
                  is curvature × Δ, to the left of the direction of travel on screen when the \
                  selection moved towards the viewer, to the right when away. Equal depths: a \
                  straight arrow.",
            inputs: ports("anchor 0 = ghost, anchor 1 = selection (world positions)"),
            outputs: output(),
            params: ArrowParams::specs(),
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
        let params = ArrowParams::read(p)?;
        let (image, annotations, camera) = inputs_of(inputs)?;
        let width = pixels("width", params.width)?;
        let curvature = pixels("curvature", params.curvature)?;
        let color = params.color;
        let (w, h) = (image.texture.width(), image.texture.height());
        let mut canvas = Canvas::new(w, h);
        let Some((shaft, head)) = arrow_shape(&annotations, &camera, (w, h), width, curvature)?
        else {
            ctx.warn("the ghost or the selection is behind the camera: no arrow");
            return draw(ctx, canvas, &image);
        };
        canvas.polyline(&shaft, width, color);
        canvas.triangle(head, color);
        draw(ctx, canvas, &image)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(ArrowNode);
}
