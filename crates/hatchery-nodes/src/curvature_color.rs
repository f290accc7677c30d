//! `CurvatureColor`: curvature colour mapping (Hadwiger, the tutorial's §1 Fig. 10) — a measure
//! of the principal curvatures through a 1-D transfer function (shaders/curvature_color.wgsl).

use crate::screen_pass::{self, IMAGE_FORMAT};
use crate::value::{Image, TransferFunction};
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

const MEASURES: &[&str] = &["curvedness", "k1", "k2", "mean", "gaussian"];

crate::uniform_block! {
    /// `CurvatureColor` of shaders/curvature_color.wgsl: (measure code, TF domain lo, hi, 0).
    pub struct CurvatureColorUniforms in "curvature_color" as "CurvatureColor" {
        pub options: [f32; 4],
    }
}

fn measure_code(name: &str) -> f32 {
    match name {
        "k1" => 0.0,
        "k2" => 1.0,
        "mean" => 2.0,
        "gaussian" => 3.0,
        _ => 4.0,
    }
}

pub struct CurvatureColorNode;

impl Node<Value, Ctx> for CurvatureColorNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "CurvatureColor",
            category: "Volume",
            doc: "Curvature colour mapping (Hadwiger's deferred iso-surface shading, the \
                  tutorial's §1, Fig. 10): a measure of Curvature's principal curvatures — \
                  curvedness √(κ1² + κ2²), κ1, κ2, mean (κ1 + κ2)/2 or Gaussian κ1·κ2, in world \
                  units⁻¹ (⁻² for Gaussian) — through a 1-D transfer function whose domain is in \
                  the same units (TransferFunction1D with custom points, e.g. \"-2: …; 2: …\"). \
                  Transparent where there is no surface.",
            inputs: vec![
                PortSpec::input("curvature", PortType::Image, "Curvature's output"),
                PortSpec::input("tf", PortType::TransferFunction, "measure → colour"),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "premultiplied colour",
            )],
            params: vec![ParamSpec::choice(
                "measure",
                "curvedness",
                MEASURES,
                "which curvature the colour shows",
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
        let curvature = inputs.require("curvature")?.image("curvature")?.clone();
        let tf = match inputs.require("tf")?.transfer_function("tf")?.as_ref() {
            TransferFunction::Color(f) => f.clone(),
            TransferFunction::Style { .. } => {
                return Err(NodeError::at_port(
                    "tf",
                    "a style transfer function; CurvatureColor takes a colour transfer function",
                ));
            }
        };
        let lut = ctx.gpu.texture_2d_init(
            "curvature lut",
            tf.lut.len() as u32,
            1,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&tf.lut),
        );
        let uniforms = CurvatureColorUniforms {
            options: [
                measure_code(p.choice("measure")),
                tf.domain[0],
                tf.domain[1],
                0.0,
            ],
        };
        let size = (curvature.texture.width(), curvature.texture.height());
        let image = screen_pass::render(
            ctx,
            "curvature_color",
            IMAGE_FORMAT,
            size,
            &[&curvature.texture, &lut],
            Some(bytemuck::bytes_of(&uniforms)),
        )
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Image(Arc::new(Image { texture: image }))])
    }
}
