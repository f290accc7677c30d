//! `MaskCombine`: per-pixel logic and arithmetic of two masks.

use crate::screen_pass;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

const OPERATIONS: &[&str] = &["and", "or", "min", "add", "subtract", "a_not_b"];

crate::uniform_block! {
    /// `Combine` of shaders/mask_combine.wgsl: options.x = the operation (index in OPERATIONS).
    pub struct CombineUniforms in "mask_combine" as "Combine" {
        pub options: [f32; 4],
    }
}

pub struct MaskCombineNode;

impl Node<Value, Ctx> for MaskCombineNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MaskCombine",
            category: "Compositing",
            doc: "Combines masks a and b per pixel: and = a·b, or = max(a, b), min, add and subtract \
                  (clamped to [0, 1]), a_not_b = a·(1 − b). E.g. eq. 10 of Fischer et al. 2005 is \
                  I_S a_not_b (silhouette_P2 and depth test).",
            inputs: vec![
                PortSpec::input("a", PortType::Mask, "first mask"),
                PortSpec::input("b", PortType::Mask, "second mask"),
            ],
            outputs: vec![PortSpec::output("mask", PortType::Mask, "the result")],
            params: vec![ParamSpec::choice(
                "operation",
                "and",
                OPERATIONS,
                "how to combine",
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
        let a = inputs.require("a")?.mask("a")?.clone();
        let b = inputs.require("b")?.mask("b")?.clone();
        let op = OPERATIONS
            .iter()
            .position(|o| *o == p.choice("operation"))
            .unwrap_or(0);
        Ok(vec![screen_pass::mask(
            ctx,
            "mask_combine",
            &[("a", &a.texture), ("b", &b.texture)],
            &[],
            Some(bytemuck::bytes_of(&CombineUniforms {
                options: [op as f32, 0.0, 0.0, 0.0],
            })),
        )?])
    }
}
