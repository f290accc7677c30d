//! One ray-casting pass: the pipeline, the bind group and the draw (see shaders/raycast.wgsl).

use super::bindings::{RayOutputs, StrokeBindings};
use super::tables::RayTables;
use super::uniforms::{RayShading, RayUniforms};
use super::{Kernel, RayOptions, Reconstruction};
use crate::Ctx;
use crate::camera::Camera;
use crate::gbuffer::NORMAL_FORMAT;
use crate::mesh_pass::DEPTH_FORMAT;
use crate::screen_pass::IMAGE_FORMAT;
use crate::value::{GBuffer, TransferFunction, Volume};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::NodeError;

/// Strokes embedded in a DVR (Yuan & Chen 2005 §5): their mask (coverage), the depth of the
/// surface they were drawn on, and their straight RGBA colour.
pub struct Strokes {
    pub mask: std::sync::Arc<crate::value::Mask>,
    pub depth: std::sync::Arc<GBuffer>,
    pub color: [f32; 4],
}

crate::uniform_block! {
    /// `Strokes` of shaders/raycast.wgsl: the embedded strokes' straight RGBA colour.
    pub struct StrokeUniforms in "raycast" as "Strokes" {
        pub color: [f32; 4],
    }
}

/// The static GPU objects of the ray caster.
pub struct Statics {
    pub sampler: wgpu::Sampler,
    /// Stand-ins for the tables a mode does not use.
    pub blank_table: wgpu::Texture,
    pub blank_styles: wgpu::Texture,
    pub blank_index: wgpu::Texture,
    pub blank_labels: wgpu::Texture,
    pub blank_label_rows: wgpu::Texture,
    /// 1×1 stand-ins when no strokes are embedded: a depth (cleared to 1) and a mask.
    pub blank_depth: wgpu::Texture,
    pub blank_mask: wgpu::Texture,
    /// A 1³ stand-in for the second and vector fields (Rgba16Float zeros).
    pub blank_field: wgpu::Texture,
}

/// A ray caster's pipelines: the full-screen fragment shader, the same rays as a compute kernel
/// (`cs_main`), and the pass that moves the kernel's r32float depths into the G-buffer's depth
/// texture.
pub struct RayPipelines {
    program: String,
    module: wgpu::ShaderModule,
    // Made on first use: a node runs one of the two paths, and each costs a shader compilation
    // (~150 ms for TwoLevelRaycast on lavapipe).
    render: std::sync::OnceLock<wgpu::RenderPipeline>,
    compute: std::sync::OnceLock<wgpu::ComputePipeline>,
    depth_copy: wgpu::RenderPipeline,
}

/// A full-screen triangle (`vs_main`) whose `fs_main` writes `targets` and the depth attachment
/// (always, no test): the ray casters' fragment path and the depth copy.
fn full_screen_pipeline(
    gpu: &GpuContext,
    name: &str,
    module: &wgpu::ShaderModule,
    targets: &[Option<wgpu::ColorTargetState>],
) -> Result<wgpu::RenderPipeline, GpuError> {
    gpu.checked(&format!("pipeline {name}"), |device| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(name),
            layout: None,
            vertex: wgpu::VertexState {
                module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: Default::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Always),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets,
            }),
            multiview_mask: None,
            cache: None,
        })
    })
}

impl RayPipelines {
    /// The pipelines of ray-casting program `program` (entry points `vs_main`/`fs_main` and
    /// `cs_main`, outputs as in shaders/raycast.wgsl).
    pub fn new(gpu: &GpuContext, program: &str) -> Result<Self, GpuError> {
        Self::specialised(gpu, program, &[])
    }

    /// [`Self::new`] with values for the program's `override` constants (raycast.wgsl's
    /// RAY_MODE and RAY_SHADING: one pipeline per mode and shading, see there), compiled as
    /// `const`s of a specialised source ([`crate::shaders::specialise`]).
    pub fn specialised(
        gpu: &GpuContext,
        program: &str,
        constants: &[(&str, f64)],
    ) -> Result<Self, GpuError> {
        let source = crate::kinds::source(program).expect("registered program");
        // The constants are written into the source (see `shaders::specialise`: lavapipe folds
        // `const`s better than pipeline-overridable constants).
        let source = crate::shaders::specialise(&source, constants).map_err(|message| {
            GpuError::Validation {
                what: format!("specialising {program}"),
                message,
            }
        })?;
        let module = gpu.shader(program, &source)?;
        let copy_source = crate::kinds::source("depth_from_texture").expect("registered program");
        let copy_module = gpu.shader("depth_from_texture", &copy_source)?;
        let depth_copy = full_screen_pipeline(gpu, "depth_from_texture", &copy_module, &[])?;
        Ok(Self {
            program: program.to_owned(),
            module,
            render: Default::default(),
            compute: Default::default(),
            depth_copy,
        })
    }

    /// The fragment path's pipeline, made on first use.
    fn render(&self, gpu: &GpuContext) -> Result<&wgpu::RenderPipeline, GpuError> {
        if let Some(p) = self.render.get() {
            return Ok(p);
        }
        let p = full_screen_pipeline(
            gpu,
            &self.program,
            &self.module,
            &[Some(IMAGE_FORMAT.into()), Some(NORMAL_FORMAT.into())],
        )?;
        Ok(self.render.get_or_init(|| p))
    }

    /// The compute path's pipeline, made on first use.
    fn compute(&self, gpu: &GpuContext) -> Result<&wgpu::ComputePipeline, GpuError> {
        if let Some(p) = self.compute.get() {
            return Ok(p);
        }
        let p = gpu.checked(&format!("pipeline {} (compute)", self.program), |device| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(&self.program),
                layout: None,
                module: &self.module,
                entry_point: Some("cs_main"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        Ok(self.compute.get_or_init(|| p))
    }
}

fn statics(gpu: &GpuContext) -> Result<Statics, GpuError> {
    let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("linear clamp"),
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Linear,
        ..Default::default()
    });
    let zeros = vec![0u8; 256 * 16];
    let blank_table = gpu.texture_2d_init(
        "blank table",
        256,
        1,
        wgpu::TextureFormat::Rgba32Float,
        &zeros,
    );
    let blank_styles = gpu.texture_2d_init(
        "blank styles",
        1,
        1,
        wgpu::TextureFormat::Rgba16Float,
        &[0u8; 8],
    );
    let blank_index = gpu.texture_2d_init(
        "blank index",
        1,
        1,
        wgpu::TextureFormat::R32Float,
        &[0u8; 4],
    );
    let blank_labels = gpu.texture_3d_init(
        "blank labels",
        [1, 1, 1],
        wgpu::TextureFormat::R8Unorm,
        &[0u8],
    );
    let blank_label_rows = gpu.texture_2d_init(
        "blank label rows",
        1,
        2,
        wgpu::TextureFormat::Rgba32Float,
        &[0u8; 32],
    );
    let blank_depth = gpu.render_target("blank stroke depth", 1, 1, DEPTH_FORMAT);
    let blank_mask = gpu.texture_2d_init(
        "blank stroke mask",
        1,
        1,
        wgpu::TextureFormat::R32Float,
        &[0u8; 4],
    );
    let blank_field = gpu.texture_3d_init(
        "blank field",
        [1, 1, 1],
        wgpu::TextureFormat::Rgba16Float,
        &[0u8; 8],
    );
    Ok(Statics {
        blank_field,
        sampler,
        blank_table,
        blank_styles,
        blank_index,
        blank_labels,
        blank_label_rows,
        blank_depth,
        blank_mask,
    })
}

/// Runs the ray caster; returns the image (premultiplied colour, `IMAGE_FORMAT`) and the
/// G-buffer where the accumulated opacity first reached `hit_opacity` (MIP: the maximum's
/// position; iso: the refined hit). Errors: see `RayTables::new`; GPU errors by name.
pub fn cast(
    ctx: &mut Ctx,
    volume: &Volume,
    camera: &Camera,
    tf: Option<&TransferFunction>,
    labels: Option<&Volume>,
    strokes: Option<&Strokes>,
    o: &RayOptions,
) -> Result<(wgpu::Texture, GBuffer), NodeError> {
    let err = |e: GpuError| NodeError::new(e.to_string());
    // A streamed volume: the region and level this view needs (see `value::stream`).
    let pool = ctx.gpu.volume_limits().map_err(err)?.pool_bytes;
    let (quick, mut coarse) = (ctx.coarse_first(), false);
    let (view, why) = volume
        .for_view(camera, pool, quick, &mut coarse)
        .map_err(|e| NodeError::new(e.to_string()))?;
    let whole = view.whole().cloned();
    let labels = match labels {
        Some(l) => Some(
            l.for_view(camera, pool, quick, &mut coarse)
                .map_err(|e| NodeError::new(e.to_string()))?
                .0,
        ),
        None => None,
    };
    if coarse {
        ctx.note_coarse();
    }
    if let Some(l) = &labels
        && l.whole().is_some() != view.whole().is_some()
    {
        return Err(NodeError::at_port(
            "labels",
            "one of the volume and its label volume is streamed (beyond HATCHERY_HOST_BUDGET_MB) \
             and the other is not: raise the budget so both load whole, or give both as \
             streamable files (OME-Zarr, .nii, .nrrd, .mha)",
        ));
    }
    if let Some(why) = why {
        ctx.warn(why);
    }
    // The level of detail the device holds (see `Volume::resident`).
    let input = volume;
    let volume = view.resident(&ctx.gpu).map_err(err)?;
    let labels = match &labels {
        Some(l) => Some(l.resident_labels(&ctx.gpu).map_err(err)?),
        None => None,
    };
    let st = ctx.cached("raycast.statics", statics).map_err(err)?;
    // The pre-integration table: rebuilt only when the function, step or ρ change.
    let preintegrated = match tf {
        Some(TransferFunction::Color(f)) if o.preintegrated => {
            use std::hash::{Hash, Hasher};
            let mut h = std::hash::DefaultHasher::new();
            f.lut
                .iter()
                .flatten()
                .for_each(|x| x.to_bits().hash(&mut h));
            (o.step_voxels.to_bits(), o.rho.to_bits()).hash(&mut h);
            Some(ctx.keep("preintegration", h.finish(), || {
                hatchery_data::preintegration::preintegrated_table(f, o.step_voxels, o.rho)
            }))
        }
        _ => None,
    };
    let gpu = &ctx.gpu;
    let volume_texture = volume.texture(gpu).map_err(err)?;
    let table = preintegrated.as_ref().map(|t| t.as_slice());
    let tables = RayTables::new(gpu, &st, volume, tf, labels, o, table)?;
    // Lighting TFs, context-preserving and style shading normalise |∇f| (eq. 5, 8, 2), and so
    // does boundary enhancement (Svakhine et al. 2005, Table 1).
    // The enhancements apply to DVR only: other modes get the pipeline without them.
    let enhancement = if o.mode == super::RayMode::Dvr {
        o.enhancement
    } else {
        super::Enhancement::OFF
    };
    let enhance = enhancement.bits();
    // A 2-D transfer function (DVR only; the Raycast node refuses it for the other modes).
    let (tf2d, second_domain) = match tf {
        Some(TransferFunction::TwoD(f)) if o.mode == super::RayMode::Dvr => {
            (super::Tf2dAxis::of(f.axis).code(), f.second_domain)
        }
        _ => (0, [0.0, 1.0]),
    };
    let max_gradient = if tables.info.shading.code() >= RayShading::Lighting.code()
        || enhance & super::EnhanceBit::Boundary.code() != 0
        || tf2d == super::Tf2dAxis::GradientMagnitude.code()
    {
        volume.max_gradient()
    } else {
        1.0
    };
    let uniforms = RayUniforms::new(
        camera,
        &volume.data,
        o,
        &tables.info,
        max_gradient,
        volume_texture.texel_range,
    )
    .with_bricks(volume_texture.layout.as_ref());
    let uniforms = match &whole {
        Some(w) => {
            let grid = super::uniforms::Grid {
                dims: w.dims,
                geometry: &w.geometry,
                value_range: volume.data.value_range,
            };
            uniforms.with_whole_grid(camera, &grid)
        }
        None => uniforms,
    };
    let uniform = gpu.buffer_init(
        "raycast",
        bytemuck::bytes_of(&uniforms),
        wgpu::BufferUsages::UNIFORM,
    );
    if let Some(s) = strokes {
        let (w, h) = (s.mask.texture.width(), s.mask.texture.height());
        if (w, h) != (camera.width, camera.height) {
            return Err(NodeError::at_port(
                "strokes",
                format!(
                    "{w}×{h} pixels, the frame {}×{}",
                    camera.width, camera.height
                ),
            ));
        }
        let c = &s.depth.camera;
        let same_view = (c.width, c.height) == (camera.width, camera.height)
            && c.view.abs_diff_eq(camera.view, 1e-5)
            && c.proj.abs_diff_eq(camera.proj, 1e-5);
        if !same_view {
            return Err(NodeError::at_port(
                "strokes_depth",
                "rendered with another camera or size than this node's: connect the same camera",
            ));
        }
    }
    let stroke_uniforms = StrokeUniforms {
        color: strokes.map_or([0.0; 4], |s| s.color),
    };
    let strokes_buffer = gpu.buffer_init(
        "strokes",
        bytemuck::bytes_of(&stroke_uniforms),
        wgpu::BufferUsages::UNIFORM,
    );
    let levels = Levels {
        input,
        resident: volume,
        streamed: whole.is_some(),
    };
    let fields = Fields::bind(gpu, &levels, tf2d, &enhancement, o)?;
    let enhancement_buffer = gpu.buffer_init(
        "enhancement",
        bytemuck::bytes_of(&super::EnhancementUniforms {
            second_domain,
            second_range: fields.second_range,
            ..enhancement.uniforms()
        }),
        wgpu::BufferUsages::UNIFORM,
    );
    let depth_only = wgpu::TextureViewDescriptor {
        aspect: wgpu::TextureAspect::DepthOnly,
        ..Default::default()
    };
    let stroke_depth_view = strokes
        .map_or(&st.blank_depth, |s| &s.depth.depth)
        .create_view(&depth_only);
    let stroke_mask_view = strokes
        .map_or(&st.blank_mask, |s| &s.mask.texture)
        .create_view(&Default::default());
    // A streamed volume's bricks are not all in memory to check: it may hold "no data".
    let no_data = u8::from(whole.is_some() || input.has_no_data() || volume.has_no_data());
    // The B-spline reads x-quads where fetches are software loops (value/bspline_quads.rs);
    // they have no "no data" guard.
    let quads = match o.reconstruction {
        Reconstruction::Bspline if no_data == 0 => volume.bspline_quads(gpu).map_err(err)?,
        _ => None,
    };
    let volume_view = quads
        .unwrap_or(&volume_texture.texture)
        .create_view(&Default::default());
    let page_view = volume_texture.page_table.create_view(&Default::default());
    let shared = tables.bindings(&uniform, &volume_view, &page_view, &st.sampler);
    let view = |t: Option<&wgpu::Texture>| {
        t.unwrap_or(&st.blank_field)
            .create_view(&Default::default())
    };
    let (second_view, vector_view) = (view(fields.second), view(fields.vector));
    let own = StrokeBindings {
        stroke_depth: Some(&stroke_depth_view),
        stroke_mask: Some(&stroke_mask_view),
        strokes: Some(&strokes_buffer),
        enhancement: Some(&enhancement_buffer),
        second_field: Some(&second_view),
        vector_field: Some(&vector_view),
    };
    // One pipeline per mode, shading, projection, exponent, bricking and set of enhancements (the
    // pipeline constants of raycast.wgsl and ray_common.wgsl).
    let (mode, shading, bricked) = (uniforms.mode, uniforms.shading, uniforms.bricked);
    // Schlick's exponent matters to context-preserving shading only: one pipeline otherwise.
    let orthographic = uniforms.orthographic;
    let fast = if shading == RayShading::ContextPreserving.code() {
        uniforms.fast_exponent
    } else {
        0
    };
    let reconstruction = o.reconstruction.code();
    let read_quads = u8::from(quads.is_some());
    let preintegrated = u8::from(o.preintegrated);
    let field = fields.measured;
    let pipelines = ctx
        .cached(
            &format!(
                "raycast.pipelines.{mode}.{shading}.{orthographic}.{fast}.{bricked}.{reconstruction}.{read_quads}.{no_data}.{preintegrated}.{enhance}.{field}.{tf2d}"
            ),
            |gpu| {
                let constants = [
                    ("RAY_MODE", mode as f64),
                    ("RAY_SHADING", shading as f64),
                    ("RAY_ORTHOGRAPHIC", orthographic as f64),
                    ("RAY_FAST_EXPONENT", fast as f64),
                    ("RAY_BRICKED", bricked as f64),
                    o.reconstruction.constant(),
                    ("RAY_BSPLINE_QUADS", f64::from(read_quads)),
                    ("RAY_NO_DATA", f64::from(no_data)),
                    ("RAY_PREINTEGRATED", f64::from(preintegrated)),
                    ("RAY_ENHANCE", f64::from(enhance)),
                    ("RAY_TF2D", f64::from(tf2d)),
                    ("RAY_ENHANCE_FIELD", f64::from(field)),
                ];
                RayPipelines::specialised(gpu, "raycast", &constants)
            },
        )
        .map_err(err)?;
    pipelines.run(ctx, camera, [shared.entries(), own.entries()], o.kernel)
}

/// The second and vector fields one pass reads (Svakhine et al. 2005 §3.2–3.3; `None`: the
/// pass does not read it, a blank stands in).
struct Fields<'a> {
    second: Option<&'a wgpu::Texture>,
    vector: Option<&'a wgpu::Texture>,
    /// The second field's value range (`EnhancementUniforms::second_range`).
    second_range: [f32; 2],
    /// `RAY_ENHANCE_FIELD` (an `EnhanceField` code).
    measured: u32,
}

/// The volume as the node got it and as the device holds it (a coarser level where the brick
/// pool cannot hold it whole), and whether it streams.
struct Levels<'v> {
    input: &'v Volume,
    resident: &'v Volume,
    streamed: bool,
}

impl<'a> Fields<'a> {
    /// The fields that a 2-D transfer function over a second field (`tf2d`) and boundary or
    /// silhouette enhancement of `enhancement.field` need, from `o`. Errors: a needed input is
    /// missing, lies on another grid than the volume, or the volume renders at a coarser level
    /// or streams (the fields are whole textures on the volume's full grid); each names its
    /// port.
    fn bind(
        gpu: &GpuContext,
        levels: &Levels,
        tf2d: u32,
        enhancement: &super::Enhancement,
        o: &RayOptions<'a>,
    ) -> Result<Self, NodeError> {
        let (volume, streamed) = (levels.input, levels.streamed);
        use super::EnhanceField;
        let err = |e: GpuError| NodeError::new(e.to_string());
        let measured = enhancement.measured_field();
        let needs_second = tf2d == super::Tf2dAxis::SecondField.code()
            || measured == Some(EnhanceField::Second);
        let needs_vector = measured == Some(EnhanceField::Vector);
        let mut fields = Fields {
            second: None,
            vector: None,
            second_range: [0.0, 1.0],
            measured: measured.map_or(0, |f| f.code()),
        };
        let why = if tf2d == super::Tf2dAxis::SecondField.code() {
            "the 2-D transfer function's axis is second_field"
        } else {
            "enhancement_field is second"
        };
        let port = if needs_second { "second" } else { "vector" };
        if (needs_second || needs_vector) && streamed {
            return Err(NodeError::at_port(
                port,
                "the volume is streamed (beyond HATCHERY_HOST_BUDGET_MB): second and vector \
                 fields need it whole on the device; raise the budget",
            ));
        }
        if (needs_second || needs_vector) && levels.resident.data.dims != volume.data.dims {
            return Err(NodeError::at_port(
                port,
                format!(
                    "the volume renders at a coarser level ({:?} of {:?} voxels: the device's \
                     brick pool cannot hold it whole), and second and vector fields are read on \
                     its full grid: render a smaller volume or raise the pool \
                     (HATCHERY_GPU_POOL_MB)",
                    levels.resident.data.dims, volume.data.dims
                ),
            ));
        }
        if needs_second {
            let Some(second) = o.second_field else {
                return Err(NodeError::at_port(
                    "second",
                    format!("{why}: connect the second scalar field (on the volume's grid)"),
                ));
            };
            let d = &second.data;
            super::tables::check_grid_at("second", "the second field", d.dims, &d.geometry, volume)?;
            fields.second = Some(second.second_field_texture(gpu).map_err(err)?);
            fields.second_range = d.value_range;
        }
        if needs_vector {
            let Some(vector) = o.vector_field else {
                return Err(NodeError::at_port(
                    "vector",
                    "enhancement_field is vector: connect a vector field (on the volume's grid)",
                ));
            };
            let d = &vector.data;
            super::tables::check_grid_at("vector", "the vector field", d.dims, &d.geometry, volume)?;
            fields.vector = Some(vector.texture(gpu).map_err(err)?.0);
        }
        Ok(fields)
    }
}

impl RayPipelines {
    /// Casts the rays of `camera`'s frame on `kernel`'s path with bind groups 0 (the shared
    /// [`RayBindings`](super::RayBindings)) and 1 (the program's own) made of `groups`' entries
    /// (against the auto-derived layout of the pipeline that runs). Returns the image and the
    /// G-buffer.
    pub fn run(
        &self,
        ctx: &mut Ctx,
        camera: &Camera,
        groups: [Vec<wgpu::BindGroupEntry>; 2],
        kernel: Kernel,
    ) -> Result<(wgpu::Texture, GBuffer), NodeError> {
        // Auto-derived layouts differ per pipeline object: bind against the one that runs. A
        // binding the program reads but `groups` lacks is a validation error: report it on the
        // node instead of drawing nothing.
        let err = |e: GpuError| NodeError::new(e.to_string());
        match kernel {
            Kernel::Compute => {
                let pipeline = self.compute(&ctx.gpu).map_err(err)?;
                let layout_of = |i| pipeline.get_bind_group_layout(i);
                let bind_groups =
                    crate::bindings::bind_groups(&ctx.gpu, "ray caster", layout_of, &groups)
                        .map_err(err)?;
                self.cast_compute(ctx, camera, &bind_groups, pipeline)
            }
            Kernel::Fragment => {
                let pipeline = self.render(&ctx.gpu).map_err(err)?;
                let layout_of = |i| pipeline.get_bind_group_layout(i);
                let bind_groups =
                    crate::bindings::bind_groups(&ctx.gpu, "ray caster", layout_of, &groups)
                        .map_err(err)?;
                self.cast_fragment(ctx, camera, &bind_groups, pipeline)
            }
        }
    }

    /// The fragment path: one full-screen triangle into colour, normal and depth attachments.
    fn cast_fragment(
        &self,
        ctx: &mut Ctx,
        camera: &Camera,
        bind_groups: &[wgpu::BindGroup],
        pipeline: &wgpu::RenderPipeline,
    ) -> Result<(wgpu::Texture, GBuffer), NodeError> {
        let gpu = &ctx.gpu;
        let (w, h) = (camera.width, camera.height);
        let image = gpu.render_target("raycast image", w, h, IMAGE_FORMAT);
        let normal = gpu.render_target("raycast normal", w, h, NORMAL_FORMAT);
        let depth = gpu.render_target("raycast depth", w, h, DEPTH_FORMAT);
        let (image_view, normal_view, depth_view) = (
            image.create_view(&Default::default()),
            normal.create_view(&Default::default()),
            depth.create_view(&Default::default()),
        );
        let clear = |view| {
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })
        };
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("raycast"),
                color_attachments: &[clear(&image_view), clear(&normal_view)],
                depth_stencil_attachment: Some(crate::mesh_pass::cleared_depth(&depth_view)),
                ..Default::default()
            });
            pass.set_pipeline(pipeline);
            for (i, group) in bind_groups.iter().enumerate() {
                pass.set_bind_group(i as u32, group, &[]);
            }
            pass.draw(0..3, 0..1);
        }
        ctx.submit(encoder.finish());
        Ok((
            image,
            GBuffer {
                depth,
                normal,
                camera: camera.clone(),
            },
        ))
    }

    /// The compute path: 8×8-pixel workgroups write colour, normal and depth to storage
    /// textures; a full-screen pass then writes the depths into the G-buffer's depth texture.
    fn cast_compute(
        &self,
        ctx: &mut Ctx,
        camera: &Camera,
        bind_groups: &[wgpu::BindGroup],
        pipeline: &wgpu::ComputePipeline,
    ) -> Result<(wgpu::Texture, GBuffer), NodeError> {
        let gpu = &ctx.gpu;
        let (w, h) = (camera.width, camera.height);
        let image = gpu.storage_target("raycast image", w, h, IMAGE_FORMAT);
        let normal = gpu.storage_target("raycast normal", w, h, NORMAL_FORMAT);
        let depth_values =
            gpu.storage_target("raycast depth values", w, h, wgpu::TextureFormat::R32Float);
        let depth = gpu.render_target("raycast depth", w, h, DEPTH_FORMAT);
        let views = [&image, &normal, &depth_values].map(|t| t.create_view(&Default::default()));
        let outputs = RayOutputs {
            out_color: Some(&views[0]),
            out_normal: Some(&views[1]),
            out_depth: Some(&views[2]),
        };
        let outputs = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("raycast outputs"),
            layout: &pipeline.get_bind_group_layout(RayOutputs::GROUP),
            entries: &outputs.entries(),
        });
        let copy_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("depth from texture"),
            layout: &self.depth_copy.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&views[2]),
            }],
        });
        let depth_view = depth.create_view(&Default::default());
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("raycast compute"),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            for (i, group) in bind_groups.iter().enumerate() {
                pass.set_bind_group(i as u32, group, &[]);
            }
            pass.set_bind_group(RayOutputs::GROUP, &outputs, &[]);
            pass.dispatch_workgroups(w.div_ceil(8), h.div_ceil(8), 1);
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("depth from texture"),
                color_attachments: &[],
                depth_stencil_attachment: Some(crate::mesh_pass::cleared_depth(&depth_view)),
                ..Default::default()
            });
            pass.set_pipeline(&self.depth_copy);
            pass.set_bind_group(0, &copy_group, &[]);
            pass.draw(0..3, 0..1);
        }
        ctx.submit(encoder.finish());
        Ok((
            image,
            GBuffer {
                depth,
                normal,
                camera: camera.clone(),
            },
        ))
    }
}
