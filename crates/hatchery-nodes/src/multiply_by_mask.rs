//! `MultiplyByMask`: darkens an image by a mask (ink where the mask says so).

use crate::screen_pass;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

crate::uniform_block! {
    /// `MultiplyParams` of shaders/multiply_by_mask.wgsl: options.x = 1 to invert the mask.
    pub struct MultiplyUniforms in "multiply_by_mask" as "MultiplyParams" {
        pub options: [f32; 4],
    }
}

pub struct MultiplyByMaskNode;

impl Node<Value, Ctx> for MultiplyByMaskNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MultiplyByMask",
            category: "Compositing",
            doc: "Colour × m (or × (1 − m) with `invert`), alpha kept: the `pixelColor *= …` lines of \
                  Fischer et al. 2005, §3.3.4 (black silhouettes, black hatching).",
            inputs: vec![
                PortSpec::input("image", PortType::Image, "the image"),
                PortSpec::input("mask", PortType::Mask, "the factor, clamped to [0, 1]"),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the darkened image",
            )],
            params: vec![ParamSpec::bool(
                "invert",
                false,
                "multiply by 1 − mask instead",
            )],
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
        let image = inputs.require("image")?.image("image")?.clone();
        let mask = inputs.require("mask")?.mask("mask")?.clone();
        let uniforms = MultiplyUniforms {
            options: [if p.bool("invert") { 1.0 } else { 0.0 }, 0.0, 0.0, 0.0],
        };
        Ok(vec![screen_pass::image(
            ctx,
            "multiply_by_mask",
            &[("image", &image.texture), ("mask", &mask.texture)],
            &[],
            Some(bytemuck::bytes_of(&uniforms)),
        )?])
    }
}
