//! `Halftone`: procedural screening of an intensity mask (Fischer et al. 2005, §3.3.2, eq. 7–9).

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

crate::uniform_block! {
    /// `Halftone` of shaders/halftone.wgsl.
    pub struct HalftoneUniforms in "halftone" as "Halftone" {
        pub theta: f32,
        pub cell: f32,
        pub c_cross: f32,
        pub cos_theta: f32,
        pub sin_theta: f32,
        pub pad0: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `Halftone`.
    pub struct HalftoneParams {
        /// rotation of the pattern, degrees
        pub theta: f32 = 20.0, range(-360.0, 360.0);
        /// spacing of the hatching lines: the pattern's cell size n in pixels
        pub cell: f32 = 4.0, range(1.0, 256.0), unit(pixels);
        /// intensity below which cross-hatching appears
        pub c_cross: f32 = 0.9, range(0.0, 1.0);
    }
}

pub struct HalftoneNode;

impl Fusable for HalftoneNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Halftone",
            category: "Illustration",
            doc: "Black-and-white hatching by procedural screening (Fischer et al. 2005, eq. 7–9): the \
                  pixel (x, y) is rotated by θ, (s, t) = ((x' mod n)/n, (y' mod n)/n), τ = c_cross·t if \
                  s ≤ c_cross else (1 − c_cross)·s + c_cross, output 1 where intensity ≥ τ, else 0 \
                  (ink). Pattern in screen pixels.",
            inputs: vec![PortSpec::input(
                "intensity",
                PortType::Mask,
                "intensity in [0, 1]",
            )],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Mask,
                "1 = paper, 0 = ink",
            )],
            params: HalftoneParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true]
    }

    fn stage(&self, _ctx: &mut Ctx, _inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let p = HalftoneParams::read(p)?;
        let theta = p.theta.to_radians();
        let uniforms = HalftoneUniforms {
            theta,
            cell: p.cell,
            c_cross: p.c_cross,
            cos_theta: theta.cos(),
            sin_theta: theta.sin(),
            pad0: 0.0,
            pad1: 0.0,
            pad2: 0.0,
        };
        Ok(Stage {
            library: "halftone",
            function: "halftone",
            uniform: Some(("Halftone", bytemuck::bytes_of(&uniforms).to_vec())),
            args: vec![Arg::At("intensity")],
            output: PortType::Mask,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&HalftoneNode)
        .program("halftone", shaders::screen(shaders::part!("halftone.wgsl")))
        .uniform(HalftoneUniforms::layout());
}
