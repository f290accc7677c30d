//! Image-space passes: one full-frame triangle through a fragment shader that reads input
//! textures by pixel. Shared by every mask and compositing node.

use crate::value::{Image, Mask};
use crate::{Ctx, Value};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::NodeError;
use std::sync::Arc;

/// Format of `Mask` values.
pub const MASK_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;
/// Format of `Image` values (premultiplied RGBA).
pub const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// A full-screen pass's pipeline: `vs_main` and `fs_main` of `program`, one `format` target.
pub fn pipeline(
    gpu: &GpuContext,
    program: &str,
    format: wgpu::TextureFormat,
) -> Result<wgpu::RenderPipeline, GpuError> {
    let source = crate::shaders::source(program).ok_or_else(|| GpuError::Validation {
        what: format!("shader {program}"),
        message: "no such shader program".into(),
    })?;
    let module = gpu.shader(program, &source)?;
    gpu.checked(&format!("pipeline {program}"), |device| {
        fullscreen_pipeline(
            device,
            program,
            None,
            (&module, &module),
            "fs_main",
            format,
            None,
        )
    })
}

/// A pipeline drawing one full-frame triangle (no vertex buffers): the vertex module's
/// `vs_main`, the fragment module's `entry` into one `format` target, with `depth` if the pass
/// has a depth attachment; `layout` `None` derives it.
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: Option<&wgpu::PipelineLayout>,
    (vertex, fragment): (&wgpu::ShaderModule, &wgpu::ShaderModule),
    entry: &str,
    format: wgpu::TextureFormat,
    depth: Option<wgpu::DepthStencilState>,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout,
        vertex: wgpu::VertexState {
            module: vertex,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: depth,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: fragment,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: &[Some(format.into())],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// An error naming `port` unless `texture` has the frame's size.
pub fn frame_sized(ctx: &Ctx, port: &str, texture: &wgpu::Texture) -> Result<(), NodeError> {
    let (width, height) = ctx.size();
    if (texture.width(), texture.height()) == (width, height) {
        return Ok(());
    }
    Err(NodeError::at_port(
        port,
        format!(
            "input is {}×{}, the frame is {width}×{height}",
            texture.width(),
            texture.height()
        ),
    ))
}

/// Runs `program` over the frame: the frame-sized `textures` are bound at bindings 0, 1, … in
/// order (each named by the port it came from, for size errors), then the `patterns` (textures of
/// any size), then the uniform (if any). Returns the new frame-sized texture of `format`.
pub fn run(
    ctx: &mut Ctx,
    program: &'static str,
    format: wgpu::TextureFormat,
    textures: &[(&str, &wgpu::Texture)],
    patterns: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<wgpu::Texture, NodeError> {
    let (width, height) = ctx.size();
    for (port, texture) in textures {
        frame_sized(ctx, port, texture)?;
    }
    let bound: Vec<&wgpu::Texture> = textures
        .iter()
        .map(|(_, t)| *t)
        .chain(patterns.iter().copied())
        .collect();
    render(ctx, program, format, (width, height), &bound, uniform)
        .map_err(|e| NodeError::new(e.to_string()))
}

/// Runs `program` into a new `size` texture of `format`, with `textures` bound at bindings
/// 0, 1, … and the uniform (if any) after them. No size checks: the shader addresses its inputs.
pub fn render(
    ctx: &mut Ctx,
    program: &'static str,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    textures: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<wgpu::Texture, GpuError> {
    let key = format!("screen:{program}:{format:?}");
    let pipeline = ctx.cached(&key, |gpu| pipeline(gpu, program, format))?;
    let gpu = &ctx.gpu;
    let views: Vec<wgpu::TextureView> = textures
        .iter()
        .map(|t| t.create_view(&Default::default()))
        .collect();
    let uniform_buffer =
        uniform.map(|bytes| gpu.buffer_init(program, bytes, wgpu::BufferUsages::UNIFORM));
    let mut entries: Vec<wgpu::BindGroupEntry> = views
        .iter()
        .enumerate()
        .map(|(i, view)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: wgpu::BindingResource::TextureView(view),
        })
        .collect();
    if let Some(buffer) = &uniform_buffer {
        entries.push(wgpu::BindGroupEntry {
            binding: views.len() as u32,
            resource: buffer.as_entire_binding(),
        });
    }
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(program),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    Ok(draw(
        ctx,
        program,
        &pipeline,
        &bind_group,
        format,
        (width, height),
    ))
}

/// One full-screen triangle of `pipeline` with `bind_group` into a new `format` target of
/// `width` × `height` (cleared to transparent), submitted; the target.
pub fn draw(
    ctx: &mut Ctx,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
) -> wgpu::Texture {
    let gpu = &ctx.gpu;
    let output = gpu.render_target(label, width, height, format);
    let output_view = output.create_view(&Default::default());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &output_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
    let work = encoder.finish();
    ctx.submit(work);
    output
}

/// [`run`] producing a `Mask` value.
pub fn mask(
    ctx: &mut Ctx,
    program: &'static str,
    textures: &[(&str, &wgpu::Texture)],
    patterns: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<Value, NodeError> {
    let texture = run(ctx, program, MASK_FORMAT, textures, patterns, uniform)?;
    Ok(Value::Mask(Arc::new(Mask { texture })))
}

/// [`run`] producing an `Image` value.
pub fn image(
    ctx: &mut Ctx,
    program: &'static str,
    textures: &[(&str, &wgpu::Texture)],
    patterns: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<Value, NodeError> {
    let texture = run(ctx, program, IMAGE_FORMAT, textures, patterns, uniform)?;
    Ok(Value::Image(Arc::new(Image { texture })))
}
