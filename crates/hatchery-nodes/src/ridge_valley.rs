//! `RidgeValley`: ridge and valley lines from principal curvatures (the tutorial's §1, Fig. 12;
//! see shaders/ridge_valley.wgsl for the extremality test).

use crate::screen_pass;
use crate::value::Mask;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `RidgeValley` of shaders/ridge_valley.wgsl.
    pub struct RidgeValleyUniforms in "ridge_valley" as "RidgeValley" {
        pub threshold: f32,
        pub thickness: f32,
        pub valleys: u32,
        pub pad0: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `RidgeValley`.
    pub struct RidgeValleyParams {
        /// smallest |κ| of a line, world units⁻¹
        pub threshold: f32 = 1.0, range(0.0, 1.0e6);
        /// line width, pixels (up to 3)
        pub thickness: f32 = 1.5, range(0.5, 3.0), unit(pixels);
    }
}

pub struct RidgeValleyNode;

impl Node<Value, Ctx> for RidgeValleyNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "RidgeValley",
            category: "Volume",
            doc: "Ridge and valley lines of an iso-surface (the tutorial's §1, Fig. 12) from \
                  Curvature's image: ridges where κ1 > threshold and κ1 is a maximum along its \
                  principal direction, valleys where κ2 < −threshold and κ2 is a minimum along \
                  the second principal direction (the extremality test: a parabola through the \
                  curvature one pixel before, at and after, along the direction on screen, with \
                  a clear maximum: constant curvature draws no line). Lines `thickness` \
                  pixels wide, as masks.",
            inputs: vec![PortSpec::input(
                "curvature",
                PortType::Image,
                "Curvature's output",
            )],
            outputs: vec![
                PortSpec::output("ridges", PortType::Mask, "1 on ridge lines"),
                PortSpec::output("valleys", PortType::Mask, "1 on valley lines"),
            ],
            params: RidgeValleyParams::specs(),
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
        let params = RidgeValleyParams::read(p)?;
        let curvature = inputs.require("curvature")?.image("curvature")?.clone();
        let size = (curvature.texture.width(), curvature.texture.height());
        let mut outputs = Vec::new();
        for valleys in [false, true] {
            let uniforms = RidgeValleyUniforms {
                threshold: params.threshold,
                thickness: params.thickness,
                valleys: valleys.into(),
                pad0: 0.0,
            };
            let mask = screen_pass::render(
                ctx,
                "ridge_valley",
                wgpu::TextureFormat::R32Float,
                size,
                &[&curvature.texture],
                Some(bytemuck::bytes_of(&uniforms)),
            )
            .map_err(|e| NodeError::new(e.to_string()))?;
            outputs.push(Value::Mask(Arc::new(Mask { texture: mask })));
        }
        Ok(outputs)
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(RidgeValleyNode)
        .program("ridge_valley", shaders::screen(shaders::part!("ridge_valley.wgsl")))
        .uniform(RidgeValleyUniforms::layout());
}
