//! `MaskCombine`: per-pixel logic and arithmetic of two masks.

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

hatchery_graph::param_choice! {
    /// How two masks combine; the code is the shader's `op` constant.
    pub enum Operation {
        And = "and",
        Or = "or",
        Min = "min",
        Add = "add",
        Subtract = "subtract",
        ANotB = "a_not_b",
    }
}

hatchery_graph::node_params! {
    /// The parameters of `MaskCombine`.
    pub struct MaskCombineParams {
        /// how the two masks combine per pixel (and, or, min, add, subtract, a_not_b)
        pub operation: Operation = Operation::And;
    }
}

pub struct MaskCombineNode;

impl Fusable for MaskCombineNode {
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
            params: MaskCombineParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(&self, _ctx: &mut Ctx, _inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let op = MaskCombineParams::read(p)?.operation as u32;
        Ok(Stage {
            library: "mask_combine",
            function: "mask_combine",
            uniform: None,
            args: vec![Arg::At("a"), Arg::At("b"), Arg::Constant(op.to_string())],
            output: PortType::Mask,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&MaskCombineNode)
        .program("mask_combine", shaders::screen(shaders::part!("mask_combine.wgsl")));
}
