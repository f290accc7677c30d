//! `Stipple`: stippling of surfaces, dots whose density gives the tone and that stick to the
//! surface (Preim & Tietjen in Viola et al.'s 2005 tutorial: "Illustrative Visualization for
//! Surgical Planning", §2.1 and §6, and the slides "Efficient Texture-based Stippling"). docs/stippling.md.

use crate::Ctx;
use crate::stage::{Arg, Fusable, Stage, StageInputs};
use hatchery_graph::{NodeError, NodeSchema, Params, PortSpec, PortType};

crate::uniform_block! {
    /// `Stipple` of shaders/stipple.wgsl (see there for the fields).
    pub struct StippleUniforms in "stipple" as "Stipple" {
        pub inverse_view_proj: [[f32; 4]; 4],
        pub view_to_world: [[f32; 4]; 4],
        pub frame: [f32; 2],
        pub spacing: f32,
        pub radius: f32,
        pub coverage: f32,
        pub seed: u32,
        pub orthographic: u32,
        pub foreshortening: u32,
        pub reach: i32,
        pub pad0: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

hatchery_graph::node_params! {
    /// The parameters of `Stipple`.
    pub struct StippleParams {
        /// distance in pixels between neighbouring dots where the tone is darkest (the stipple lattice's cell on screen; Preim & Tietjen's "adjustable level of sparseness")
        pub spacing: f32 = 3.0, range(1.0, 64.0), unit(pixels);
        /// radius of each dot in pixels, at most `spacing` (above half of it the pass searches 125 lattice cells per level instead of 27)
        pub radius: f32 = 1.2, range(0.3, 64.0), unit(pixels);
        /// thin the dots where the surface turns away from the viewer (by n·v), so a tilted surface shows the tone its shading asks for rather than more dots per pixel
        pub foreshortening: bool = true;
        /// number that picks another random dot pattern (the same seed gives the same dots)
        pub seed: u32 = 0, range(0, 1000000);
    }
}

pub struct StippleNode;

impl Fusable for StippleNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Stipple",
            category: "Illustration",
            doc: "Stippling of a surface (Preim & Tietjen, Viola et al. 2005 tutorial, §2.1, §6 and \
                  \"Efficient Texture-based Stippling\"): round ink dots of `radius` pixels whose \
                  density gives the tone, ink coverage = darkness 1 − intensity (up to \
                  1 − exp(−π·radius²/spacing²)). The dots are a solid texture in world space — one \
                  jittered point with a random threshold per lattice cell, kept where its threshold \
                  is below the density and it lies within half a cell of the surface — so they \
                  stay on the surface when the camera orbits; the lattice's cell follows \
                  `spacing` pixels through power-of-two levels of detail, cross-faded.",
            inputs: vec![
                PortSpec::input(
                    "intensity",
                    PortType::Mask,
                    "shading intensity in [0, 1] (e.g. DiffuseIntensity); darker = more dots",
                ),
                PortSpec::input(
                    "gbuffer",
                    PortType::GBuffer,
                    "the surface: its depth places the dots in world space, its normal orients them",
                ),
            ],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Mask,
                "1 = paper, 0 = ink (anti-aliased dot edges)",
            )],
            params: StippleParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn pointwise(&self) -> &'static [bool] {
        &[true, true]
    }

    fn stage(&self, ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?;
        let p = StippleParams::read(p)?;
        let camera = &gbuffer.camera;
        let (w, h) = ctx.size();
        let spacing = p.spacing.max(1e-3);
        let radius = p.radius.clamp(1e-3, spacing);
        let uniforms = StippleUniforms {
            inverse_view_proj: camera.view_proj().inverse().to_cols_array_2d(),
            view_to_world: camera.view.inverse().to_cols_array_2d(),
            frame: [w as f32, h as f32],
            spacing,
            radius,
            coverage: std::f32::consts::PI * radius * radius / (spacing * spacing),
            seed: p.seed,
            orthographic: camera.orthographic.into(),
            foreshortening: p.foreshortening.into(),
            reach: if radius <= 0.5 * spacing { 1 } else { 2 },
            pad0: 0.0,
            pad1: 0.0,
            pad2: 0.0,
        };
        Ok(Stage {
            library: "stipple",
            function: "stipple",
            uniform: Some(("Stipple", bytemuck::bytes_of(&uniforms).to_vec())),
            args: vec![Arg::At("intensity"), Arg::At("gbuffer")],
            output: PortType::Mask,
        })
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&StippleNode)
        .program("stipple", shaders::screen(shaders::part!("stipple.wgsl")))
        .uniform(StippleUniforms::layout());
}
