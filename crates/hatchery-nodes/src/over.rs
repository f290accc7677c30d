//! `Over`: one image over another (premultiplied Porter–Duff over), e.g. a volume rendering over
//! paper, or strokes embedded over a rendering.

use crate::fused_pass::{self, Arg, Fusable, Stage, StageInputs};
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

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
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        fused_pass::execute(self, ctx, inputs, p)
    }
}

impl Fusable for OverNode {
    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(
        &self,
        _ctx: &mut Ctx,
        _inputs: &StageInputs,
        _p: &Params,
    ) -> Result<Stage, NodeError> {
        Ok(Stage {
            library: "over",
            function: "over",
            uniform: None,
            args: vec![Arg::At("front"), Arg::At("back")],
            output: PortType::Image,
        })
    }
}
