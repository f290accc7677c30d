//! `Over`: one image over another (premultiplied Porter–Duff over), e.g. a volume rendering over
//! paper, or strokes embedded over a rendering.

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

pub struct OverNode;

impl Fusable for OverNode {
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


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&OverNode)
        .program("over", shaders::screen(shaders::part!("over.wgsl")));
}
