//! `DiffuseIntensity`: max(n · l, 0) of a G-buffer layer (Fischer et al. 2005, eq. 1 and 6).

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

crate::uniform_block! {
    /// `Diffuse` of shaders/diffuse_intensity.wgsl (see there for the fields).
    pub struct DiffuseUniforms in "diffuse_intensity" as "Diffuse" {
        pub inverse_proj: [[f32; 4]; 4],
        pub light_dir: [f32; 3],
        pub empty: f32,
        pub frame: [f32; 2],
        pub orthographic: u32,
        pub pad0: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `DiffuseIntensity`.
    pub struct DiffuseIntensityParams {
        /// value where the layer has no surface
        pub empty: f32 = 1.0, range(0.0, 1.0);
        /// light back faces with the flipped normal
        pub two_sided: bool = false;
    }
}

pub struct DiffuseIntensityNode;

impl Fusable for DiffuseIntensityNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "DiffuseIntensity",
            category: "Illustration",
            doc: "Diffuse intensity I = max(n · lightDir, 0) per pixel of a G-buffer layer (Fischer et al. \
                  2005, eq. 1/6), with the light's direction in view space. Pixels without surface get \
                  `empty` (1 = paper stays white under halftoning).",
            inputs: vec![
                PortSpec::input("gbuffer", PortType::GBuffer, "the layer"),
                PortSpec::input("light", PortType::Light, "the light"),
            ],
            outputs: vec![PortSpec::output(
                "intensity",
                PortType::Mask,
                "intensity in [0, 1]",
            )],
            params: DiffuseIntensityParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(&self, ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?;
        let light = inputs.require("light")?.light("light")?;
        let params = DiffuseIntensityParams::read(p)?;
        let l = light.view_direction(&gbuffer.camera);
        let (w, h) = ctx.size();
        let uniforms = DiffuseUniforms {
            inverse_proj: gbuffer.camera.proj.inverse().to_cols_array_2d(),
            light_dir: l.to_array(),
            empty: params.empty,
            frame: [w as f32, h as f32],
            orthographic: gbuffer.camera.orthographic.into(),
            pad0: 0.0,
        };
        Ok(Stage {
            library: "diffuse_intensity",
            function: "diffuse_intensity",
            uniform: Some(("Diffuse", bytemuck::bytes_of(&uniforms).to_vec())),
            // The depth is read for two-sided lighting only.
            args: vec![
                if params.two_sided {
                    Arg::At("gbuffer")
                } else {
                    Arg::NormalAt("gbuffer")
                },
                Arg::Constant(params.two_sided.to_string()),
            ],
            output: PortType::Mask,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&DiffuseIntensityNode)
        .program("diffuse_intensity", shaders::screen(shaders::part!("diffuse_intensity.wgsl")))
        .uniform(DiffuseUniforms::layout());
}
