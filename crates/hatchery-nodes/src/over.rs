//! `Over`: one image over another (premultiplied Porter–Duff over), e.g. a volume rendering over
//! paper, or strokes embedded over a rendering.

use crate::screen_pass::{self, IMAGE_FORMAT};
use crate::value::Image;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

pub struct OverNode;

impl Node<Value, Ctx> for OverNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Over",
            category: "Compositing",
            doc: "front + (1 − α_front)·back per pixel, on premultiplied colours (Porter–Duff over).",
            inputs: vec![
                PortSpec::input("front", PortType::Image, "the image on top"),
                PortSpec::input("back", PortType::Image, "the image underneath"),
            ],
            outputs: vec![PortSpec::output("image", PortType::Image, "the composite")],
            params: vec![],
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        _p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let front = inputs.require("front")?.image("front")?.clone();
        let back = inputs.require("back")?.image("back")?.clone();
        let texture = screen_pass::run(
            ctx,
            "over",
            IMAGE_FORMAT,
            &[("front", &front.texture), ("back", &back.texture)],
            &[],
            None,
        )?;
        Ok(vec![Value::Image(Arc::new(Image { texture }))])
    }
}
