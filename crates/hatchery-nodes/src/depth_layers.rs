//! `DepthLayers`: the first two depth layers of a mesh (Fischer et al. 2005, §3.1) from one
//! geometry pass — a k-buffer of k = 2 (Bavoil et al. 2007) updated with 64-bit atomics
//! (shaders/depth_layers.wgsl), then written out as two G-buffers
//! (shaders/depth_layers_resolve.wgsl). The same layers as GBuffer + DepthPeel, which need two
//! geometry passes; where the adapter has no 64-bit atomics it runs exactly those two passes.
//! (Coincident triangles differ: a second fragment at exactly layer 1's depth is layer 2 here,
//! while peeling skips it.)

use crate::gbuffer::{NORMAL_FORMAT, render_layer};
use crate::mesh_pass;
use crate::value::{GBuffer, Mesh};
use crate::{Ctx, Value, camera::Camera};
use hatchery_gpu::GpuContext;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::param_choice! {
    /// Auto: one pass where the adapter has 64-bit atomics, else two; peel: always the two passes
    /// of GBuffer + DepthPeel (to compare).
    pub enum Method { Auto = "auto", Peel = "peel" }
}

hatchery_graph::node_params! {
    /// Parameters of `DepthLayers`.
    pub struct DepthLayersParams {
        /// auto: one pass where the adapter has 64-bit atomics, else two; peel: always the two
        /// passes of GBuffer + DepthPeel (to compare)
        pub method: Method = Method::Auto;
    }
}

pub struct DepthLayersNode;

crate::uniform_block! {
    /// The frame for both steps: the width in pixels and the slot resolved.
    pub struct LayersUniform in "depth_layers_resolve" as "ResolveFrame" {
        pub width: u32,
        pub slot: u32,
        pub pad0: u32,
        pub pad1: u32,
    }
}

/// The features the one-pass k-buffer needs.
pub fn single_pass_features() -> wgpu::Features {
    wgpu::Features::SHADER_INT64 | wgpu::Features::SHADER_INT64_ATOMIC_ALL_OPS
}

impl Node<Value, Ctx> for DepthLayersNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "DepthLayers",
            category: "Rendering",
            doc: "The nearest surface of a mesh and the one behind it (Fischer et al. 2005, §3.1) from \
                  one geometry pass: a k-buffer of the two smallest (depth, normal) keys per pixel, \
                  kept with 64-bit atomics (Bavoil et al. 2007). The same layers as GBuffer + \
                  DepthPeel, which draw the mesh twice (normals within 2e-3: 16 bits per \
                  octahedral coordinate; with coincident triangles the fragment kept may differ). \
                  Without 64-bit atomics, or when the frame needs a k-buffer larger than the \
                  adapter's storage binding limit (16 bytes per pixel), it draws those two passes.",
            inputs: vec![
                PortSpec::input("mesh", PortType::Mesh, "the surface"),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![
                PortSpec::output(
                    "layer1",
                    PortType::GBuffer,
                    "depth + normal of the nearest surface",
                ),
                PortSpec::output(
                    "layer2",
                    PortType::GBuffer,
                    "depth + normal of the surface behind it",
                ),
            ],
            params: DepthLayersParams::specs(),
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
        let params = DepthLayersParams::read(p)?;
        let mesh = inputs.require("mesh")?.mesh("mesh")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let able = single_pass_possible(&ctx.gpu, camera.width, camera.height);
        let (first, second) = if able && params.method == Method::Auto {
            single_pass(ctx, &mesh, &camera)?
        } else {
            let first = render_layer(ctx, &mesh, &camera, None)?;
            let second = render_layer(ctx, &mesh, &camera, Some(&first))?;
            (first, second)
        };
        Ok(vec![
            Value::GBuffer(Arc::new(first)),
            Value::GBuffer(Arc::new(second)),
        ])
    }
}

/// Whether the one-pass k-buffer runs on this device for a `width` × `height` frame: the
/// adapter has 64-bit atomics and the buffer (16 bytes per pixel) fits one storage binding.
pub fn single_pass_possible(gpu: &GpuContext, width: u32, height: u32) -> bool {
    let bytes = u64::from(width) * u64::from(height) * 16;
    gpu.device.features().contains(single_pass_features())
        && bytes <= gpu.device.limits().max_storage_buffer_binding_size
}

/// The k-buffer pass and the two resolves.
fn single_pass(
    ctx: &mut Ctx,
    mesh: &Mesh,
    camera: &Camera,
) -> Result<(GBuffer, GBuffer), NodeError> {
    let err = |e: hatchery_gpu::GpuError| NodeError::new(e.to_string());
    let capture = ctx
        .cached("depth_layers.pipeline", capture_pipeline)
        .map_err(err)?;
    let resolve = ctx
        .cached("depth_layers_resolve.pipeline", resolve_pipeline)
        .map_err(err)?;
    // A handle of the device (cheap to clone) so that work can be submitted through ctx.
    let gpu = &ctx.gpu.clone();
    let (w, h) = (camera.width, camera.height);
    let keys = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("depth layers k-buffer"),
        size: u64::from(w) * u64::from(h) * 16,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let frame = |slot: u32| {
        gpu.buffer_init(
            "depth layers frame",
            bytemuck::bytes_of(&LayersUniform {
                width: w,
                slot,
                pad0: 0,
                pad1: 0,
            }),
            wgpu::BufferUsages::UNIFORM,
        )
    };
    let camera_uniform = camera.uniform_buffer(gpu);
    let capture_frame = frame(0);
    let capture_group = gpu.bind_group(
        "depth layers",
        &capture.get_bind_group_layout(0),
        &[
            (0, camera_uniform.as_entire_binding()),
            (1, keys.as_entire_binding()),
            (2, capture_frame.as_entire_binding()),
        ],
    );
    // The depth target is only there because a pass needs an attachment (test: always).
    let scratch = mesh_pass::depth_target(gpu, "depth layers scratch", w, h);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encoder.clear_buffer(&keys, 0, None);
    let clear = encoder.finish();
    let draw = mesh_pass::draw_mesh_targets(gpu, &capture, &capture_group, mesh, &[], &scratch);
    ctx.submit(clear);
    ctx.submit(draw);

    let mut layers = Vec::new();
    for slot in 0..2 {
        let slot_frame = frame(slot);
        let group = gpu.bind_group(
            "depth layers resolve",
            &resolve.get_bind_group_layout(0),
            &[
                (0, keys.as_entire_binding()),
                (1, slot_frame.as_entire_binding()),
            ],
        );
        let normal = gpu.render_target("depth layer normal", w, h, NORMAL_FORMAT);
        let depth = mesh_pass::depth_target(gpu, "depth layer", w, h);
        let work = resolve_draw(gpu, &resolve, &group, &normal, &depth);
        ctx.submit(work);
        layers.push(GBuffer {
            depth,
            normal,
            camera: camera.clone(),
        });
    }
    let second = layers.pop().expect("two layers");
    let first = layers.pop().expect("two layers");
    Ok((first, second))
}

/// The capture pipeline: the mesh's vertex stage, the k-buffer fragment stage, no colour
/// target, a depth attachment that never rejects and is never written.
fn capture_pipeline(gpu: &GpuContext) -> Result<wgpu::RenderPipeline, hatchery_gpu::GpuError> {
    let depth = wgpu::DepthStencilState {
        depth_write_enabled: Some(false),
        depth_compare: Some(wgpu::CompareFunction::Always),
        ..mesh_pass::depth_state()
    };
    mesh_pass::mesh_pipeline_with(gpu, "depth_layers", &[], depth)
}

/// The resolve pipeline: one full-frame triangle writing depth and the normal target.
fn resolve_pipeline(gpu: &GpuContext) -> Result<wgpu::RenderPipeline, hatchery_gpu::GpuError> {
    let source = crate::kinds::source("depth_layers_resolve").expect("registered program");
    let module = gpu.shader("depth_layers_resolve", &source)?;
    let depth = wgpu::DepthStencilState {
        depth_compare: Some(wgpu::CompareFunction::Always),
        ..mesh_pass::depth_state()
    };
    gpu.checked("pipeline depth_layers_resolve", |device| {
        let stages = crate::screen_pass::Stages {
            vertex: &module,
            fragment: &module,
            entry: "fs_main",
            constants: &[],
        };
        crate::screen_pass::fullscreen_pipeline(
            device,
            "depth_layers_resolve",
            None,
            stages,
            &[NORMAL_FORMAT],
            Some(depth),
        )
    })
}

/// One resolve: clears the layer (depth 1, normal 0) and draws the full-frame triangle.
fn resolve_draw(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
    normal: &wgpu::Texture,
    depth: &wgpu::Texture,
) -> wgpu::CommandBuffer {
    let normal_view = normal.create_view(&Default::default());
    let depth_view = depth.create_view(&Default::default());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("depth layer resolve"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &normal_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(mesh_pass::cleared_depth(&depth_view)),
            ..Default::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.draw(0..3, 0..1);
    }
    encoder.finish()
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    use crate::uniforms::UniformLayout;
    k.node(DepthLayersNode)
        .program("depth_layers", shaders::mesh(shaders::part!("depth_layers.wgsl")))
        .program("depth_layers_resolve", shaders::screen(shaders::part!("depth_layers_resolve.wgsl")))
        .uniform(LayersUniform::layout())
        .uniform(UniformLayout {
            program: "depth_layers",
            wgsl_struct: "LayersFrame",
            ..LayersUniform::layout()
        })
        .uniform_in("depth_layers", crate::camera::CameraUniform::layout());
}
