//! `Fan`: the fan between the ghost's and the selection's screen rectangles (VolumeShop §6.3). The geometry is in [`crate::visual_conventions`] (shared with SaveSvg).

use crate::overlay::{Canvas, pixels};
use crate::visual_conventions::{draw, inputs_of, output, ports, fan_shape};
use crate::{Ctx, Value};
use hatchery_graph::{NodeError, NodeInputs, NodeSchema, Params, executor::Node};

hatchery_graph::node_params! {
    /// Parameters of `Fan`.
    pub struct FanParams {
        /// outline and line colour
        pub color: [f32; 4] = [0.2, 0.2, 0.2, 1.0];
        /// line width, pixels
        pub width: f32 = 1.5, range(0.1, 32.0), unit(pixels);
        /// colour between the rectangles (alpha 0: no fill)
        pub fill: [f32; 4] = [0.3, 0.3, 0.3, 0.15];
    }
}

pub struct FanNode;

impl Node<Value, Ctx> for FanNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Fan",
            category: "Annotation",
            doc: "A fan between ghost (anchor 0) and selection (anchor 1), VolumeShop §6.3 \
                  \"Fans\": the screen-space bounding rectangles of their world boxes (the \
                  projected 8 corners each), outlined, joined by the two outer common tangents \
                  (the edges of the convex hull of both rectangles' corners that go from one \
                  rectangle to the other; none when one rectangle contains the other), with a \
                  translucent fill between them that leaves both rectangles' insides clear.",
            inputs: ports("anchor 0 = ghost, anchor 1 = selection, with world boxes as bounds"),
            outputs: output(),
            params: FanParams::specs(),
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
        let params = FanParams::read(p)?;
        let (image, annotations, camera) = inputs_of(inputs)?;
        let width = pixels("width", params.width)?;
        let color = params.color;
        let (w, h) = (image.texture.width(), image.texture.height());
        let mut canvas = Canvas::new(w, h);
        let Some(fan) = fan_shape(&annotations, &camera, (w, h))? else {
            ctx.warn("the ghost or the selection is behind the camera: no fan");
            return draw(ctx, canvas, &image);
        };
        let [ghost, selection] = fan.rects;
        canvas.convex_polygon(&fan.hull, params.fill, [Some(ghost), Some(selection)]);
        for (lo, hi) in fan.rects {
            canvas.rect_outline(lo, hi, width, color);
        }
        for [a, b] in fan.bridges {
            canvas.line(a, b, width, color);
        }
        draw(ctx, canvas, &image)
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(FanNode);
}
