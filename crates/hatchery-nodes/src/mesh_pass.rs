//! Drawing a mesh with a camera: the pass shared by GBuffer and ShadedSurface.

use crate::value::Mesh;
use hatchery_gpu::{GpuContext, GpuError};

/// Depth format of every mesh pass (sampled later by depth peeling and compositing).
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];

/// Interleaved position + normal, as [`crate::value::Mesh`] uploads them.
pub fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: 24,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// The ordinary depth test, writing depth.
pub fn depth_state() -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(true),
        depth_compare: Some(wgpu::CompareFunction::Less),
        stencil: Default::default(),
        bias: Default::default(),
    }
}

/// A render pipeline drawing meshes with `program` (a name from [`crate::kinds::programs`]).
pub fn mesh_pipeline(
    gpu: &GpuContext,
    program: &str,
    color_format: wgpu::TextureFormat,
    blend: Option<wgpu::BlendState>,
) -> Result<wgpu::RenderPipeline, GpuError> {
    let target = wgpu::ColorTargetState {
        format: color_format,
        blend,
        write_mask: wgpu::ColorWrites::ALL,
    };
    mesh_pipeline_with(gpu, program, &[Some(target)], depth_state())
}

/// [`mesh_pipeline`] with any colour targets (none, several) and depth state.
pub fn mesh_pipeline_with(
    gpu: &GpuContext,
    program: &str,
    targets: &[Option<wgpu::ColorTargetState>],
    depth: wgpu::DepthStencilState,
) -> Result<wgpu::RenderPipeline, GpuError> {
    let source = crate::kinds::source(program).ok_or_else(|| GpuError::Validation {
        what: format!("shader {program}"),
        message: "no such shader program".into(),
    })?;
    let module = gpu.shader(program, &source)?;
    gpu.checked(&format!("pipeline {program}"), |device| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(program),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(vertex_layout())],
            },
            // No culling: illustration shows inner and back faces (peeled layers, open meshes).
            primitive: wgpu::PrimitiveState {
                cull_mode: None,
                ..Default::default()
            },
            depth_stencil: Some(depth),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    })
}

/// `view` as a pass's depth attachment, cleared to 1 (far) and stored.
pub fn cleared_depth(view: &wgpu::TextureView) -> wgpu::RenderPassDepthStencilAttachment<'_> {
    wgpu::RenderPassDepthStencilAttachment {
        view,
        depth_ops: Some(wgpu::Operations {
            load: wgpu::LoadOp::Clear(1.0),
            store: wgpu::StoreOp::Store,
        }),
        stencil_ops: None,
    }
}

/// A depth target of the frame size.
pub fn depth_target(gpu: &GpuContext, label: &str, width: u32, height: u32) -> wgpu::Texture {
    gpu.render_target(label, width, height, DEPTH_FORMAT)
}

/// Clears `color` (to `clear`) and `depth` and draws the mesh into them; submit the commands.
#[must_use]
pub fn draw_mesh(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
    mesh: &Mesh,
    color: &wgpu::Texture,
    clear: wgpu::Color,
    depth: &wgpu::Texture,
) -> wgpu::CommandBuffer {
    draw(gpu, pipeline, bind_group, mesh, &[(color, clear)], depth)
}

/// Like [`draw_mesh`] with several colour targets, all cleared to zero.
#[must_use]
pub fn draw_mesh_targets(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
    mesh: &Mesh,
    colors: &[&wgpu::Texture],
    depth: &wgpu::Texture,
) -> wgpu::CommandBuffer {
    let targets: Vec<(&wgpu::Texture, wgpu::Color)> = colors
        .iter()
        .map(|t| (*t, wgpu::Color::TRANSPARENT))
        .collect();
    draw(gpu, pipeline, bind_group, mesh, &targets, depth)
}

fn draw(
    gpu: &GpuContext,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
    mesh: &Mesh,
    colors: &[(&wgpu::Texture, wgpu::Color)],
    depth: &wgpu::Texture,
) -> wgpu::CommandBuffer {
    let buffers = mesh.buffers(gpu);
    let views: Vec<wgpu::TextureView> = colors
        .iter()
        .map(|(t, _)| t.create_view(&Default::default()))
        .collect();
    let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
        .iter()
        .zip(colors)
        .map(|(view, (_, clear))| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(*clear),
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    let depth_view = depth.create_view(&Default::default());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("mesh pass"),
            color_attachments: &attachments,
            depth_stencil_attachment: Some(cleared_depth(&depth_view)),
            ..Default::default()
        });
        if buffers.index_count > 0 {
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind_group, &[]);
            pass.set_vertex_buffer(0, buffers.vertices.slice(..));
            pass.set_index_buffer(buffers.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..buffers.index_count, 0, 0..1);
        }
    }
    encoder.finish()
}
