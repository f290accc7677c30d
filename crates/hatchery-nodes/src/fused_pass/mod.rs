//! Fused image-space passes: the image-space nodes that read their inputs only at the pixel they
//! write (diffuse intensity, halftoning, mask arithmetic, compositing — and silhouettes, which
//! read a G-buffer around the pixel but only from outside the pass) are *stages*: a WGSL function
//! each (shaders/<node>.wgsl). The executor groups connected stages that run in the same frame
//! (`hatchery_graph::fusion`); this module writes one fragment shader calling the group's
//! functions in order, each result passed on in a register instead of a render target, and draws
//! it once with a colour target for every output something outside the group reads. A node
//! running alone is a group of one, so fused and unfused frames run the same code.
//!
//! Why: each full-frame pass has a fixed cost (on lavapipe 5–11 ms at 1024×768 for one texture
//! read), and the hidden-layers frame of Fischer et al. 2005 is seven of them after the geometry.
//! Images passed between stages are rounded to binary16 as an Rgba16Float target stores them
//! (`as_rgba16float` in shaders/fullscreen.wgsl), so a fused frame equals the unfused one bit
//! for bit on lavapipe (tests/fused_pass.rs).

use crate::kernel::Kernel;
use crate::screen_pass::{self, IMAGE_FORMAT};
pub use crate::stage::{Arg, Fusable, Stage, StageInputs};
use crate::{Ctx, Value};
use hatchery_graph::executor::Node;
use hatchery_graph::fusion::{Fuser, Member, Outside, Source};
use hatchery_graph::{NodeError, NodeInputs, NodeSchema, Params, PortType};
use shader::build;

mod recycle;
use std::hash::{DefaultHasher, Hash, Hasher};

mod shader;

/// The fusable node kind `kind` (as the modules declare them, [`crate::kinds::Kinds::image_stage`]).
pub fn fusable(kind: &str) -> Option<&'static dyn Fusable> {
    static STAGES: std::sync::OnceLock<Vec<(&'static str, &'static dyn Fusable)>> =
        std::sync::OnceLock::new();
    STAGES
        .get_or_init(|| {
            let stages = crate::kinds::Kinds::all().stages;
            stages.into_iter().map(|s| (s.schema().kind, s)).collect()
        })
        .iter()
        .find(|(k, _)| *k == kind)
        .map(|(_, s)| *s)
}

/// `Node::execute` of a fusable kind: the node as a pass of its own.
pub fn execute(
    node: &dyn Fusable,
    ctx: &mut Ctx,
    inputs: &NodeInputs<Value>,
    params: &Params,
) -> Result<Vec<Value>, NodeError> {
    let schema = node.schema();
    let sources: Vec<Source<Value>> = schema
        .inputs
        .iter()
        .map(|port| match inputs.get(port.name) {
            Some(value) => Source::External(value.clone()),
            None => Source::Absent,
        })
        .collect();
    let member = Member {
        id: "",
        kind: schema.kind,
        params,
        inputs: sources,
        keep: vec![true; schema.outputs.len()],
    };
    let mut outputs = run_group(ctx, &[member]).map_err(|(_, e)| e)?;
    Ok(outputs
        .pop()
        .unwrap_or_default()
        .into_iter()
        .flatten()
        .collect())
}

/// The executor's fuser for [`Ctx`].
pub struct ImageFuser;

impl Fuser<Value, Ctx> for ImageFuser {
    fn pointwise(&self, kind: &str, _params: &Params) -> Option<Vec<bool>> {
        fusable(kind).map(|node| node.pointwise().to_vec())
    }

    fn fits(&self, ctx: &Ctx, group: &[Member<'_, Outside<'_>>]) -> bool {
        let limits = ctx.gpu.device.limits();
        let mut textures = 0;
        let mut bound = std::collections::BTreeSet::new();
        let (mut targets, mut bytes) = (0, 0);
        for member in group {
            let Some(node) = fusable(member.kind) else {
                return false;
            };
            textures += node.own_textures();
            for source in &member.inputs {
                if let Source::External(outside) = source
                    && bound.insert((outside.node, outside.port))
                {
                    textures += match outside.ty {
                        PortType::GBuffer => 2,
                        PortType::Image | PortType::Mask => 1,
                        _ => 0,
                    };
                }
            }
            for _ in member.keep.iter().filter(|k| **k) {
                targets += 1;
                // The widest output (an Image) per kept port.
                bytes += IMAGE_FORMAT.target_pixel_byte_cost().unwrap_or(8);
            }
        }
        // A uniform block per member, one buffer: far below every adapter's limit for the
        // groups this cap allows.
        let outputs_fit = match ctx.image_kernel() {
            Kernel::Fragment => {
                targets <= limits.max_color_attachments
                    && bytes <= limits.max_color_attachment_bytes_per_sample
            }
            Kernel::Compute => targets <= limits.max_storage_textures_per_shader_stage,
        };
        group.len() <= 32 && textures <= limits.max_sampled_textures_per_shader_stage && outputs_fit
    }

    fn run(
        &self,
        ctx: &mut Ctx,
        group: &[Member<'_, Value>],
    ) -> Result<Vec<Vec<Option<Value>>>, (usize, NodeError)> {
        run_group(ctx, group)
    }
}

/// Runs `group` (stages in order) as one full-frame pass; per member, its output where `keep`
/// says. Errors name the member they belong to.
pub fn run_group(
    ctx: &mut Ctx,
    group: &[Member<'_, Value>],
) -> Result<Vec<Vec<Option<Value>>>, (usize, NodeError)> {
    let last = group.len().saturating_sub(1);
    let shader = build(ctx, group)?;
    let kernel = ctx.image_kernel();
    let source = shader.source(kernel).map_err(|e| (last, e))?;
    let formats: Vec<wgpu::TextureFormat> = shader.targets.iter().map(|(_, f)| *f).collect();
    let label = match group {
        [one] => fusable(one.kind).map_or("stage", |n| n.schema().kind),
        _ => "fused pass",
    };
    let members: Vec<&str> = group.iter().map(|m| m.id).collect();
    let (width, height) = ctx.size();
    let textures: Vec<&wgpu::Texture> = shader.bindings.iter().map(|b| &b.texture).collect();
    let uniform = (!shader.uniform_bytes.is_empty()).then_some(shader.uniform_bytes.as_slice());
    // A compile error of the pass: every member's stage is in it.
    let error = |e: hatchery_gpu::GpuError| {
        let message = match group {
            [_] => e.to_string(),
            _ => format!("the fused pass of {}: {e}", members.join(", ")),
        };
        (last, NodeError::new(message))
    };
    let targets: Vec<recycle::Target> = match kernel {
        Kernel::Fragment => {
            let pipeline = ctx
                .cached(&pipeline_key(&source, &formats), |gpu| {
                    let module = gpu.shader(label, &source)?;
                    gpu.checked(&format!("pipeline {label}"), |device| {
                        let stages = screen_pass::Stages {
                            vertex: &module,
                            fragment: &module,
                            entry: "fs_main",
                            constants: &[],
                        };
                        screen_pass::fullscreen_pipeline(
                            device, label, None, stages, &formats, None,
                        )
                    })
                })
                .map_err(error)?;
            let pool = recycle::Recycled::of(ctx).map_err(error)?;
            let gpu = &ctx.gpu;
            let bind_group = screen_pass::bind_group(gpu, label, &pipeline, &textures, uniform);
            let needs = wgpu::TextureUsages::RENDER_ATTACHMENT;
            let targets = pool.targets(&formats, (width, height), needs, IMAGE_FORMAT, |f| {
                gpu.render_target(label, width, height, f)
            });
            // A recycled target is loaded, not cleared: the full-screen triangle writes every
            // pixel unless a stage discards.
            let writes_all = !source.contains("discard");
            let attachments: Vec<(&wgpu::Texture, bool)> = targets
                .iter()
                .map(|t| (t.texture(), t.recycled && writes_all))
                .collect();
            let work =
                screen_pass::draw_into_loading(gpu, label, &pipeline, &[&bind_group], &attachments);
            ctx.submit(work);
            targets
        }
        Kernel::Compute => {
            let pipeline = ctx
                .cached(&pipeline_key(&source, &formats), |gpu| {
                    let module = gpu.shader(label, &source)?;
                    gpu.checked(&format!("pipeline {label}"), |device| {
                        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                            label: Some(label),
                            layout: None,
                            module: &module,
                            entry_point: Some("cs_main"),
                            compilation_options: Default::default(),
                            cache: None,
                        })
                    })
                })
                .map_err(error)?;
            let pool = recycle::Recycled::of(ctx).map_err(error)?;
            let gpu = &ctx.gpu;
            let needs = wgpu::TextureUsages::STORAGE_BINDING;
            let targets = pool.targets(&formats, (width, height), needs, IMAGE_FORMAT, |f| {
                gpu.storage_target(label, width, height, f)
            });
            let bound: Vec<&wgpu::Texture> = textures
                .iter()
                .copied()
                .chain(targets.iter().map(|t| t.texture()))
                .collect();
            let layout = pipeline.get_bind_group_layout(0);
            let bind_group = screen_pass::bind_group_with(gpu, label, &layout, &bound, uniform);
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some(label),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(width.div_ceil(8), height.div_ceil(8), 1);
            }
            ctx.submit(encoder.finish());
            targets
        }
    };

    let mut outputs: Vec<Vec<Option<Value>>> = group
        .iter()
        .map(|m| vec![None; m.keep.len().max(1)])
        .collect();
    for ((member, _), target) in shader.targets.iter().zip(targets) {
        outputs[*member][0] = Some(target.value);
    }
    Ok(outputs)
}

/// The cache key of a pass's pipeline: its source and target formats.
fn pipeline_key(source: &str, formats: &[wgpu::TextureFormat]) -> String {
    let mut hasher = DefaultHasher::new();
    (source, formats).hash(&mut hasher);
    format!("fused:{:016x}:{}", hasher.finish(), source.len())
}

impl crate::kinds::Kinds {
    /// An image-space kind that runs as a stage of a fused pass ([`crate::fused_pass`]): its
    /// node (whose `execute` runs it as a pass of its own) and its stage.
    #[track_caller]
    pub fn image_stage(&mut self, stage: &'static dyn Fusable) -> &mut Self {
        let file = std::panic::Location::caller().file();
        let kind = self.registry.register(ImageStage(stage));
        self.files.push((kind, file));
        self.stages.push(stage);
        self
    }
}

/// The one `Node` implementation of every fusable kind: the schema is the stage's, and
/// `execute` runs the node as a fused pass of one (so fused and unfused frames run the same
/// code).
struct ImageStage(&'static dyn Fusable);

impl Node<Value, Ctx> for ImageStage {
    fn schema(&self) -> NodeSchema {
        self.0.schema()
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        execute(self.0, ctx, inputs, p)
    }
}
