//! `CurvatureFlow`: noise advected along principal curvature directions (the tutorial's §1,
//! Fig. 11/14; see shaders/curvature_flow.wgsl for the line integral convolution).

use crate::curvature::gbuffer_sized;
use crate::screen_pass::{self, MASK_FORMAT};
use crate::value::Mask;
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `Flow` of shaders/curvature_flow.wgsl (see there for the fields).
    pub struct FlowUniforms in "curvature_flow" as "Flow" {
        pub inv_view_proj: [[f32; 4]; 4],
        pub frame: [f32; 2],
        pub steps: u32,
        pub step: f32,
        pub grain: f32,
        pub smaller_curvature: u32,
        pub contrast: f32,
        pub mean: f32,
    }
}

hatchery_graph::param_choice! {
    /// The principal direction of the larger or of the smaller |κ|.
    pub enum Direction { MaxCurvature = "max_curvature", MinCurvature = "min_curvature" }
}

hatchery_graph::node_params! {
    /// Parameters of `CurvatureFlow`.
    pub struct CurvatureFlowParams {
        /// streamline length, pixels
        pub length: f32 = 20.0, range(2.0, 200.0), unit(pixels);
        /// integration step along a streamline, pixels (smaller follows curved fields more closely)
        pub step: f32 = 1.0, range(0.25, 4.0), unit(pixels);
        /// the principal direction of the larger or of the smaller |κ|
        pub direction: Direction = Direction::MaxCurvature;
        /// noise cell size on the surface, world units (about a pixel's footprint)
        pub grain: f32 = 1.0, range(1e-6, 1e6);
        /// how strongly the streaks stand out from the surface around them
        pub contrast: f32 = 1.0, range(0.0, 4.0);
        /// average output (e.g. 0.8 to multiply a colour image by the streaks)
        pub mean: f32 = 0.5, range(0.0, 1.0);
    }
}

pub struct CurvatureFlowNode;

impl Node<Value, Ctx> for CurvatureFlowNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "CurvatureFlow",
            category: "Volume",
            doc: "Flow along curvature directions (the tutorial's §1, Fig. 11/14): a line \
                  integral convolution of 3-D value noise along Curvature's principal-direction \
                  field in image space — each surface pixel averages the noise at the surface \
                  points along its streamline (`length` pixels, RK2 steps of `step`), so the \
                  streaks follow the larger-|κ| direction (or the smaller) and stay on the \
                  surface as the view moves. A mask in [0, 1] (`mean` on average), 0 off the surface; \
                  mix it with MixByMask or multiply a shaded image by it.",
            inputs: vec![
                PortSpec::input("curvature", PortType::Image, "Curvature's output"),
                PortSpec::input(
                    "gbuffer",
                    PortType::GBuffer,
                    "the surface (the G-buffer Curvature read)",
                ),
            ],
            outputs: vec![PortSpec::output(
                "flow",
                PortType::Mask,
                "streaks along the principal direction",
            )],
            params: CurvatureFlowParams::specs(),
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
        let params = CurvatureFlowParams::read(p)?;
        let curvature = inputs.require("curvature")?.image("curvature")?.clone();
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?.clone();
        gbuffer_sized(
            "curvature",
            &curvature.texture,
            &gbuffer,
            ": connect the Curvature of this G-buffer",
        )?;
        let camera = &gbuffer.camera;
        let size = (camera.width, camera.height);
        let step = params.step;
        let uniforms = FlowUniforms {
            inv_view_proj: camera.view_proj().inverse().to_cols_array_2d(),
            frame: [size.0 as f32, size.1 as f32],
            steps: (0.5 * params.length / step).ceil().clamp(1.0, 256.0) as u32,
            step,
            grain: params.grain,
            smaller_curvature: (params.direction == Direction::MinCurvature).into(),
            contrast: params.contrast,
            mean: params.mean,
        };
        let flow = screen_pass::render(
            ctx,
            "curvature_flow",
            MASK_FORMAT,
            size,
            &[&curvature.texture, &gbuffer.depth],
            Some(bytemuck::bytes_of(&uniforms)),
        )
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Mask(Arc::new(Mask { texture: flow }))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(CurvatureFlowNode)
        .program(
            "curvature_flow",
            vec![
                ("fullscreen.wgsl", shaders::FULLSCREEN),
                ("curvature_field.wgsl", shaders::CURVATURE_FIELD),
                shaders::part!("curvature_flow.wgsl"),
            ],
        )
        .uniform(FlowUniforms::layout());
}
