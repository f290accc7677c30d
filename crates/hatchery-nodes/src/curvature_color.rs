//! `CurvatureColor`: curvature colour mapping (Hadwiger, the tutorial's §1 Fig. 10) — a measure
//! of the principal curvatures through a 1-D transfer function, or both through a 2-D (κ1, κ2)
//! map (shaders/curvature_color.wgsl).

use crate::screen_pass::{self, IMAGE_FORMAT};
use crate::value::{Image, TransferFunction};
use crate::{Ctx, Value};
use hatchery_graph::{
    FilePath, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// Texels per side of the built-in (κ1, κ2) map.
pub const SHAPE_MAP_SIZE: u32 = 65;

/// The built-in 2-D (κ1, κ2) map, `SHAPE_MAP_SIZE`² straight RGBA texels, row 0 at κ2 = +r: the
/// colour of Koenderink's shape index s = (2/π)·atan((κ1 + κ2)/(κ1 − κ2)) (κ1 ≥ κ2; −1 cup
/// blue, −½ rut cyan, 0 saddle green, ½ ridge yellow, 1 cap red), faded towards paper white as
/// the curvedness √(κ1² + κ2²) falls below 2/3 of the range (flat regions stay light).
pub fn shape_map() -> Vec<[f32; 4]> {
    const STOPS: [[f32; 3]; 5] = [
        [0.2, 0.35, 0.8],
        [0.3, 0.7, 0.8],
        [0.55, 0.78, 0.45],
        [0.95, 0.8, 0.3],
        [0.85, 0.25, 0.2],
    ];
    const PAPER: [f32; 3] = [0.95, 0.93, 0.9];
    let n = SHAPE_MAP_SIZE;
    let mut texels = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            // Coordinates in units of the range.
            let a = -1.0 + 2.0 * i as f32 / (n - 1) as f32;
            let b = 1.0 - 2.0 * j as f32 / (n - 1) as f32;
            let (k1, k2) = (a.max(b), a.min(b));
            let s = if k1 == k2 {
                k1.signum()
            } else {
                std::f32::consts::FRAC_2_PI * ((k1 + k2) / (k1 - k2)).atan()
            };
            let x = (s + 1.0) * 2.0;
            let k = (x.floor() as usize).min(3);
            let f = x - k as f32;
            let class: Vec<f32> = (0..3)
                .map(|c| STOPS[k][c] + (STOPS[k + 1][c] - STOPS[k][c]) * f)
                .collect();
            let strength = ((k1 * k1 + k2 * k2).sqrt() * 1.5).min(1.0);
            texels.push([
                PAPER[0] + (class[0] - PAPER[0]) * strength,
                PAPER[1] + (class[1] - PAPER[1]) * strength,
                PAPER[2] + (class[2] - PAPER[2]) * strength,
                1.0,
            ]);
        }
    }
    texels
}

/// The colour of (κ1, κ2) in a `width`×`height` map of straight RGBA texels (row 0 at κ2 = +r)
/// spanning [−r, r]²: bilinear between texels, clamped at the edges (shaders/curvature_color.wgsl).
pub fn map_lookup(map: &[[f32; 4]], width: u32, height: u32, range: f32, k: [f32; 2]) -> [f32; 4] {
    let r = range.max(1e-12);
    let u = ((k[0] + r) / (2.0 * r)).clamp(0.0, 1.0) * (width - 1) as f32;
    let v = ((r - k[1]) / (2.0 * r)).clamp(0.0, 1.0) * (height - 1) as f32;
    let (bu, bv) = (
        u.floor().min(width.saturating_sub(2) as f32),
        v.floor().min(height.saturating_sub(2) as f32),
    );
    let (fu, fv) = (u - bu, v - bv);
    let at = |i: u32, j: u32| map[(j.min(height - 1) * width + i.min(width - 1)) as usize];
    let (i, j) = (bu as u32, bv as u32);
    let mut out = [0.0; 4];
    for (c, o) in out.iter_mut().enumerate() {
        let top = at(i, j)[c] + (at(i + 1, j)[c] - at(i, j)[c]) * fu;
        let bottom = at(i, j + 1)[c] + (at(i + 1, j + 1)[c] - at(i, j + 1)[c]) * fu;
        *o = top + (bottom - top) * fv;
    }
    out
}

crate::uniform_block! {
    /// `CurvatureColor` of shaders/curvature_color.wgsl.
    pub struct CurvatureColorUniforms in "curvature_color" as "CurvatureColor" {
        /// A [`Measure`] code.
        pub measure: u32,
        pub map_range: f32,
        pub domain: [f32; 2],
    }
}


hatchery_graph::param_choice! {
    /// Which curvature the colour shows (k1_k2: the 2-D map).
    pub enum Measure {
        Curvedness = "curvedness",
        K1 = "k1",
        K2 = "k2",
        Mean = "mean",
        Gaussian = "gaussian",
        K1K2 = "k1_k2",
    }
}

crate::wgsl_constants! {
    Measure in "curvature_color" {
        Curvedness = "MEASURE_CURVEDNESS",
        K1 = "MEASURE_K1",
        K2 = "MEASURE_K2",
        Mean = "MEASURE_MEAN",
        Gaussian = "MEASURE_GAUSSIAN",
        K1K2 = "MEASURE_K1_K2",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `CurvatureColor`.
    pub struct CurvatureColorParams {
        /// which curvature the colour shows (k1_k2: the 2-D map)
        pub measure: Measure = Measure::Curvedness;
        /// k1_k2: a 2-D transfer function image (PNG, …); empty = the built-in map
        pub map: FilePath = "";
        /// k1_k2: |κ| at the map's edges, world units⁻¹
        pub range: f32 = 0.25, range(1e-9, 1e9);
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
                  the same units (TransferFunction1D with custom points, e.g. \"-2: …; 2: …\"); \
                  or, with measure `k1_k2`, both curvatures through a 2-D transfer function: \
                  the image `map` (x: κ1 from −`range` to `range`, y: κ2 from `range` at the \
                  top to −`range`), or without a map the built-in shape-class map (shape index \
                  cup blue, rut cyan, saddle green, ridge yellow, cap red; flat regions light). \
                  Transparent where there is no surface.",
            inputs: vec![
                PortSpec::input("curvature", PortType::Image, "Curvature's output"),
                PortSpec::optional(
                    "tf",
                    PortType::TransferFunction,
                    "measure → colour (all measures but k1_k2)",
                ),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "premultiplied colour",
            )],
            params: CurvatureColorParams::specs(),
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
        let params = CurvatureColorParams::read(p)?;
        let curvature = inputs.require("curvature")?.image("curvature")?.clone();
        let two_d = params.measure == Measure::K1K2;
        let (lut, domain) = if two_d {
            (ctx.blank_texture(), [0.0, 1.0])
        } else {
            let tf = match inputs
                .get("tf")
                .ok_or_else(|| {
                    NodeError::at_port(
                        "tf",
                        "not connected; every measure but k1_k2 needs a transfer function",
                    )
                })?
                .transfer_function("tf")?
                .as_ref()
            {
                TransferFunction::Color(f) => f.clone(),
                TransferFunction::Style { .. } => {
                    return Err(NodeError::at_port(
                        "tf",
                        "a style transfer function; CurvatureColor takes a colour transfer \
                         function",
                    ));
                }
                TransferFunction::TwoD(_) => {
                    return Err(NodeError::at_port(
                        "tf",
                        "a 2-D transfer function; CurvatureColor takes a 1-D colour transfer \
                         function",
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
            (lut, tf.domain)
        };
        let map = if !two_d {
            ctx.blank_texture()
        } else if params.map.is_blank() {
            ctx.cached("curvature_color.shape_map", |gpu| {
                Ok(gpu.texture_2d_init(
                    "shape map",
                    SHAPE_MAP_SIZE,
                    SHAPE_MAP_SIZE,
                    wgpu::TextureFormat::Rgba32Float,
                    bytemuck::cast_slice(&shape_map()),
                ))
            })
            .map_err(|e| NodeError::new(e.to_string()))?
            .as_ref()
            .clone()
        } else {
            ctx.file_texture(&params.map.resolved)
                .map_err(|e| NodeError::new(format!("param `map`: {e}")))?
        };
        let uniforms = CurvatureColorUniforms {
            measure: params.measure.code(),
            map_range: params.range,
            domain,
        };
        let size = (curvature.texture.width(), curvature.texture.height());
        let image = screen_pass::render(
            ctx,
            "curvature_color",
            IMAGE_FORMAT,
            size,
            &[&curvature.texture, &lut, &map],
            Some(bytemuck::bytes_of(&uniforms)),
        )
        .map_err(|e| NodeError::new(e.to_string()))?;
        Ok(vec![Value::Image(Arc::new(Image { texture: image }))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(CurvatureColorNode)
        .program("curvature_color", shaders::screen(shaders::part!("curvature_color.wgsl")))
        .uniform(CurvatureColorUniforms::layout())
        .gpu_enum(Measure::wgsl());
}
