//! `Silhouette`: image-space feature lines of a G-buffer layer (Fischer et al. 2005, §3.3.1), with
//! optional procedurally perturbed sampling (PIP, Yuan & Chen 2005, §6, eq. 2).

use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::Ctx;
use hatchery_graph::{
    NodeError, NodeSchema, Params, PortSpec, PortType, 
};

crate::uniform_block! {
    /// `Silhouette` of shaders/silhouette.wgsl (the PIP mode and the switches are constants of
    /// the pass).
    pub struct SilhouetteUniforms in "silhouette" as "Silhouette" {
        /// Threshold on the Sobel depth-gradient magnitude (eq. 3).
        pub depth_threshold: f32,
        /// Threshold on the summed neighbour normal dot products (eq. 4–5).
        pub normal_threshold: f32,
        /// PIP: P's scale in pixels (Yuan & Chen §6, eq. 2).
        pub pip_amount: f32,
        /// PIP: pattern size in pixels (`noise`, `dots`).
        pub pip_scale: f32,
        /// PIP: seed of the `noise` pattern.
        pub pip_seed: f32,
        /// Distance of the unperturbed taps, whole pixels (1: the paper's neighbours).
        pub tap_distance: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

hatchery_graph::param_choice! {
    /// Perturbation P(x, y) of the sampling positions (Yuan & Chen 2005, §6); the code is the
    /// shader's `mode` constant.
    pub enum PipMode {
        None = "none",
        Constant = "constant",
        Texture = "texture",
        Noise = "noise",
        Dots = "dots",
    }
}

hatchery_graph::node_params! {
    /// The parameters of `Silhouette`.
    pub struct SilhouetteParams {
        /// threshold on the Sobel depth-gradient magnitude
        pub depth_threshold: f32 = 0.001, range(0.0, 100.0);
        /// threshold on the summed neighbour normal dot products
        pub normal_threshold: f32 = 3.98, range(-4.0, 4.0);
        /// distance of the depth and normal taps from the pixel (rounded to whole pixels; 1: the
        /// paper's neighbours): lines are about twice this wide
        pub tap_distance: f32 = 1.0, range(1.0, 16.0), unit(pixels);
        /// draw lines where the depth jumps: outlines against the background and other parts
        /// (eq. 3)
        pub use_depth: bool = true;
        /// draw lines where the surface bends sharply: creases and edges (eq. 4–5)
        pub use_normals: bool = true;
        /// perturbation P(x, y) of the sampling positions
        pub pip: PipMode = PipMode::None;
        /// P's scale in pixels (the constant for `constant`)
        pub pip_amount: f32 = 1.0, range(0.0, 16.0), unit(pixels);
        /// pattern size in pixels for `noise` and `dots`
        pub pip_scale: f32 = 8.0, range(1.0, 256.0), unit(pixels);
        /// seed of the `noise` pattern
        pub pip_seed: i64 = 0, range(0, 1_000_000);
        /// grey-scale PNG tiled over the frame for `texture`
        pub pip_texture: std::path::PathBuf = "";
    }
}

pub struct SilhouetteNode;

impl Fusable for SilhouetteNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Silhouette",
            category: "Illustration",
            doc: "Binary silhouette mask of a G-buffer layer: Sobel magnitude of the window-space depth \
                  ≥ depth_threshold (eq. 3) OR the sum of the dot products with the four neighbour \
                  normals < normal_threshold (eq. 4–5), Fischer et al. 2005. PIP (Yuan & Chen 2005, \
                  eq. 2) scales every tap offset by P(x, y): a constant (line width), a tiled PNG, \
                  value noise or a dot matrix (stippled, felt-tip lines); P = 0 detects nothing.",
            inputs: vec![PortSpec::input("gbuffer", PortType::GBuffer, "the layer")],
            outputs: vec![PortSpec::output(
                "mask",
                PortType::Mask,
                "1 on silhouettes, 0 elsewhere",
            )],
            params: SilhouetteParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    /// The G-buffer is read around the pixel.
    fn pointwise(&self) -> &'static [bool] {
        &[false]
    }

    fn own_textures(&self) -> u32 {
        1
    }

    fn stage(&self, ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        inputs.require("gbuffer")?.gbuffer("gbuffer")?;
        let p = SilhouetteParams::read(p)?;
        let pattern = if p.pip == PipMode::Texture {
            if p.pip_texture.as_os_str().is_empty() {
                return Err(NodeError::new(
                    "pip \"texture\" needs parameter `pip_texture` (a PNG file)",
                ));
            }
            ctx.file_texture(&p.pip_texture)?
        } else {
            ctx.blank_texture()
        };
        let uniforms = SilhouetteUniforms {
            depth_threshold: p.depth_threshold,
            normal_threshold: p.normal_threshold,
            pip_amount: p.pip_amount,
            pip_scale: p.pip_scale,
            pip_seed: p.pip_seed as f32,
            tap_distance: p.tap_distance.round().max(1.0),
            ..Default::default()
        };
        // The mode and switches as constants (shaders/silhouette.wgsl says why).
        Ok(Stage {
            library: "silhouette",
            function: "silhouette",
            uniform: Some(("Silhouette", bytemuck::bytes_of(&uniforms).to_vec())),
            args: vec![
                Arg::Textures("gbuffer"),
                Arg::Texture(pattern),
                Arg::Constant((p.pip as u32).to_string()),
                Arg::Constant(p.use_depth.to_string()),
                Arg::Constant(p.use_normals.to_string()),
            ],
            output: PortType::Mask,
        })
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.image_stage(&SilhouetteNode)
        .program("silhouette", shaders::screen(shaders::part!("silhouette.wgsl")))
        .uniform(SilhouetteUniforms::layout());
}
