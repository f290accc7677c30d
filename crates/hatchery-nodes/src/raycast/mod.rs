//! `Raycast` (here) and `IsoSurfaceRaycast` (iso_surface_raycast.rs): GPU volume ray casting.
//! The parts, shared with the two-level ray caster: `uniforms` (the `Ray` block), `tables` (classification, lighting and
//! skipping tables), `pass` (pipeline and draw); in WGSL, shaders/ray_common.wgsl (sampling,
//! primary rays), ray_classify, ray_shade, ray_skip, and raycast.wgsl's compositing loop.

mod bindings;
mod enhancement;
mod importance_pass;
mod iso_surface_raycast;
pub mod objects;
mod pass;
mod tables;
mod uniforms;

pub use crate::kernel::{Kernel, KernelChoice};
pub use crate::reconstruction::Reconstruction;
pub use bindings::{RayBindings, RayOutputs, StrokeBindings};
pub use enhancement::{
    EnhanceBit, EnhanceField, Enhancement, EnhancementField, EnhancementParams,
    EnhancementUniforms, Tf2dAxis,
};
pub(crate) use importance_pass::PingPong;
pub use importance_pass::{ImportanceBindings, ImportancePipelines, PassUniforms};
pub use iso_surface_raycast::{IsoSurfaceRaycastNode, IsoSurfaceRaycastParams};
pub use pass::{RayPipelines, StrokeUniforms, Strokes, cast};
pub use tables::{check_grid_at, check_same_grid};
pub use uniforms::{Grid, RayMode, RayShading, RayUniforms, TableInfo};

use crate::camera::Camera;
use crate::value::{Image, TransferFunction, Volume};
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_graph::{
    DataValue, Group, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// What one ray-casting pass needs besides the volume and the camera.
pub struct RayOptions<'a> {
    pub mode: RayMode,
    pub iso: f32,
    pub step_voxels: f32,
    pub shading: RayShading,
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
    /// How values and gradients are reconstructed between voxels (Hadwiger §1.3).
    pub reconstruction: Reconstruction,
    /// DVR with a pre-integrated transfer function (Engel et al. 2001): each sample composites
    /// the segment from the previous sample (`hatchery_data::preintegration`).
    pub preintegrated: bool,
    /// Svakhine et al. 2005's Table 1 enhancements (Raycast, DVR; off for the other casters).
    pub enhancement: Enhancement,
    /// A second scalar field on the volume's grid (Raycast's `second`): a 2-D transfer
    /// function's second_field axis, or the gradient enhancement measures.
    pub second_field: Option<&'a Volume>,
    /// A vector field on the volume's grid (Raycast's `vector`) enhancement may measure.
    pub vector_field: Option<&'a crate::value::vector_field::VectorField>,
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
            mode: RayMode::Dvr,
            iso: 0.0,
            step_voxels,
            shading: RayShading::None,
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
            reconstruction: Reconstruction::Trilinear,
            preintegrated: false,
            enhancement: Enhancement::OFF,
            second_field: None,
            vector_field: None,
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

hatchery_graph::node_params! {
    /// The Blinn–Phong parameters of eq. 3 (c_a, c_d, c_s, c_e), shared by the ray casters.
    pub struct PhongParams {
        /// ambient light: brightness of every shaded sample, lit or not (c_a of eq. 3)
        pub ambient: f32 = 0.15, range(0.0, 1.0);
        /// diffuse light: brightness where the surface faces the light (c_d of eq. 3)
        pub diffuse: f32 = 0.85, range(0.0, 4.0);
        /// specular light: strength of the highlight (c_s of eq. 3)
        pub specular: f32 = 0.4, range(0.0, 4.0);
        /// shininess: higher makes the highlight smaller and sharper (c_e of eq. 3)
        pub exponent: f32 = 32.0, range(1.0, 512.0);
    }
}

impl PhongParams {
    /// (c_a, c_d, c_s, c_e), the order of the `Ray` block's `phong`.
    pub fn values(&self) -> [f32; 4] {
        [self.ambient, self.diffuse, self.specular, self.exponent]
    }
}

/// The view-space direction towards the light: the `light` input's, else a headlight.
pub fn light_direction(inputs: &NodeInputs<Value>, camera: &Camera) -> Result<Vec3, NodeError> {
    Ok(match inputs.get("light") {
        Some(light) => light.light("light")?.view_direction(camera),
        None => Vec3::new(0.3, 0.4, 1.0).normalize(),
    })
}

hatchery_graph::param_choice! {
    /// Compositing.
    pub enum Mode { Dvr = "dvr", Mip = "mip", Iso = "iso" }
}

hatchery_graph::param_choice! {
    /// Shading (style TFs always use their styles).
    pub enum Shading {
        None = "none",
        Phong = "phong",
        Lighting = "lighting",
        ContextPreserving = "context_preserving",
    }
}

hatchery_graph::param_choice! {
    /// Lighting transfer function for `lighting`.
    pub enum LightingModel {
        Phong = "phong",
        PhongContour = "phong_contour",
        Cartoon = "cartoon",
        Metal = "metal",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `Raycast`.
    pub struct RaycastParams {
        /// how the samples along a ray make the pixel: dvr (composited front to back), mip (the
        /// largest value) or iso (the first surface at the iso value)
        pub mode: Mode = Mode::Dvr;
        /// iso value for mode iso (data units, or "percentile(P)", "range(F)", "otsu")
        pub iso: DataValue = 0.5, range(-1e12, 1e12);
        /// sample distance in voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// shading (style TFs always use their styles)
        pub shading: Shading = Shading::Phong;
        /// lighting transfer function for `lighting`
        pub lighting_model: LightingModel = LightingModel::PhongContour;
        pub phong: PhongParams = Group;
        /// how deep to look inside: more shows more of the interior through weakly lit, flat
        /// regions (κt of eq. 5; 0 = plain DVR)
        pub kappa_t: f32 = 0.0, range(0.0, 1000.0);
        /// how sharply the view into the interior starts (κs of eq. 5)
        pub kappa_s: f32 = 0.5, range(0.0, 100.0);
        /// context_preserving: Schlick's rational approximation of eq. 5's two exponentiations (the
        /// paper's §6, eq. 6–7) instead of pow
        pub fast_exponent: bool = false;
        /// draw dark contour lines where the surface turns away from the viewer (§3.3)
        pub contours: bool = true;
        /// contour thickness T, world units
        pub thickness: f32 = 2.0, range(0.0, 1000.0);
        /// see-through styles: a style's opacity falls where it faces the viewer, so inner
        /// structures show (eq. 2)
        pub transparency: bool = true;
        /// bias of the style mip level
        pub mip_bias: f32 = 0.0, range(-4.0, 8.0);
        /// jitter the first sample per pixel (hides wood-grain artefacts)
        pub jitter: bool = true;
        /// reconstruction between voxels: trilinear (fast), or the tricubic B-spline's values
        /// and gradients (no voxel lattice on sharp boundaries; about 4× the fetches)
        pub reconstruction: Reconstruction = Reconstruction::Trilinear;
        /// DVR: a pre-integrated transfer function (Engel et al. 2001) — each sample composites
        /// the whole segment from the previous one, so sharp opacity ramps between samples are
        /// not missed (a 1-D colour transfer function, shading none or phong)
        pub preintegrated: bool = false;
        pub enhancement: EnhancementParams = Group;
        /// global alpha ρ (Yuan & Chen §5): every sample's opacity × ρ (DVR), so embedded strokes
        /// show through
        pub rho: f32 = 1.0, range(0.0, 1.0);
        /// colour of embedded strokes
        pub stroke_color: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// stop a ray at this opacity (1 = never)
        pub early_termination: f32 = 0.99, range(0.5, 1.0);
        /// accumulated opacity that defines the G-buffer depth
        pub hit_opacity: f32 = 0.5, range(0.001, 1.0);
        /// jump over 8³-voxel bricks that cannot change the picture (DVR: values the transfer
        /// function makes transparent; iso: all below the iso value) — same picture, fewer samples.
        /// MIP never skips: its plain loop is faster
        pub skip_empty: bool = true;
        /// GPU path: fragment shader or compute kernel (same picture); auto picks the faster one
        /// for the adapter
        pub kernel: KernelChoice = KernelChoice::Auto;
    }
}

pub struct RaycastNode;

impl Node<Value, Ctx> for RaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Raycast",
            category: "Volume",
            doc: "GPU ray casting of a volume. Front-to-back compositing (eq. 1 of the context-preserving \
                  paper) with opacity correction for the sample distance, early ray termination, \
                  jittered start, trilinear sampling with gradients by central differences in voxel space \
                  (respecting spacing) or tricubic B-spline values and gradients (Hadwiger §1.3); \
                  perspective or orthographic. Modes: dvr, mip (maximum \
                  intensity), iso (first hit, refined linearly). Shading: none, phong (eq. 3), lighting \
                  (VolumeShop lighting transfer function, eq. 8), context_preserving (eq. 5; κt = 0 is \
                  plain DVR). A StyleTransferFunction on `tf` switches to style shading (Bruckner & \
                  Gröller 2007: lit spheres, style contours eq. 1, illustrative transparency eq. 2). \
                  Strokes (a mask with the depth of its surface) are embedded as Yuan & Chen \
                  2005 §5 do: rays stop at a stroke and its colour lies under what is in front; \
                  `rho` scales every sample's opacity (DVR). Svakhine et al. 2005's Table 1 \
                  enhancements of each sample's opacity (DVR): boundary enhancement |∇P|^n, \
                  silhouette enhancement (1 − |∇P̂·V|)^n and the banding widget \
                  ((1 + sin(o·π·m)) / 2)^n, measuring the rendered field, a second field's \
                  gradient (`second`) or a vector field U (`vector`: |U|^n, (1 − |Û·V|)^n); a \
                  2-D transfer function over value × gradient magnitude, Laplacian or the second \
                  field (docs/enhancement.md).",
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
                    "second",
                    PortType::Volume,
                    "a second scalar field on the same grid (Svakhine et al. 2005 §3.2–3.3): a \
                     2-D transfer function's second_field axis, or enhancement_field second",
                ),
                PortSpec::optional(
                    "vector",
                    PortType::VectorField,
                    "a vector field on the same grid, for enhancement_field vector (Table 1's U)",
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
            params: RaycastParams::specs(),
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
        let params = RaycastParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let tf = inputs.require("tf")?.transfer_function("tf")?.clone();
        let second = inputs.get("second").map(|v| v.volume("second")).transpose()?;
        let vector = inputs.get("vector").map(|v| v.vector_field("vector")).transpose()?;
        let options = RayOptions {
            mode: params.mode.into(),
            iso: crate::relative::data_value(ctx, "iso", params.iso, &volume.data)?,
            step_voxels: params.step,
            shading: params.shading.into(),
            lighting_model: params.lighting_model.name(),
            phong: params.phong.values(),
            kappa: [params.kappa_t, params.kappa_s],
            contours: params.contours,
            thickness: params.thickness,
            transparency: params.transparency,
            mip_bias: params.mip_bias,
            jitter: params.jitter,
            early_termination: params.early_termination,
            skip_empty: params.skip_empty,
            kernel: Kernel::choose(params.kernel, &ctx.gpu),
            hit_opacity: params.hit_opacity,
            light_view: light_direction(inputs, &camera)?,
            rho: params.rho,
            embed: false,
            fast_exponent: params.fast_exponent,
            reconstruction: params.reconstruction.on(ctx, &volume.data),
            preintegrated: params.preintegrated,
            enhancement: params.enhancement.enhancement(),
            second_field: second.map(|v| v.as_ref()),
            vector_field: vector.map(|v| v.as_ref()),
        };
        let labels = inputs
            .get("labels")
            .map(|l| l.volume("labels").cloned())
            .transpose()?;
        if matches!(tf.as_ref(), TransferFunction::TwoD(_)) && options.mode != RayMode::Dvr {
            return Err(NodeError::at_port(
                "tf",
                "a 2-D transfer function classifies DVR samples only: use mode dvr, or a 1-D \
                 transfer function for mip and iso",
            ));
        }
        if options.preintegrated {
            let plain_tf = matches!(tf.as_ref(), TransferFunction::Color(_));
            let shading = matches!(options.shading, RayShading::None | RayShading::Phong);
            if options.mode != RayMode::Dvr || !plain_tf || !shading || labels.is_some() {
                return Err(NodeError::new(
                    "parameter `preintegrated`: pre-integration needs mode dvr, a 1-D colour \
                     transfer function, no label volume and shading none or phong",
                ));
            }
            if options.enhancement.any() {
                return Err(NodeError::new(
                    "parameters `boundary_enhancement`, `silhouette_enhancement`, `banding`: the \
                     enhancements modulate each sample's own opacity, which a pre-integrated \
                     segment does not have: turn `preintegrated` off or the enhancements to 0",
                ));
            }
        }
        let strokes = match (inputs.get("strokes"), inputs.get("strokes_depth")) {
            (Some(m), Some(g)) => Some(Strokes {
                mask: m.mask("strokes")?.clone(),
                depth: g.gbuffer("strokes_depth")?.clone(),
                color: params.stroke_color,
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

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    iso_surface_raycast::declare(k);
    k.node(RaycastNode)
        .program("raycast", shaders::ray(shaders::part!("raycast.wgsl")))
        .program(
            "depth_from_texture",
            shaders::screen(shaders::part!("depth_from_texture.wgsl")),
        )
        .uniform(RayUniforms::layout())
        .bind_group(RayBindings::layout())
        .bind_group(StrokeBindings::layout())
        .bind_group(RayOutputs::layout())
        .uniform(StrokeUniforms::layout())
        .uniform(EnhancementUniforms::layout())
        .gpu_enum(EnhanceBit::wgsl())
        .gpu_enum(Tf2dAxis::wgsl())
        .gpu_enum(RayMode::wgsl())
        .gpu_enum(RayShading::wgsl());
}

#[cfg(test)]
mod tests {
    use super::LightingModel;

    #[test]
    fn lighting_models_match_the_data_crates_tables() {
        assert_eq!(
            LightingModel::NAMES,
            hatchery_data::lighting::LIGHTING_MODELS
        );
    }
}
