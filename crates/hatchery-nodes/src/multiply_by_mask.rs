//! `MultiplyByMask`: darkens an image by a mask (ink where the mask says so).

use crate::fused_pass::{self, Arg, Fusable, Stage, StageInputs};
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};

hatchery_graph::node_params! {
    /// The parameters of `MultiplyByMask`.
    pub struct MultiplyByMaskParams {
        /// multiply by 1 − mask instead
        pub invert: bool = false;
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
            params: MultiplyByMaskParams::specs(),
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

impl Fusable for MultiplyByMaskNode {
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
