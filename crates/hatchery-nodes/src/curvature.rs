//! `Curvature`: principal curvatures and directions of the iso-surface in a G-buffer, from the
//! volume's gradient and Hessian (Hadwiger's deferred iso-surface shading, the tutorial's §1;
//! see shaders/curvature.wgsl for the rule and the output's channels).

use crate::raycast::{Kernel, RayBindings, RayOptions, RayUniforms, TableInfo, linear_clamp_sampler};
pub use crate::reconstruction::Reconstruction;
use crate::screen_pass;
use crate::value::Image;
use crate::{Ctx, Value};
use hatchery_gpu::GpuError;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `CurvatureParams` of shaders/curvature_common.wgsl: the finite-difference step h in
    /// world units.
    pub struct CurvatureUniforms in "curvature" as "CurvatureParams" {
        pub step: f32,
        pub pad0: f32,
        pub pad1: f32,
        pub pad2: f32,
    }
}

/// The curvature image's format: data, not colour, so full float precision (RidgeValley's
/// extremality test compares neighbouring pixels' curvatures).
pub const CURVATURE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// θ of a pixel without a surface (outside [−π/2, π/2)): shaders test θ1 < −5.
pub const NO_SURFACE: f32 = -10.0;

hatchery_graph::node_params! {
    /// The parameters of `Curvature`.
    pub struct CurvatureParams {
        /// finite-difference step of the Hessian, voxels (of the smallest spacing)
        pub step: f32 = 1.0, range(0.25, 8.0);
        /// reconstruction: trilinear with the Hessian by central differences of the gradient at
        /// ±`step`, or the tricubic B-spline's own gradient and second derivatives (Hadwiger
        /// §1.3; `step` unused)
        pub reconstruction: Reconstruction = Reconstruction::Trilinear;
    }
}

pub struct CurvatureNode;

impl Node<Value, Ctx> for CurvatureNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Curvature",
            category: "Volume",
            doc: "Principal curvatures of the iso-surface in a G-buffer (Hadwiger's deferred \
                  iso-surface shading, the tutorial's §1): at each pixel's surface point the \
                  volume's gradient g and Hessian H (central differences of the gradient at \
                  ±`step` voxels along the world axes, or the tricubic B-spline's own second \
                  derivatives with reconstruction bspline), the shape operator −P H P / |g| in the \
                  tangent plane, its eigenvalues κ1 ≥ κ2 (world units⁻¹, positive where the \
                  surface bulges towards lower values) and the first principal direction. \
                  Output image channels (32-bit float data): (κ1, κ2, θ1, θ2) with θ1, θ2 the \
                  principal directions' screen angles (radians, x right, y down, in \
                  [−π/2, π/2)); θ1 = θ2 = −10 where there is no surface. Connect the G-buffer \
                  of IsoSurfaceRaycast (or Raycast, mode iso) over the same volume.",
            inputs: vec![
                PortSpec::input("gbuffer", PortType::GBuffer, "the iso-surface's depth"),
                PortSpec::input(
                    "volume",
                    PortType::Volume,
                    "the scalar field it is a level of",
                ),
            ],
            outputs: vec![PortSpec::output(
                "curvature",
                PortType::Image,
                "(κ1, κ2, θ1, θ2) per pixel (data, not colour)",
            )],
            params: CurvatureParams::specs(),
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
        let params = CurvatureParams::read(p)?;
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?.clone();
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let hessian = HessianFilter::of(params.step, params.reconstruction.on(ctx, &volume.data));
        let output = surface_pass(
            ctx,
            "curvature",
            CURVATURE_FORMAT,
            &gbuffer,
            &volume,
            hessian,
            None,
        )?;
        Ok(vec![Value::Image(Arc::new(Image { texture: output }))])
    }
}

/// How a curvature pass reconstructs the Hessian: central differences of the gradient at
/// ±`step_voxels` (voxels of the smallest spacing), or the B-spline's own second derivatives
/// (Hadwiger §1.3; the step is then unused but next to "no data").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HessianFilter {
    pub step_voxels: f32,
    pub reconstruction: Reconstruction,
}

impl HessianFilter {
    pub fn of(step_voxels: f32, reconstruction: Reconstruction) -> HessianFilter {
        HessianFilter { step_voxels, reconstruction }
    }
}

/// Runs a fragment program of the curvature family (shaders/curvature_common.wgsl prepended)
/// over the G-buffer's frame: in group 0 the ray uniforms of `gbuffer`'s camera over `volume`,
/// the volume and its sampler ([`RayBindings`]); in group 1 the G-buffer depth and the
/// finite-difference step of `hessian` × the smallest spacing ([`CurvatureBindings`]), the
/// program specialised for its reconstruction and, if given, `extra` as the program's own
/// uniform after them ([`CURVATURE_OWN_FIRST`]).
pub fn surface_pass(
    ctx: &mut Ctx,
    program: &'static str,
    format: wgpu::TextureFormat,
    gbuffer: &crate::value::GBuffer,
    volume: &crate::value::Volume,
    hessian: HessianFilter,
    extra: Option<&[u8]>,
) -> Result<wgpu::Texture, NodeError> {
    let HessianFilter { step_voxels, reconstruction } = hessian;
    let camera = &gbuffer.camera;
    let err = |e: GpuError| NodeError::new(e.to_string());
    let pipeline = ctx
        .cached(&format!("{program}.pipeline.{}", reconstruction.code()), |gpu| {
            screen_pass::pipeline_specialised(gpu, program, format, &[reconstruction.constant()])
        })
        .map_err(err)?;
    let sampler = linear_clamp_sampler(ctx).map_err(err)?;
    let gpu = &ctx.gpu;
    // The level of detail the device holds (see `Volume::resident`).
    let volume = volume.resident(gpu).map_err(err)?;
    let v = &volume.data;
    let texture = volume.texture(gpu).map_err(err)?;
    let options = RayOptions::plain(1.0, false, 1.0, glam::Vec3::Z, Kernel::Fragment);
    let info = TableInfo::plain();
    let ray = RayUniforms::new(camera, v, &options, &info, 1.0, texture.texel_range)
        .with_bricks(texture.layout.as_ref());
    let min_spacing = v.spacing().iter().copied().fold(f32::INFINITY, f32::min);
    let params = CurvatureUniforms {
        step: step_voxels * min_spacing,
        pad0: 0.0,
        pad1: 0.0,
        pad2: 0.0,
    };
    let uniform = |label, bytes: &[u8]| gpu.buffer_init(label, bytes, wgpu::BufferUsages::UNIFORM);
    let ray_buffer = uniform("curvature ray", bytemuck::bytes_of(&ray));
    let params_buffer = uniform("curvature params", bytemuck::bytes_of(&params));
    let extra_buffer = extra.map(|bytes| uniform("curvature extra", bytes));
    let volume_view = texture.texture.create_view(&Default::default());
    let page_view = texture.page_table.create_view(&Default::default());
    let depth_view = gbuffer.depth.create_view(&wgpu::TextureViewDescriptor {
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    });
    let shared = RayBindings {
        ray: Some(&ray_buffer),
        volume: Some(&volume_view),
        linear_clamp: Some(&sampler),
        page_table: Some(&page_view),
        ..Default::default()
    };
    let own = CurvatureBindings {
        gbuffer_depth: Some(&depth_view),
        curvature_params: Some(&params_buffer),
    };
    // A program's own uniform (CurvatureContours') follows the shared ones in group 1.
    let mut own_entries = own.entries();
    if let Some(buffer) = &extra_buffer {
        own_entries.push(wgpu::BindGroupEntry {
            binding: CURVATURE_OWN_FIRST,
            resource: buffer.as_entire_binding(),
        });
    }
    let groups = crate::bindings::bind_groups(
        gpu,
        program,
        |i| pipeline.get_bind_group_layout(i),
        &[shared.entries(), own_entries],
    )
    .map_err(err)?;
    let size = (camera.width, camera.height);
    Ok(screen_pass::draw(
        ctx,
        program,
        &pipeline,
        &[&groups[0], &groups[1]],
        format,
        size,
    ))
}

crate::bind_group! {
    /// Group 1 of the curvature programs: shaders/curvature_common.wgsl's bindings.
    pub struct CurvatureBindings in "curvature", group 1 from 0 {
        pub gbuffer_depth: TextureView,
        pub curvature_params: Buffer,
    }
}

/// The binding of a curvature program's own uniform in group 1, after [`CurvatureBindings`].
pub const CURVATURE_OWN_FIRST: u32 = 2;

/// An error at `port` unless `texture` has the G-buffer's frame size ("is A×B, the G-buffer
/// W×H" followed by `hint`).
pub fn gbuffer_sized(
    port: &str,
    texture: &wgpu::Texture,
    gbuffer: &crate::value::GBuffer,
    hint: &str,
) -> Result<(), NodeError> {
    let size = (gbuffer.camera.width, gbuffer.camera.height);
    crate::screen_pass::sized(port, texture, size, ("is ", "the G-buffer", hint))
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(CurvatureNode)
        .program("curvature", shaders::curvature(shaders::part!("curvature.wgsl")))
        .uniform(CurvatureUniforms::layout())
        .bind_group(CurvatureBindings::layout())
        .bind_group_in("curvature", crate::raycast::RayBindings::layout())
        .bind_group_in("curvature", crate::raycast::RayOutputs::layout())
        .uniform_in("curvature", crate::raycast::RayUniforms::layout());
}
