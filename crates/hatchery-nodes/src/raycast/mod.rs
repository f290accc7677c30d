//! `Raycast` and `IsoSurfaceRaycast`: GPU volume ray casting. The parts, shared with the
//! two-level ray caster: `uniforms` (the `Ray` block), `tables` (classification, lighting and
//! skipping tables), `pass` (pipeline and draw); in WGSL, shaders/ray_common.wgsl (sampling,
//! primary rays), ray_classify, ray_shade, ray_skip, and raycast.wgsl's compositing loop.

mod pass;
mod tables;
mod uniforms;

pub use pass::{RayPipelines, StrokeUniforms, Strokes, cast};
pub use tables::check_same_grid;
pub use uniforms::{Grid, RayUniforms, TableInfo};

use crate::camera::Camera;
use crate::value::Image;
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_data::lighting;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

const MODES: &[&str] = &["dvr", "mip", "iso"];
const SHADINGS: &[&str] = &["none", "phong", "lighting", "context_preserving"];

/// What one ray-casting pass needs besides the volume and the camera.
pub struct RayOptions<'a> {
    pub mode: usize,
    pub iso: f32,
    pub step_voxels: f32,
    pub shading: usize,
    pub lighting_model: &'a str,
    pub phong: [f32; 4],
    pub kappa: [f32; 2],
    pub contours: bool,
    pub thickness: f32,
    pub transparency: bool,
    pub mip_bias: f32,
    pub jitter: bool,
    pub early_termination: f32,
    pub hit_opacity: f32,
    pub light_view: Vec3,
    /// Jump over bricks no visible value can be sampled in (DVR; the picture is unchanged).
    pub skip_empty: bool,
    /// Which GPU path runs the rays (the same rays and picture either way).
    pub kernel: Kernel,
    /// Global alpha ρ: every sample's opacity × ρ before the step correction (DVR).
    pub rho: f32,
    /// Whether strokes are embedded (`cast`'s `strokes`).
    pub embed: bool,
    /// Context-preserving: Schlick's approximation of eq. 5's exponentiations (§6, eq. 6–7).
    pub fast_exponent: bool,
}

impl RayOptions<'static> {
    /// DVR options for ray casters that classify and shade on their own (TwoLevelRaycast,
    /// ImportanceCompositing, SelectionRender): no shading, contours or skipping in the shared
    /// uniform block.
    pub fn plain(
        step_voxels: f32,
        jitter: bool,
        early_termination: f32,
        light_view: Vec3,
        kernel: Kernel,
    ) -> Self {
        Self {
            mode: 0,
            iso: 0.0,
            step_voxels,
            shading: 0,
            lighting_model: "phong",
            phong: [0.0; 4],
            kappa: [0.0, 0.0],
            contours: false,
            thickness: 0.0,
            transparency: false,
            mip_bias: 0.0,
            jitter,
            early_termination,
            hit_opacity: 0.5,
            light_view,
            skip_empty: false,
            kernel,
            rho: 1.0,
            embed: false,
            fast_exponent: false,
        }
    }
}

/// The trilinear, clamp-to-edge sampler of the ray casters' volumes, made once per device.
pub fn linear_clamp_sampler(ctx: &mut Ctx) -> Result<Arc<wgpu::Sampler>, hatchery_gpu::GpuError> {
    ctx.cached("ray.linear_clamp", |gpu| {
        Ok(gpu.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("linear clamp"),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        }))
    })
}

/// The GPU path of a ray-casting pass: a full-screen fragment shader, or a compute kernel over
/// 8×8-pixel tiles. Same rays, same samples, same picture (tests/raycast.rs compares them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    Fragment,
    Compute,
}

pub const KERNELS: &[&str] = &["auto", "fragment", "compute"];

impl Kernel {
    /// The path for parameter value `name` on `gpu`. `auto` picks the fragment path, the faster
    /// one measured on lavapipe, except on adapters whose graphics pipeline runs on part of the
    /// chip only (NVIDIA's H100/H200 compute parts), where compute is many times faster
    /// (docs/benchmarks.md).
    pub fn choose(name: &str, gpu: &hatchery_gpu::GpuContext) -> Kernel {
        match name {
            "fragment" => Kernel::Fragment,
            "compute" => Kernel::Compute,
            _ if gpu.is_compute_part() => Kernel::Compute,
            _ => Kernel::Fragment,
        }
    }
}

/// The Blinn–Phong parameters of eq. 3 (c_a, c_d, c_s, c_e), shared by the ray casters.
pub fn phong_params() -> [ParamSpec; 4] {
    [
        ParamSpec::float("ambient", 0.15, 0.0, 1.0, "c_a of eq. 3"),
        ParamSpec::float("diffuse", 0.85, 0.0, 4.0, "c_d of eq. 3"),
        ParamSpec::float("specular", 0.4, 0.0, 4.0, "c_s of eq. 3"),
        ParamSpec::float("exponent", 32.0, 1.0, 512.0, "c_e of eq. 3"),
    ]
}

/// The values of [`phong_params`].
pub fn phong_values(p: &Params) -> [f32; 4] {
    [
        p.f32("ambient"),
        p.f32("diffuse"),
        p.f32("specular"),
        p.f32("exponent"),
    ]
}

/// The view-space direction towards the light: the `light` input's, else a headlight.
pub fn light_direction(inputs: &NodeInputs<Value>, camera: &Camera) -> Result<Vec3, NodeError> {
    Ok(match inputs.get("light") {
        Some(light) => light.light("light")?.view_direction(camera),
        None => Vec3::new(0.3, 0.4, 1.0).normalize(),
    })
}

pub struct RaycastNode;

impl Node<Value, Ctx> for RaycastNode {
    fn schema(&self) -> NodeSchema {
        let [ambient, diffuse, specular, exponent] = phong_params();
        NodeSchema {
            kind: "Raycast",
            category: "Volume",
            doc: "GPU ray casting of a volume. Front-to-back compositing (eq. 1 of the context-preserving \
                  paper) with opacity correction for the sample distance, early ray termination, \
                  jittered start, trilinear sampling, gradients by central differences in voxel space \
                  (respecting spacing); perspective or orthographic. Modes: dvr, mip (maximum \
                  intensity), iso (first hit, refined linearly). Shading: none, phong (eq. 3), lighting \
                  (VolumeShop lighting transfer function, eq. 8), context_preserving (eq. 5; κt = 0 is \
                  plain DVR). A StyleTransferFunction on `tf` switches to style shading (Bruckner & \
                  Gröller 2007: lit spheres, style contours eq. 1, illustrative transparency eq. 2). \
                  Strokes (a mask with the depth of its surface) are embedded as Yuan & Chen \
                  2005 §5 do: rays stop at a stroke and its colour lies under what is in front; \
                  `rho` scales every sample's opacity (DVR).",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input(
                    "tf",
                    PortType::TransferFunction,
                    "colour/opacity or style transfer function",
                ),
                PortSpec::optional("light", PortType::Light, "the light (default: a headlight)"),
                PortSpec::optional(
                    "labels",
                    PortType::Volume,
                    "object labels on the same grid (per-label style rows, §4.2)",
                ),
                PortSpec::optional(
                    "strokes",
                    PortType::Mask,
                    "lines or strokes to embed (Yuan & Chen §5), with `strokes_depth`",
                ),
                PortSpec::optional(
                    "strokes_depth",
                    PortType::GBuffer,
                    "the depth of the surface the strokes were drawn on",
                ),
            ],
            outputs: vec![
                PortSpec::output("image", PortType::Image, "premultiplied colour"),
                PortSpec::output(
                    "gbuffer",
                    PortType::GBuffer,
                    "depth and normal where opacity first reaches `hit_opacity`",
                ),
            ],
            params: vec![
                ParamSpec::choice("mode", "dvr", MODES, "compositing"),
                ParamSpec::float(
                    "iso",
                    0.5,
                    -1e12,
                    1e12,
                    "iso value for mode iso (data units, or \"percentile(P)\", \"range(F)\", \"otsu\")",
                )
                .relative(),
                ParamSpec::float(
                    "step",
                    0.5,
                    0.05,
                    8.0,
                    "sample distance in voxels (of the smallest spacing)",
                ),
                ParamSpec::choice(
                    "shading",
                    "phong",
                    SHADINGS,
                    "shading (style TFs always use their styles)",
                ),
                ParamSpec::choice(
                    "lighting_model",
                    "phong_contour",
                    lighting::LIGHTING_MODELS,
                    "lighting transfer function for `lighting`",
                ),
                ambient,
                diffuse,
                specular,
                exponent,
                ParamSpec::float(
                    "kappa_t",
                    0.0,
                    0.0,
                    1000.0,
                    "κt of eq. 5: how deep to look inside (0 = plain DVR)",
                ),
                ParamSpec::float(
                    "kappa_s",
                    0.5,
                    0.0,
                    100.0,
                    "κs of eq. 5: sharpness of the cut",
                ),
                ParamSpec::bool(
                    "fast_exponent",
                    false,
                    "context_preserving: Schlick's rational approximation of eq. 5's two \
                     exponentiations (the paper's §6, eq. 6–7) instead of pow",
                ),
                ParamSpec::bool("contours", true, "style contours (§3.3)"),
                ParamSpec::float(
                    "thickness",
                    2.0,
                    0.0,
                    1000.0,
                    "contour thickness T, world units",
                ),
                ParamSpec::bool(
                    "transparency",
                    true,
                    "illustrative transparency (eq. 2) for styles",
                ),
                ParamSpec::float("mip_bias", 0.0, -4.0, 8.0, "bias of the style mip level"),
                ParamSpec::bool(
                    "jitter",
                    true,
                    "jitter the first sample per pixel (hides wood-grain artefacts)",
                ),
                ParamSpec::float(
                    "rho",
                    1.0,
                    0.0,
                    1.0,
                    "global alpha ρ (Yuan & Chen §5): every sample's opacity × ρ (DVR), so \
                     embedded strokes show through",
                ),
                ParamSpec::color(
                    "stroke_color",
                    [0.0, 0.0, 0.0, 1.0],
                    "colour of embedded strokes",
                ),
                ParamSpec::float(
                    "early_termination",
                    0.99,
                    0.5,
                    1.0,
                    "stop a ray at this opacity (1 = never)",
                ),
                ParamSpec::float(
                    "hit_opacity",
                    0.5,
                    0.001,
                    1.0,
                    "accumulated opacity that defines the G-buffer depth",
                ),
                ParamSpec::bool(
                    "skip_empty",
                    true,
                    "jump over 8³-voxel bricks that cannot change the picture (DVR: values the \
                     transfer function makes transparent; iso: all below the iso value) — same \
                     picture, fewer samples. MIP never skips: its plain loop is faster",
                ),
                ParamSpec::choice(
                    "kernel",
                    "auto",
                    KERNELS,
                    "GPU path: fragment shader or compute kernel (same picture); auto picks \
                     the faster one for the adapter",
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
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let tf = inputs.require("tf")?.transfer_function("tf")?.clone();
        let options = RayOptions {
            mode: MODES
                .iter()
                .position(|m| *m == p.choice("mode"))
                .unwrap_or(0),
            iso: crate::relative::data_value(ctx, p, "iso", &volume.data)?,
            step_voxels: p.f32("step"),
            shading: SHADINGS
                .iter()
                .position(|s| *s == p.choice("shading"))
                .unwrap_or(0),
            lighting_model: p.choice("lighting_model"),
            phong: phong_values(p),
            kappa: [p.f32("kappa_t"), p.f32("kappa_s")],
            contours: p.bool("contours"),
            thickness: p.f32("thickness"),
            transparency: p.bool("transparency"),
            mip_bias: p.f32("mip_bias"),
            jitter: p.bool("jitter"),
            early_termination: p.f32("early_termination"),
            skip_empty: p.bool("skip_empty"),
            kernel: Kernel::choose(p.choice("kernel"), &ctx.gpu),
            hit_opacity: p.f32("hit_opacity"),
            light_view: light_direction(inputs, &camera)?,
            rho: p.f32("rho"),
            embed: false,
            fast_exponent: p.bool("fast_exponent"),
        };
        let labels = inputs
            .get("labels")
            .map(|l| l.volume("labels").cloned())
            .transpose()?;
        let strokes = match (inputs.get("strokes"), inputs.get("strokes_depth")) {
            (Some(m), Some(g)) => Some(Strokes {
                mask: m.mask("strokes")?.clone(),
                depth: g.gbuffer("strokes_depth")?.clone(),
                color: p.color("stroke_color"),
            }),
            (None, None) => None,
            (Some(_), None) => {
                return Err(NodeError::at_port(
                    "strokes_depth",
                    "embedded strokes need the depth of their surface (a G-buffer)",
                ));
            }
            (None, Some(_)) => {
                return Err(NodeError::at_port(
                    "strokes",
                    "a stroke depth without strokes: connect the stroke mask",
                ));
            }
        };
        let options = RayOptions {
            embed: strokes.is_some(),
            ..options
        };
        let (image, gbuffer) = cast(
            ctx,
            &volume,
            &camera,
            Some(&tf),
            labels.as_deref(),
            strokes.as_ref(),
            &options,
        )?;
        Ok(vec![
            Value::Image(Arc::new(Image { texture: image })),
            Value::GBuffer(Arc::new(gbuffer)),
        ])
    }
}

pub struct IsoSurfaceRaycastNode;

impl Node<Value, Ctx> for IsoSurfaceRaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "IsoSurfaceRaycast",
            category: "Volume",
            doc: "First hit of an iso value along each ray (refined linearly between samples) as a \
                  G-buffer: window depth and the view-space normal −∇f/|∇f|. Feeds Silhouette, \
                  DiffuseIntensity, Halftone and the compositing nodes with no mesh at all.",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![PortSpec::output(
                "gbuffer",
                PortType::GBuffer,
                "depth + normal of the iso-surface",
            )],
            params: vec![
                crate::relative::iso_param(),
                ParamSpec::float("step", 0.25, 0.05, 8.0, "sample distance in voxels"),
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
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let options = RayOptions {
            mode: 2,
            iso: crate::relative::data_value(ctx, p, "iso", &volume.data)?,
            step_voxels: p.f32("step"),
            shading: 0,
            lighting_model: "phong",
            phong: [0.0, 1.0, 0.0, 1.0],
            kappa: [0.0, 0.0],
            contours: false,
            thickness: 0.0,
            transparency: false,
            mip_bias: 0.0,
            jitter: false,
            early_termination: 1.0,
            hit_opacity: 1.0,
            light_view: Vec3::Z,
            skip_empty: true,
            kernel: Kernel::choose("auto", &ctx.gpu),
            rho: 1.0,
            embed: false,
            fast_exponent: false,
        };
        let (_, gbuffer) = cast(ctx, &volume, &camera, None, None, None, &options)?;
        Ok(vec![Value::GBuffer(Arc::new(gbuffer))])
    }
}
