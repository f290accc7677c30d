//! `Halftone`: procedural screening of an intensity mask (Fischer et al. 2005, §3.3.2, eq. 7–9).

use crate::screen_pass;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

crate::uniform_block! {
    /// `Halftone` of shaders/halftone.wgsl: (θ in radians, cell size in pixels, c_cross, 0).
    pub struct HalftoneUniforms in "halftone" as "Halftone" {
        pub params: [f32; 4],
    }
}

pub struct HalftoneNode;

impl Node<Value, Ctx> for HalftoneNode {
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
            params: vec![
                ParamSpec::float(
                    "theta",
                    20.0,
                    -360.0,
                    360.0,
                    "rotation of the pattern, degrees",
                ),
                ParamSpec::float("cell", 4.0, 1.0, 256.0, "cell size n in pixels"),
                ParamSpec::float(
                    "c_cross",
                    0.9,
                    0.0,
                    1.0,
                    "intensity below which cross-hatching appears",
                ),
            ],
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
        let intensity = inputs.require("intensity")?.mask("intensity")?.clone();
        let uniforms = HalftoneUniforms {
            params: [
                p.f32("theta").to_radians(),
                p.f32("cell"),
                p.f32("c_cross"),
                0.0,
            ],
        };
        Ok(vec![screen_pass::mask(
            ctx,
            "halftone",
            &[("intensity", &intensity.texture)],
            &[],
            Some(bytemuck::bytes_of(&uniforms)),
        )?])
    }
}
