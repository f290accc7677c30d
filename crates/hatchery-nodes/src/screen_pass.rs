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
    pipeline_specialised(gpu, program, format, &[])
}

/// [`pipeline`] with values for the shader's pipeline-overridable constants (`override`):
/// the compiler folds them, so a mode chosen this way costs nothing per pixel — where a uniform
/// would leave every mode's code in the loop (on lavapipe the silhouette pass ran 2.2× slower
/// with its PIP mode in a uniform than as a constant).
pub fn pipeline_specialised(
    gpu: &GpuContext,
    program: &str,
    format: wgpu::TextureFormat,
    constants: &[(&str, f64)],
) -> Result<wgpu::RenderPipeline, GpuError> {
    let source = crate::kinds::source(program).ok_or_else(|| GpuError::Validation {
        what: format!("shader {program}"),
        message: "no such shader program".into(),
    })?;
    let module = gpu.shader(program, &source)?;
    gpu.checked(&format!("pipeline {program}"), |device| {
        let stages = Stages {
            vertex: &module,
            fragment: &module,
            entry: "fs_main",
            constants,
        };
        fullscreen_pipeline(device, program, None, stages, &[format], None)
    })
}

/// The shader stages of a full-frame pipeline: the vertex module's `vs_main`, the fragment
/// module's `entry`, with values for the fragment stage's `override` constants.
pub struct Stages<'a> {
    pub vertex: &'a wgpu::ShaderModule,
    pub fragment: &'a wgpu::ShaderModule,
    pub entry: &'a str,
    pub constants: &'a [(&'a str, f64)],
}

/// A pipeline drawing one full-frame triangle (no vertex buffers) with `stages` into one colour
/// target per format of `formats`, with `depth` if the pass has a depth attachment; `layout`
/// `None` derives it.
pub fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: Option<&wgpu::PipelineLayout>,
    stages: Stages,
    formats: &[wgpu::TextureFormat],
    depth: Option<wgpu::DepthStencilState>,
) -> wgpu::RenderPipeline {
    let targets: Vec<Option<wgpu::ColorTargetState>> =
        formats.iter().map(|&f| Some(f.into())).collect();
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout,
        vertex: wgpu::VertexState {
            module: stages.vertex,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: depth,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: stages.fragment,
            entry_point: Some(stages.entry),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: stages.constants,
                ..Default::default()
            },
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// An error naming `port` unless `texture` has the frame's size.
pub fn frame_sized(ctx: &Ctx, port: &str, texture: &wgpu::Texture) -> Result<(), NodeError> {
    sized(port, texture, ctx.size(), ("input is ", "the frame is", ""))
}

/// An error naming `port` unless `texture` is `width` × `height`; the message reads
/// "{is}A×B, {against} W×H{hint}".
pub fn sized(
    port: &str,
    texture: &wgpu::Texture,
    (width, height): (u32, u32),
    (is, against, hint): (&str, &str, &str),
) -> Result<(), NodeError> {
    if (texture.width(), texture.height()) == (width, height) {
        return Ok(());
    }
    Err(NodeError::at_port(
        port,
        format!(
            "{is}{}×{}, {against} {width}×{height}{hint}",
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
    run_specialised(ctx, (program, &[]), format, textures, patterns, uniform)
}

/// [`run`] with values for the program's `override` constants (see [`pipeline_specialised`]).
pub fn run_specialised(
    ctx: &mut Ctx,
    (program, constants): (&'static str, &[(&str, f64)]),
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
    render_specialised(
        ctx,
        (program, constants),
        format,
        (width, height),
        &bound,
        uniform,
    )
    .map_err(|e| NodeError::new(e.to_string()))
}

/// Runs `program` into a new `size` texture of `format`, with `textures` bound at bindings
/// 0, 1, … and the uniform (if any) after them. No size checks: the shader addresses its inputs.
pub fn render(
    ctx: &mut Ctx,
    program: &'static str,
    format: wgpu::TextureFormat,
    size: (u32, u32),
    textures: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<wgpu::Texture, GpuError> {
    render_specialised(ctx, (program, &[]), format, size, textures, uniform)
}

/// [`render`] with values for the program's `override` constants; one pipeline per set of
/// values, cached.
pub fn render_specialised(
    ctx: &mut Ctx,
    (program, constants): (&'static str, &[(&str, f64)]),
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
    textures: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> Result<wgpu::Texture, GpuError> {
    let key = format!("screen:{program}:{format:?}:{constants:?}");
    let pipeline = ctx.cached(&key, |gpu| {
        pipeline_specialised(gpu, program, format, constants)
    })?;
    let bind_group = bind_group(&ctx.gpu, program, &pipeline, textures, uniform);
    Ok(draw(
        ctx,
        program,
        &pipeline,
        &[&bind_group],
        format,
        (width, height),
    ))
}

/// Group 0 of `pipeline`: `textures` at bindings 0, 1, …, then a uniform buffer holding `uniform`
/// (if any).
pub fn bind_group(
    gpu: &GpuContext,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    textures: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> wgpu::BindGroup {
    bind_group_with(
        gpu,
        label,
        &pipeline.get_bind_group_layout(0),
        textures,
        uniform,
    )
}

/// [`bind_group`] for `layout`: `textures` (sampled or storage, as the layout says) at bindings
/// 0, 1, …, then the uniform buffer (if any).
pub fn bind_group_with(
    gpu: &GpuContext,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    textures: &[&wgpu::Texture],
    uniform: Option<&[u8]>,
) -> wgpu::BindGroup {
    let views: Vec<wgpu::TextureView> = textures
        .iter()
        .map(|t| t.create_view(&Default::default()))
        .collect();
    let uniform_buffer =
        uniform.map(|bytes| gpu.buffer_init(label, bytes, wgpu::BufferUsages::UNIFORM));
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
    gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// One full-screen triangle of `pipeline` with `bind_group` into a new `format` target of
/// `width` × `height` (cleared to transparent), submitted; the target.
pub fn draw(
    ctx: &mut Ctx,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind_groups: &[&wgpu::BindGroup],
    format: wgpu::TextureFormat,
    (width, height): (u32, u32),
) -> wgpu::Texture {
    let output = ctx.gpu.render_target(label, width, height, format);
    let work = draw_into(
        &ctx.gpu,
        label,
        pipeline,
        bind_groups,
        std::slice::from_ref(&output),
    );
    ctx.submit(work);
    output
}

/// One full-frame triangle of `pipeline` with `bind_groups` (groups 0, 1, …) into `targets`
/// (one colour attachment each, cleared to transparent); the work, not yet submitted.
pub fn draw_into(
    gpu: &GpuContext,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind_groups: &[&wgpu::BindGroup],
    targets: &[wgpu::Texture],
) -> wgpu::CommandBuffer {
    let targets: Vec<(&wgpu::Texture, bool)> = targets.iter().map(|t| (t, false)).collect();
    draw_into_loading(gpu, label, pipeline, bind_groups, &targets)
}

/// [`draw_into`], loading the targets marked `true` instead of clearing them: for targets that
/// already hold a picture the pass overwrites at every pixel (no clear to pay for).
pub fn draw_into_loading(
    gpu: &GpuContext,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    bind_groups: &[&wgpu::BindGroup],
    targets: &[(&wgpu::Texture, bool)],
) -> wgpu::CommandBuffer {
    let views: Vec<(wgpu::TextureView, bool)> = targets
        .iter()
        .map(|(t, load)| (t.create_view(&Default::default()), *load))
        .collect();
    let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
        .iter()
        .map(|(view, load)| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: if *load {
                        wgpu::LoadOp::Load
                    } else {
                        wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT)
                    },
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(label),
            color_attachments: &attachments,
            ..Default::default()
        });
        pass.set_pipeline(pipeline);
        for (i, group) in bind_groups.iter().enumerate() {
            pass.set_bind_group(i as u32, *group, &[]);
        }
        pass.draw(0..3, 0..1);
    }
    encoder.finish()
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
