//! `DepthTestMask`: where one layer lies in front of another (Fischer et al. 2005, eq. 10).

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

hatchery_graph::param_choice! {
    /// The depth comparison of layer a with layer b; the code is the shader's constant.
    pub enum Comparison {
        LessEqual = "a<=b",
        Less = "a<b",
        GreaterEqual = "a>=b",
        Greater = "a>b",
    }
}

hatchery_graph::node_params! {
    /// The parameters of `DepthTestMask`.
    pub struct DepthTestMaskParams {
        /// the mask is 1 where layer a is in front of b (a<b, a<=b: smaller depth is nearer) or
        /// behind it (a>b, a>=b)
        pub compare: Comparison = Comparison::LessEqual;
    }
}

pub struct DepthTestMaskNode;

impl Fusable for DepthTestMaskNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "DepthTestMask",
            category: "Compositing",
            doc: "1 where the window-space depths of layers a and b compare true, else 0. With a = layer 2 \
                  and b = the secondary geometry, `a<=b` is the depth test of Fischer et al. 2005, eq. 10. \
                  Empty pixels have depth 1.",
            inputs: vec![
                PortSpec::input("a", PortType::GBuffer, "first layer"),
                PortSpec::input("b", PortType::GBuffer, "second layer"),
            ],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Mask,
                "the test result, 0 or 1",
            )],
            params: DepthTestMaskParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(&self, _ctx: &mut Ctx, _inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let op = DepthTestMaskParams::read(p)?.compare as u32;
        Ok(Stage {
            library: "depth_test_mask",
            function: "depth_test_mask",
            uniform: None,
            args: vec![
                Arg::DepthAt("a"),
                Arg::DepthAt("b"),
                Arg::Constant(op.to_string()),
            ],
            output: PortType::Mask,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&DepthTestMaskNode)
        .program("depth_test_mask", shaders::screen(shaders::part!("depth_test_mask.wgsl")));
}
