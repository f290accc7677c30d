//! `Fill`: a frame of one colour (the paper of an illustration).

use crate::screen_pass;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

crate::uniform_block! {
    /// `Fill` of shaders/fill.wgsl: the straight (not premultiplied) RGBA colour.
    pub struct FillUniforms in "fill" as "Fill" {
        pub color: [f32; 4],
    }
}

hatchery_graph::node_params! {
    /// The parameters of `Fill`.
    pub struct FillParams {
        /// the colour that fills the whole frame (alpha = opacity)
        pub color: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
    }
}

pub struct FillNode;

impl Node<Value, Ctx> for FillNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Fill",
            category: "Compositing",
            doc: "An image of the frame size filled with one colour (e.g. paperColor of Fischer et al. \
                  2005, §3.3.4).",
            inputs: vec![],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the filled frame",
            )],
            params: FillParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        _inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        Ok(vec![screen_pass::image(
            ctx,
            "fill",
            &[],
            &[],
            Some(bytemuck::bytes_of(&FillUniforms {
                color: FillParams::read(p)?.color,
            })),
        )?])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(FillNode)
        .program("fill", shaders::screen(shaders::part!("fill.wgsl")))
        .uniform(FillUniforms::layout());
}
