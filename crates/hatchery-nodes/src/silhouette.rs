//! `Silhouette`: image-space feature lines of a G-buffer layer (Fischer et al. 2005, §3.3.1), with
//! optional procedurally perturbed sampling (PIP, Yuan & Chen 2005, §6, eq. 2).

use crate::fused_pass::{self, Arg, Fusable, Stage, StageInputs};
use crate::{Ctx, Value};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

crate::uniform_block! {
    /// `Silhouette` of shaders/silhouette.wgsl: (depth threshold, normal threshold, use depth,
    /// use normals) and the pip settings (mode, amount, scale, seed).
    pub struct SilhouetteUniforms in "silhouette" as "Silhouette" {
        pub thresholds: [f32; 4],
        pub pip: [f32; 4],
    }
}

pub const PIP_MODES: &[&str] = &["none", "constant", "texture", "noise", "dots"];

pub struct SilhouetteNode;

impl Node<Value, Ctx> for SilhouetteNode {
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
            params: vec![
                ParamSpec::float(
                    "depth_threshold",
                    0.001,
                    0.0,
                    100.0,
                    "threshold on the Sobel depth-gradient magnitude",
                ),
                ParamSpec::float(
                    "normal_threshold",
                    3.98,
                    -4.0,
                    4.0,
                    "threshold on the summed neighbour normal dot products",
                ),
                ParamSpec::bool("use_depth", true, "detect depth discontinuities (eq. 3)"),
                ParamSpec::bool(
                    "use_normals",
                    true,
                    "detect normal discontinuities (eq. 4–5)",
                ),
                ParamSpec::choice(
                    "pip",
                    "none",
                    PIP_MODES,
                    "perturbation P(x, y) of the sampling positions",
                ),
                ParamSpec::float(
                    "pip_amount",
                    1.0,
                    0.0,
                    16.0,
                    "P's scale in pixels (the constant for `constant`)",
                ),
                ParamSpec::float(
                    "pip_scale",
                    8.0,
                    1.0,
                    256.0,
                    "pattern size in pixels for `noise` and `dots`",
                ),
                ParamSpec::int("pip_seed", 0, 0, 1_000_000, "seed of the `noise` pattern"),
                ParamSpec::path(
                    "pip_texture",
                    "",
                    "grey-scale PNG tiled over the frame for `texture`",
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
        fused_pass::execute(self, ctx, inputs, p)
    }
}

impl Fusable for SilhouetteNode {
    /// The G-buffer is read around the pixel.
    fn pointwise(&self) -> &'static [bool] {
        &[false]
    }

    fn own_textures(&self) -> u32 {
        1
    }

    fn stage(&self, ctx: &mut Ctx, inputs: &StageInputs, p: &Params) -> Result<Stage, NodeError> {
        inputs.require("gbuffer")?.gbuffer("gbuffer")?;
        let mode = PIP_MODES
            .iter()
            .position(|m| *m == p.choice("pip"))
            .unwrap_or(0);
        let pattern = if PIP_MODES[mode] == "texture" {
            let path = p.path("pip_texture");
            if path.as_os_str().is_empty() {
                return Err(NodeError::new(
                    "pip \"texture\" needs parameter `pip_texture` (a PNG file)",
                ));
            }
            ctx.file_texture(&path).map_err(NodeError::new)?
        } else {
            ctx.blank_texture()
        };
        let uniforms = SilhouetteUniforms {
            thresholds: [
                p.f32("depth_threshold"),
                p.f32("normal_threshold"),
                0.0,
                0.0,
            ],
            pip: [
                0.0,
                p.f32("pip_amount"),
                p.f32("pip_scale"),
                p.int("pip_seed") as f32,
            ],
        };
        // The mode and switches as constants (shaders/silhouette.wgsl says why).
        Ok(Stage {
            library: "silhouette",
            function: "silhouette",
            uniform: Some(("Silhouette", bytemuck::bytes_of(&uniforms).to_vec())),
            args: vec![
                Arg::Textures("gbuffer"),
                Arg::Texture(pattern),
                Arg::Constant(mode.to_string()),
                Arg::Constant(p.bool("use_depth").to_string()),
                Arg::Constant(p.bool("use_normals").to_string()),
            ],
            output: PortType::Mask,
        })
    }
}
