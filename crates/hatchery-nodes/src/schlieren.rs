//! `Schlieren`: simulated Schlieren photographs and shadowgraphs of a volume (Svakhine, Ebert et
//! al. 2005, §4 "Photographic techniques", eq. 1–5): per pixel the ray integral of the density
//! gradient across the ray (the deflection ε, eq. 1) or of the Laplacian across the ray (the
//! shadowgraph's L, eq. 2), turned into intensity by a knife edge (eq. 3), a circular cutoff
//! (eq. 4), a colour wheel (colour Schlieren) or eq. 5. The rays are the shared ray casters'
//! (shaders/ray_common.wgsl: the camera's rays through the voxel → world transform, bricked
//! volumes, trilinear or B-spline reconstruction); the integral is shaders/schlieren.wgsl.

use crate::raycast::{
    Kernel, KernelChoice, RayBindings, RayOptions, RayPipelines, RayUniforms, Reconstruction,
    TableInfo,
};
use crate::value::Image;
use crate::{Ctx, Value};
use glam::Vec3;
use hatchery_gpu::GpuError;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `Schlieren` of shaders/schlieren.wgsl (its comments say what each field holds).
    pub struct SchlierenUniforms in "schlieren" as "Schlieren" {
        pub knife: [f32; 2],
        pub gain: f32,
        pub brightness: f32,
        /// A [`SchlierenMode`] code.
        pub mode: u32,
        pub threshold: f32,
        pub difference: f32,
        pub deflection_scale: f32,
        pub per_voxel_scale: f32,
        pub pad0: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

hatchery_graph::param_choice! {
    /// What the picture shows (§4): a Schlieren photograph through a knife edge (eq. 3), with a
    /// circular cutoff (eq. 4) or a colour filter (the colour-wheel Schlieren), or a shadowgraph
    /// (eq. 5), signed or as its absolute value (the paper's Fig. 13e).
    pub enum SchlierenMode {
        Schlieren = "schlieren",
        SchlierenCircular = "schlieren_circular",
        SchlierenColor = "schlieren_color",
        Shadowgraph = "shadowgraph",
        ShadowgraphAbs = "shadowgraph_abs",
    }
}

crate::wgsl_constants! {
    SchlierenMode in "schlieren" {
        Schlieren = "SCHLIEREN_KNIFE_EDGE",
        SchlierenCircular = "SCHLIEREN_CIRCULAR",
        SchlierenColor = "SCHLIEREN_COLOR",
        Shadowgraph = "SCHLIEREN_SHADOWGRAPH",
        ShadowgraphAbs = "SCHLIEREN_SHADOWGRAPH_ABS",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `Schlieren`.
    pub struct SchlierenParams {
        /// what the picture shows (§4): schlieren is the knife-edge photograph, grey plus or
        /// minus the deflection along the knife's normal (eq. 3); schlieren_circular the
        /// deflection's length through a circular cutoff (eq. 4); schlieren_color its
        /// direction as hue and length as saturation (colour Schlieren); shadowgraph grey plus
        /// or minus the Laplacian across the rays (eq. 2, 5); shadowgraph_abs its absolute
        /// value (Fig. 13e)
        pub mode: SchlierenMode = SchlierenMode::Schlieren;
        /// direction of the knife edge's normal k in the picture, degrees counter-clockwise
        /// from the picture's right: 0 brightens where the density grows to the right (a
        /// vertical knife edge), 90 where it grows upwards (eq. 3, §4)
        pub knife_angle: f32 = 0.0, range(-360.0, 360.0);
        /// sensitivity, the constant of eq. 1: how strongly a deflection of one value range
        /// of the volume (one voxel for the shadowgraph) shows (§4); negative turns the sign
        /// round (a real shadowgraph darkens where eq. 5 brightens: gain below 0)
        pub gain: f32 = 1.0, range(-10000.0, 10000.0);
        /// the coefficient s of eq. 3–5 that scales the whole picture: 1 gives a mid-grey
        /// background (§4)
        pub brightness: f32 = 1.0, range(0.0, 4.0);
        /// samples whose density gradient across the ray is below this (per voxel, as a
        /// fraction of the value range) add nothing: removes weak gradients (§4, Fig. 10b)
        pub threshold: f32 = 0.0, range(0.0, 1.0);
        /// distance between samples along the ray, voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// spacing of the central differences across the ray, voxels (of the smallest
        /// spacing): larger smooths the derivatives
        pub difference: f32 = 1.0, range(0.25, 8.0);
        /// reconstruction of the data between voxels: trilinear, or the tricubic B-spline
        /// (smoother derivatives, Hadwiger §1.3)
        pub reconstruction: Reconstruction = Reconstruction::Trilinear;
        /// GPU path: fragment shader or compute kernel (same picture)
        pub kernel: KernelChoice = KernelChoice::Auto;
    }
}

pub struct SchlierenNode;

impl Node<Value, Ctx> for SchlierenNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Schlieren",
            category: "Volume",
            doc: "Simulated Schlieren photographs and shadowgraphs of a density volume \
                  (Svakhine, Ebert et al. 2005, §4, eq. 1–5). Each ray integrates over the \
                  volume the density gradient across the ray along the picture's x and y axes, \
                  the light's deflection ε = (∫∂ρ/∂x dz, ∫∂ρ/∂y dz) (eq. 1), and the Laplacian \
                  across the ray, L = ∫(∂²ρ/∂x² + ∂²ρ/∂y²) dz (eq. 2), by central differences \
                  at ±`difference` voxels; ε is measured in value ranges of the volume, L in \
                  value ranges per voxel. Intensity: s(1 + g ε·k)/2 with k the knife edge's \
                  normal (eq. 3), s g|ε| (eq. 4), a colour wheel (hue the direction of ε, \
                  saturation g|ε|), or s(1 + g L)/2 (eq. 5), clamped to [0, 1]; g is `gain`, s \
                  `brightness`.",
            inputs: vec![
                PortSpec::input(
                    "volume",
                    PortType::Volume,
                    "the density (refractive index) field",
                ),
                PortSpec::input(
                    "camera",
                    PortType::Camera,
                    "the view (the light runs along its rays)",
                ),
            ],
            outputs: vec![
                PortSpec::output("image", PortType::Image, "the photograph (opaque)"),
                PortSpec::output(
                    "deflection",
                    PortType::Image,
                    "data, not colour: (ε_x, ε_y, L, 1) per pixel before the gain (x right, \
                     y up)",
                ),
            ],
            params: SchlierenParams::specs(),
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
        let params = SchlierenParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let err = |e: GpuError| NodeError::new(e.to_string());
        // The level of detail the device holds (see `Volume::resident`).
        let volume = volume.resident(&ctx.gpu).map_err(err)?;
        let v = &volume.data;
        let kernel = Kernel::choose(params.kernel, &ctx.gpu);
        let reconstruction = params.reconstruction.on(ctx, v);
        let options = RayOptions {
            reconstruction,
            ..RayOptions::plain(params.step, false, 1.0, Vec3::Z, kernel)
        };
        let bricked = volume.texture(&ctx.gpu).map_err(err)?.layout.is_some();
        let orthographic = camera.orthographic;
        // Bricking, projection and reconstruction as constants (shaders/ray_common.wgsl).
        let pipelines = ctx
            .cached(
                &format!(
                    "schlieren.pipelines.{bricked}.{orthographic}.{}",
                    reconstruction.code()
                ),
                |gpu| {
                    let constants = [
                        ("RAY_BRICKED", bricked.into()),
                        ("RAY_ORTHOGRAPHIC", orthographic.into()),
                        reconstruction.constant(),
                    ];
                    RayPipelines::specialised(gpu, "schlieren", &constants)
                },
            )
            .map_err(err)?;
        let sampler = crate::raycast::linear_clamp_sampler(ctx).map_err(err)?;
        let gpu = &ctx.gpu;
        let texture = volume.texture(gpu).map_err(err)?;
        let ray = RayUniforms::new(
            &camera,
            v,
            &options,
            &TableInfo::plain(),
            1.0,
            texture.texel_range,
        )
        .with_bricks(texture.layout.as_ref());
        let min_spacing = v.spacing().iter().copied().fold(f32::INFINITY, f32::min);
        let range = v.value_range[1] - v.value_range[0];
        let range = if range.is_finite() && range > 0.0 {
            range
        } else {
            1.0
        };
        let angle = params.knife_angle.to_radians();
        let uniforms = SchlierenUniforms {
            knife: [angle.cos(), angle.sin()],
            gain: params.gain,
            brightness: params.brightness,
            mode: params.mode.code(),
            threshold: params.threshold,
            difference: params.difference * min_spacing,
            deflection_scale: 1.0 / range,
            per_voxel_scale: min_spacing / range,
            pad0: 0.0,
            pad1: 0.0,
            pad2: 0.0,
        };
        let uniform =
            |label, bytes: &[u8]| gpu.buffer_init(label, bytes, wgpu::BufferUsages::UNIFORM);
        let ray_buffer = uniform("schlieren ray", bytemuck::bytes_of(&ray));
        let schlieren_buffer = uniform("schlieren", bytemuck::bytes_of(&uniforms));
        let volume_view = texture.texture.create_view(&Default::default());
        let page_view = texture.page_table.create_view(&Default::default());
        let shared = RayBindings {
            ray: Some(&ray_buffer),
            volume: Some(&volume_view),
            linear_clamp: Some(&sampler),
            page_table: Some(&page_view),
            ..Default::default()
        };
        let own = SchlierenBindings {
            schlieren: Some(&schlieren_buffer),
        };
        let (image, gbuffer) =
            pipelines.run(ctx, &camera, [shared.entries(), own.entries()], kernel)?;
        Ok(vec![
            Value::Image(Arc::new(Image { texture: image })),
            Value::Image(Arc::new(Image {
                texture: gbuffer.normal,
            })),
        ])
    }
}

crate::bind_group! {
    /// Schlieren's own group (shaders/schlieren.wgsl).
    pub struct SchlierenBindings in "schlieren", group 1 from 0 {
        pub schlieren: Buffer,
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(SchlierenNode)
        .program(
            "schlieren",
            shaders::ray_sampling(shaders::part!("schlieren.wgsl")),
        )
        .uniform(SchlierenUniforms::layout())
        .bind_group(SchlierenBindings::layout())
        .bind_group_in("schlieren", crate::raycast::RayBindings::layout())
        .bind_group_in("schlieren", crate::raycast::RayOutputs::layout())
        .gpu_enum(SchlierenMode::wgsl())
        .uniform_in("schlieren", crate::raycast::RayUniforms::layout());
}
