//! `HatchStrokes`: hatching strokes along the principal curvature directions of an iso-surface
//! (Nagy et al. 2002; Yuan & Chen 2005 §4.4), traced and drawn on the GPU
//! (shaders/hatch_strokes.wgsl), output as a coverage mask and as vector polylines for SaveSvg.
//!
//! Seeds are the vertices of a mesh of the same surface (e.g. MarchingCubes of the volume at the
//! iso value): surface points, not pixels, so an orbiting view keeps its strokes (Yuan–Chen's
//! "subset of the surface points"); each seed's random number is a hash of its index.

use crate::curvature::gbuffer_sized;
use crate::screen_pass::MASK_FORMAT;
use crate::value::Mask;
use crate::{Ctx, Value};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::{Arc, OnceLock};

crate::uniform_block! {
    /// `Hatch` of shaders/hatch_strokes.wgsl (see there for the fields).
    pub struct HatchUniforms in "hatch_strokes" as "Hatch" {
        pub view_proj: [[f32; 4]; 4],
        pub view: [[f32; 4]; 4],
        pub inv_proj: [[f32; 4]; 4],
        pub frame: [f32; 2],
        pub step: f32,
        pub steps: u32,
        pub density: f32,
        pub cross_threshold: f32,
        pub depth_tolerance: f32,
        pub max_strokes: u32,
        pub width: f32,
        pub taper: f32,
        pub smaller_curvature: u32,
        pub use_tone: u32,
        pub seeds: u32,
        pub salt: u32,
        pub pad0: u32,
        pub pad1: u32,
    }
}

/// Format the strokes are drawn in: blendable (max of overlapping strokes), then copied into a
/// 32-bit Mask.
const DRAW_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R16Float;
/// Most RK4 steps per half stroke.
const MAX_STEPS: u32 = 128;

pub use crate::value::strokes::{StrokeLine, Strokes};

/// The compute and render pipelines of shaders/hatch_strokes.wgsl.
struct HatchPipelines {
    trace: wgpu::ComputePipeline,
    finish: wgpu::ComputePipeline,
    draw: wgpu::RenderPipeline,
}

impl HatchPipelines {
    fn new(gpu: &GpuContext) -> Result<Self, GpuError> {
        let source = crate::kinds::source("hatch_strokes").expect("registered program");
        let module = gpu.shader("hatch_strokes", &source)?;
        let compute = |entry: &str| {
            gpu.checked(&format!("pipeline hatch_strokes/{entry}"), |device| {
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(entry),
                    layout: None,
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    cache: None,
                })
            })
        };
        let max = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Max,
        };
        let draw = gpu.checked("pipeline hatch_strokes/draw", |device| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("hatch strokes"),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_stroke"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_stroke"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: DRAW_FORMAT,
                        blend: Some(wgpu::BlendState {
                            color: max,
                            alpha: max,
                        }),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        })?;
        Ok(Self {
            trace: compute("trace")?,
            finish: compute("finish")?,
            draw,
        })
    }
}

hatchery_graph::param_choice! {
    /// The principal direction of the larger or of the smaller |κ|.
    pub enum Direction { MaxCurvature = "max_curvature", MinCurvature = "min_curvature" }
}

hatchery_graph::node_params! {
    /// Parameters of `HatchStrokes`.
    pub struct HatchStrokesParams {
        /// chance that a seed at full darkness draws a stroke
        pub density: f32 = 0.05, range(0.0, 1.0);
        /// stroke length, pixels (at most 256 RK4 steps)
        pub length: f32 = 24.0, range(2.0, 256.0), unit(pixels);
        /// stroke width in the middle, pixels
        pub width: f32 = 1.2, range(0.25, 8.0), unit(pixels);
        /// fraction of the length over which each end thins to nothing
        pub taper: f32 = 0.3, range(0.0, 0.5);
        /// integration step along a stroke (RK4), pixels (smaller follows curved fields more closely)
        pub step: f32 = 1.0, range(0.25, 4.0), unit(pixels);
        /// the principal direction of the larger or of the smaller |κ|
        pub direction: Direction = Direction::MaxCurvature;
        /// darkness above which a second stroke crosses the first (1 = never)
        pub cross_hatching: f32 = 0.6, range(0.0, 1.0);
        /// visibility and fold test: depth difference allowed, as a fraction of the seed mesh's
        /// bounding-box diagonal
        pub depth_tolerance: f32 = 0.01, range(0.0, 1.0);
        /// most strokes drawn
        pub max_strokes: u32 = 20000, range(1, 1_000_000);
        /// varies the random numbers
        pub seed: u32 = 0, range(0, 1 << 20);
    }
}

pub struct HatchStrokesNode;

impl Node<Value, Ctx> for HatchStrokesNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "HatchStrokes",
            category: "Volume",
            doc: "Hatching strokes along principal curvature directions (Nagy et al. 2002; Yuan \
                  & Chen 2005 §4.4). Seeds are the vertices of `seeds`, a mesh of the same \
                  surface (MarchingCubes of the volume at the iso value): a seed draws when it \
                  is visible in the G-buffer and its random number (a hash of its index, so \
                  strokes stay on the surface as the view moves) is below `density` × its \
                  darkness (1 − `tone`, or 1 − the headlight Lambert term of the G-buffer \
                  normal without a tone). Each stroke is integrated both ways from the seed \
                  with RK4 in image space through Curvature's direction field (the larger-|κ| \
                  principal direction, or the smaller), stopping where the surface ends, the \
                  depth jumps or the field turns; where the darkness exceeds `cross_hatching` \
                  a second stroke follows the other direction. Drawn anti-aliased with tapered \
                  ends into `mask`; `strokes` carries the polylines for SaveSvg.",
            inputs: vec![
                PortSpec::input("curvature", PortType::Image, "Curvature's output"),
                PortSpec::input(
                    "gbuffer",
                    PortType::GBuffer,
                    "the surface (the G-buffer Curvature read)",
                ),
                PortSpec::input(
                    "seeds",
                    PortType::Mesh,
                    "candidate seeds: a mesh of the same surface (its vertices)",
                ),
                PortSpec::optional(
                    "tone",
                    PortType::Mask,
                    "brightness in [0, 1] (e.g. DiffuseIntensity); darker = more strokes",
                ),
            ],
            outputs: vec![
                PortSpec::output("mask", PortType::Mask, "stroke coverage"),
                PortSpec::output("strokes", PortType::Strokes, "the strokes as polylines"),
            ],
            params: HatchStrokesParams::specs(),
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
        let params = HatchStrokesParams::read(p)?;
        let curvature = inputs.require("curvature")?.image("curvature")?.clone();
        let gbuffer = inputs.require("gbuffer")?.gbuffer("gbuffer")?.clone();
        let seeds = inputs.require("seeds")?.mesh("seeds")?.clone();
        let tone = match inputs.get("tone") {
            Some(t) => Some(t.mask("tone")?.clone()),
            None => None,
        };
        let camera = &gbuffer.camera;
        let (width, height) = (camera.width, camera.height);
        gbuffer_sized(
            "curvature",
            &curvature.texture,
            &gbuffer,
            ": connect the Curvature of this G-buffer",
        )?;
        if let Some(t) = &tone {
            gbuffer_sized("tone", &t.texture, &gbuffer, "")?;
        }
        let err = |e: GpuError| NodeError::new(e.to_string());
        let pipelines = ctx
            .cached("hatch_strokes.pipelines", HatchPipelines::new)
            .map_err(err)?;

        let vertex_count = seeds.data.positions.len() as u32;
        // The seeds are read as one storage binding (24 bytes per vertex).
        let limit = ctx.gpu.device.limits().max_storage_buffer_binding_size;
        if 24 * vertex_count as u64 > limit {
            return Err(NodeError::at_port(
                "seeds",
                format!(
                    "{vertex_count} vertices ({} bytes) exceed the adapter's storage binding \
                     limit of {limit} bytes (max_storage_buffer_binding_size); decimate the \
                     mesh",
                    24 * vertex_count as u64
                ),
            ));
        }
        let diagonal = seeds
            .data
            .bounds()
            .map_or(1.0, |(lo, hi)| (hi - lo).length().max(1e-6));
        let step = params.step;
        let steps = ((0.5 * params.length / step).ceil() as u32).clamp(1, MAX_STEPS);
        let slots = 2 * steps + 1;
        let max_strokes = params.max_strokes.max(1).min(
            (ctx.gpu.device.limits().max_storage_buffer_binding_size / (8 * slots as u64)).max(1)
                as u32,
        );
        let uniforms = HatchUniforms {
            view_proj: camera.view_proj().to_cols_array_2d(),
            view: camera.view.to_cols_array_2d(),
            inv_proj: camera.proj.inverse().to_cols_array_2d(),
            frame: [width as f32, height as f32],
            step,
            steps,
            density: params.density,
            // ≥ 1: no cross-hatching.
            cross_threshold: if params.cross_hatching >= 1.0 {
                2.0
            } else {
                params.cross_hatching
            },
            depth_tolerance: params.depth_tolerance * diagonal,
            max_strokes,
            width: params.width,
            taper: params.taper,
            smaller_curvature: (params.direction == Direction::MinCurvature).into(),
            use_tone: tone.is_some().into(),
            seeds: vertex_count,
            salt: params.seed.wrapping_mul(0x9E37_79B9),
            pad0: 0,
            pad1: 0,
        };
        let blank = ctx.blank_texture();
        let gpu = &ctx.gpu;
        let storage = |label, size: u64, extra: wgpu::BufferUsages| {
            gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size.max(16),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | extra,
                mapped_at_creation: false,
            })
        };
        let uniform = gpu.buffer_init(
            "hatch uniforms",
            bytemuck::bytes_of(&uniforms),
            wgpu::BufferUsages::UNIFORM,
        );
        let counter = gpu.buffer_init(
            "hatch counter",
            &[0u8; 16],
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let headers = storage(
            "hatch strokes",
            16 * max_strokes as u64,
            wgpu::BufferUsages::empty(),
        );
        let points = storage(
            "hatch points",
            8 * (max_strokes as u64) * slots as u64,
            wgpu::BufferUsages::empty(),
        );
        let indirect = storage("hatch indirect", 16, wgpu::BufferUsages::INDIRECT);
        let mesh = seeds.buffers(gpu);

        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let curvature_view = view(&curvature.texture);
        let depth_view = gbuffer.depth.create_view(&wgpu::TextureViewDescriptor {
            aspect: wgpu::TextureAspect::DepthOnly,
            ..Default::default()
        });
        let normal_view = view(&gbuffer.normal);
        let tone_view = view(tone.as_ref().map_or(&blank, |t| &t.texture));
        use wgpu::BindingResource::TextureView as Tex;
        let trace_group = gpu.bind_group(
            "hatch trace",
            &pipelines.trace.get_bind_group_layout(0),
            &[
                (0, uniform.as_entire_binding()),
                (1, Tex(&curvature_view)),
                (2, Tex(&depth_view)),
                (3, Tex(&normal_view)),
                (4, Tex(&tone_view)),
                (5, mesh.vertices.as_entire_binding()),
                (6, headers.as_entire_binding()),
                (7, points.as_entire_binding()),
                (8, counter.as_entire_binding()),
            ],
        );
        let finish_group = gpu.bind_group(
            "hatch finish",
            &pipelines.finish.get_bind_group_layout(0),
            &[
                (0, uniform.as_entire_binding()),
                (8, counter.as_entire_binding()),
                (9, indirect.as_entire_binding()),
            ],
        );
        let draw_group = gpu.bind_group(
            "hatch draw",
            &pipelines.draw.get_bind_group_layout(0),
            &[
                (0, uniform.as_entire_binding()),
                (10, headers.as_entire_binding()),
                (11, points.as_entire_binding()),
            ],
        );
        let target = gpu.render_target("hatch strokes", width, height, DRAW_FORMAT);
        let target_view = view(&target);
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("hatch trace"),
                timestamp_writes: None,
            });
            let groups = vertex_count.div_ceil(64);
            if groups > 0 {
                pass.set_pipeline(&pipelines.trace);
                pass.set_bind_group(0, &trace_group, &[]);
                pass.dispatch_workgroups(groups.min(65535), groups.div_ceil(65535), 1);
            }
            pass.set_pipeline(&pipelines.finish);
            pass.set_bind_group(0, &finish_group, &[]);
            pass.dispatch_workgroups(1, 1, 1);
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("hatch draw"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &target_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipelines.draw);
            pass.set_bind_group(0, &draw_group, &[]);
            pass.draw_indirect(&indirect, 0);
        }
        ctx.submit(encoder.finish());
        let mask = crate::screen_pass::render(
            ctx,
            "mask_copy",
            MASK_FORMAT,
            (width, height),
            &[&target],
            None,
        )
        .map_err(err)?;
        let strokes = Strokes {
            counter,
            headers,
            points,
            slots,
            max_strokes,
            width: params.width,
            taper: params.taper,
            frame: (width, height),
            lines: OnceLock::new(),
        };
        Ok(vec![
            Value::Mask(Arc::new(Mask { texture: mask })),
            Value::Strokes(Arc::new(strokes)),
        ])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(HatchStrokesNode)
        // Compute tracing plus instanced segments.
        .program(
            "hatch_strokes",
            vec![
                ("curvature_field.wgsl", shaders::CURVATURE_FIELD),
                shaders::part!("hatch_strokes.wgsl"),
            ],
        )
        .program("mask_copy", shaders::screen(shaders::part!("mask_copy.wgsl")))
        .uniform(HatchUniforms::layout());
}
