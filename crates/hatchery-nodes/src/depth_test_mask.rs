//! `DepthTestMask`: where one layer lies in front of another (Fischer et al. 2005, eq. 10).

use crate::screen_pass;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

const COMPARISONS: &[&str] = &["a<=b", "a<b", "a>=b", "a>b"];

crate::uniform_block! {
    /// `DepthTest` of shaders/depth_test_mask.wgsl: options.x = the comparison (index in
    /// COMPARISONS).
    pub struct DepthTestUniforms in "depth_test_mask" as "DepthTest" {
        pub options: [f32; 4],
    }
}

pub struct DepthTestMaskNode;

impl Node<Value, Ctx> for DepthTestMaskNode {
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
            params: vec![ParamSpec::choice(
                "compare",
                "a<=b",
                COMPARISONS,
                "the comparison",
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
        let a = inputs.require("a")?.gbuffer("a")?.clone();
        let b = inputs.require("b")?.gbuffer("b")?.clone();
        let op = COMPARISONS
            .iter()
            .position(|c| *c == p.choice("compare"))
            .unwrap_or(0);
        Ok(vec![screen_pass::mask(
            ctx,
            "depth_test_mask",
            &[("a", &a.depth), ("b", &b.depth)],
            &[],
            Some(bytemuck::bytes_of(&DepthTestUniforms {
                options: [op as f32, 0.0, 0.0, 0.0],
            })),
        )?])
    }
}
