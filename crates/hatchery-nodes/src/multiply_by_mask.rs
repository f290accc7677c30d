//! `MultiplyByMask`: darkens an image by a mask (ink where the mask says so).

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

hatchery_graph::node_params! {
    /// The parameters of `MultiplyByMask`.
    pub struct MultiplyByMaskParams {
        /// multiply by 1 − mask instead
        pub invert: bool = false;
    }
}

pub struct MultiplyByMaskNode;

impl Fusable for MultiplyByMaskNode {
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
            params: MultiplyByMaskParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(&self, _ctx: &mut Ctx, _inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        Ok(Stage {
            library: "multiply_by_mask",
            function: "multiply_by_mask",
            uniform: None,
            args: vec![
                Arg::At("image"),
                Arg::At("mask"),
                Arg::Constant(MultiplyByMaskParams::read(p)?.invert.to_string()),
            ],
            output: PortType::Image,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&MultiplyByMaskNode)
        .program("multiply_by_mask", shaders::screen(shaders::part!("multiply_by_mask.wgsl")));
}
