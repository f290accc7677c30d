//! `MixByMask`: mix(base, over, mask) — an image or a colour blended in where a mask is set.

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

crate::uniform_block! {
    /// `MixParams` of shaders/mix_by_mask.wgsl: the premultiplied colour (whether an `over`
    /// image replaces it is a constant of the pass).
    pub struct MixUniforms in "mix_by_mask" as "MixParams" {
        pub color: [f32; 4],
    }
}

hatchery_graph::node_params! {
    /// The parameters of `MixByMask`.
    pub struct MixByMaskParams {
        /// colour mixed in when `over` is not connected
        pub color: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
    }
}

pub struct MixByMaskNode;

impl Fusable for MixByMaskNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "MixByMask",
            category: "Compositing",
            doc: "Per pixel mix(base, over, m) = (1 − m)·base + m·over with m the mask clamped to [0, 1]; \
                  `over` is the `over` image if connected, else `color`. The mix() lines of Fischer et al. \
                  2005, §3.3.4.",
            inputs: vec![
                PortSpec::input("base", PortType::Image, "the image underneath"),
                PortSpec::input("mask", PortType::Mask, "how much of `over` to take"),
                PortSpec::optional("over", PortType::Image, "the image mixed in (else `color`)"),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the mixed image",
            )],
            params: MixByMaskParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true, true]
    }

    fn stage(&self, _ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let c = MixByMaskParams::read(p)?.color;
        let uniforms = MixUniforms {
            color: [c[0] * c[3], c[1] * c[3], c[2] * c[3], c[3]],
        };
        Ok(Stage {
            library: "mix_by_mask",
            function: "mix_by_mask",
            uniform: Some(("MixParams", bytemuck::bytes_of(&uniforms).to_vec())),
            args: vec![
                Arg::At("base"),
                Arg::At("mask"),
                Arg::At("over"),
                Arg::Constant(inputs.connected("over").to_string()),
            ],
            output: PortType::Image,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&MixByMaskNode)
        .program("mix_by_mask", shaders::screen(shaders::part!("mix_by_mask.wgsl")))
        .uniform(MixUniforms::layout());
}
