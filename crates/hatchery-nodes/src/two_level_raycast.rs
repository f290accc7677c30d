//! `TwoLevelRaycast`: two-level volume rendering of a segmented volume (Hadwiger §2.2–2.4) —
//! per-object transfer functions, rendering and local compositing modes, combined along each
//! ray by a global compositing mode (see shaders/two_level_raycast.wgsl).

use crate::camera::Camera;
use crate::raycast::objects::{
    ObjectBindings, TABLE_WIDTH, TwoLevelUniforms, brick_table, check_labels_grid, object_tables,
};
use crate::raycast::{
    ImportanceBindings, ImportancePipelines, Kernel, KernelChoice, PhongParams, RayBindings, RayOptions, RayPipelines, RayShading, RayUniforms, TableInfo,
};
use crate::value::{
    Compositing, Image, Importance, ImportanceMethod, ObjectStyle, RenderMode,
};
use crate::{Ctx, Value};
use hatchery_data::transfer_function::LUT_SIZE;
use hatchery_gpu::GpuError;
use hatchery_graph::{
    Group, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// The sparse style's rendering mode and local compositing: `RenderMode` and `Compositing` codes.
fn sparse_codes(mode: SparseMode, compositing: SparseCompositing) -> [u32; 2] {
    let mode = match mode {
        SparseMode::Dvr => RenderMode::Dvr,
        SparseMode::ShadedDvr => RenderMode::ShadedDvr,
        SparseMode::Tone => RenderMode::Tone,
        SparseMode::Mip => RenderMode::Mip,
        SparseMode::Contours => RenderMode::Contours,
    };
    let compositing = match compositing {
        SparseCompositing::Over => Compositing::Over,
        SparseCompositing::Sum => Compositing::Sum,
        SparseCompositing::Mip => Compositing::Mip,
    };
    [mode.code(), compositing.code()]
}

/// The importance input, checked against this node's view; `styles` then take their
/// importance from it (the sums were made with those values).
fn importance_input(
    inputs: &NodeInputs<Value>,
    camera: &Camera,
    styles: &mut [ObjectStyle],
) -> Result<Option<Arc<Importance>>, NodeError> {
    let Some(value) = inputs.get("importance") else {
        return Ok(None);
    };
    let importance = value.importance("importance")?.clone();
    let c = &importance.camera;
    let same = c.width == camera.width
        && c.height == camera.height
        && c.view.abs_diff_eq(camera.view, 1e-5)
        && c.proj.abs_diff_eq(camera.proj, 1e-5);
    if !same {
        return Err(NodeError::at_port(
            "importance",
            format!(
                "made for another view ({}×{}, or other view/projection matrices) than this \
                 node's camera ({}×{}): connect the same camera to ImportanceCompositing",
                c.width, c.height, camera.width, camera.height
            ),
        ));
    }
    let mut missing = Vec::new();
    for s in styles.iter_mut() {
        match importance.importance.iter().find(|(id, _)| *id == s.id) {
            Some((_, i)) => s.importance = *i,
            None => {
                s.importance = 0.0;
                if s.enabled {
                    missing.push(s.id.to_string());
                }
            }
        }
    }
    if !missing.is_empty() {
        return Err(NodeError::at_port(
            "importance",
            format!(
                "objects {} are drawn here but not in ImportanceCompositing's object table: \
                 connect the same ObjectStyles to both",
                missing.join(", ")
            ),
        ));
    }
    Ok(Some(importance))
}

hatchery_graph::param_choice! {
    /// Global compositing of the segments.
    pub enum Global { Over = "over", Mip = "mip", Sum = "sum" }
}

crate::wgsl_constants! {
    Global in "two_level_raycast" { Over = "GLOBAL_OVER", Mip = "GLOBAL_MIP", Sum = "GLOBAL_SUM" }
}

hatchery_graph::param_choice! {
    /// Object membership: filtered binary masks (§2.3) or the nearest voxel's id.
    pub enum Boundary { Filtered = "filtered", Point = "point" }
}

hatchery_graph::param_choice! {
    /// Shading normals from the data's gradient, or from each object's filtered mask (for label
    /// maps without intensities).
    pub enum Normals { Data = "data", Objects = "objects" }
}

hatchery_graph::param_choice! {
    /// With `importance` (AImC): how a level of sparseness S shows — opacity × S, opacity and
    /// colour saturation × S, a screen door keeping S of the voxels, a sparse rendering style
    /// where S < 1, or volume thinning (Viola et al. §V.C: only the context's strongest samples,
    /// by gradient then curvature magnitude, kept).
    pub enum Sparseness {
        Opacity = "opacity",
        Saturation = "saturation",
        ScreenDoor = "screen_door",
        Style = "style",
        Thinning = "thinning",
    }
}

crate::wgsl_constants! {
    Sparseness in "two_level_raycast" {
        Opacity = "SPARSE_OPACITY",
        Saturation = "SPARSE_SATURATION",
        ScreenDoor = "SPARSE_SCREEN_DOOR",
        Style = "SPARSE_STYLE",
        Thinning = "SPARSE_THINNING",
    }
}

hatchery_graph::param_choice! {
    /// The sparse style's rendering mode.
    pub enum SparseMode {
        Contours = "contours",
        Dvr = "dvr",
        ShadedDvr = "shaded_dvr",
        Tone = "tone",
        Mip = "mip",
    }
}

hatchery_graph::param_choice! {
    /// The sparse style's local compositing.
    pub enum SparseCompositing { Mip = "mip", Over = "over", Sum = "sum" }
}

hatchery_graph::node_params! {
    /// Parameters of `TwoLevelRaycast`.
    pub struct TwoLevelRaycastParams {
        /// global compositing of the segments
        pub global: Global = Global::Over;
        /// object membership: filtered binary masks (§2.3) or the nearest voxel's id
        pub boundary: Boundary = Boundary::Filtered;
        /// shading normals from the data's gradient, or from each object's filtered mask (for label
        /// maps without intensities)
        pub normals: Normals = Normals::Data;
        /// with normals `objects`: the normals of iso-surfaces averaged over ±this many voxels
        /// (the 3-D Sobel operator of the object's mask at this spacing), so a label map
        /// segmented slice by slice does not show every slice as a terrace; 0: central
        /// differences of neighbouring voxels
        pub surface_smoothing: f32 = 0.0, range(0.0, 4.0);
        /// sample distance in voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// reconstruction of the data between voxels: trilinear, or the tricubic B-spline's
        /// values and gradients (Hadwiger §1.3)
        pub reconstruction: crate::reconstruction::Reconstruction =
            crate::reconstruction::Reconstruction::Trilinear;
        pub phong: PhongParams = Group;
        /// jitter the first sample per pixel
        pub jitter: bool = true;
        /// stop a ray at this opacity with global over (1 = never)
        pub early_termination: f32 = 0.99, range(0.5, 1.0);
        /// jump over 8³-voxel bricks that no drawn object reaches — same picture, fewer samples
        pub skip_empty: bool = true;
        /// GPU path: fragment shader or compute kernel (same picture)
        pub kernel: KernelChoice = KernelChoice::Auto;
        /// with `importance` (AImC): how a level of sparseness S shows — opacity × S, opacity and
        /// colour saturation × S, a screen door keeping S of the voxels, a sparse rendering
        /// style where S < 1, or volume thinning (a context sample kept only where its strength
        /// key, gradient-magnitude level then curvature magnitude, exceeds 1 − S)
        pub sparseness: Sparseness = Sparseness::Opacity;
        /// the sparse style's rendering mode
        pub sparse_mode: SparseMode = SparseMode::Contours;
        /// the sparse style's local compositing
        pub sparse_compositing: SparseCompositing = SparseCompositing::Mip;
        /// volume thinning: levels B of the normalised gradient magnitude, the first sorting
        /// key; within a level the curvature magnitude orders the samples (1: curvature alone)
        pub thinning_levels: u32 = 4, range(1, 64);
    }
}

/// 1×1 textures bound where a pass has nothing to read, made once per device: `one` (1, 1, 1, 1)
/// for no importance, no countersink and no occluder; `zero` for the lighting TF of
/// shade_surface's `lighting` branch, which two-level never takes.
struct Placeholders {
    one: wgpu::Texture,
    zero: wgpu::Texture,
    /// A 1³ 3-D texture for the gradients when thinning does not read them.
    grid: wgpu::Texture,
}

impl Placeholders {
    fn new(gpu: &hatchery_gpu::GpuContext) -> Self {
        let texture = |label, value: f32| {
            gpu.texture_2d_init(
                label,
                1,
                1,
                wgpu::TextureFormat::Rgba32Float,
                bytemuck::cast_slice(&[value; 4]),
            )
        };
        Placeholders {
            one: texture("two-level placeholder (1)", 1.0),
            zero: texture("two-level placeholder (0)", 0.0),
            // Rgba16Float: filterable on every device, as the binding is sampled.
            grid: gpu.texture_3d_init(
                "two-level placeholder (3-D)",
                [1, 1, 1],
                wgpu::TextureFormat::Rgba16Float,
                &[0u8; 8],
            ),
        }
    }
}

pub struct TwoLevelRaycastNode;

impl Node<Value, Ctx> for TwoLevelRaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "TwoLevelRaycast",
            category: "Volume",
            doc: "Two-level volume rendering of a segmented volume (Hadwiger §2.2–2.4): each ray \
                  is split into segments where it passes through one object (object membership \
                  by boundary filtering, §2.3: each object's binary mask filtered trilinearly \
                  and thresholded at 0.5); each segment is composited with its object's local \
                  mode and rendering mode from ObjectStyles, and the segments are combined front \
                  to back with the global mode: over, mip (per-channel maximum) or sum. Same \
                  camera, light and jitter rules as Raycast.",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input(
                    "labels",
                    PortType::Labels,
                    "object ids on the volume's grid",
                ),
                PortSpec::input("styles", PortType::ObjectStyles, "the object table"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::optional("light", PortType::Light, "the light (default: a headlight)"),
                PortSpec::optional(
                    "importance",
                    PortType::Importance,
                    "importance-driven rendering: ImportanceCompositing of the same view",
                ),
            ],
            outputs: vec![
                PortSpec::output("image", PortType::Image, "premultiplied colour"),
                PortSpec::output(
                    "gbuffer",
                    PortType::GBuffer,
                    "depth and normal of the first visible segment",
                ),
            ],
            params: TwoLevelRaycastParams::specs(),
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
        let params = TwoLevelRaycastParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        // The level of detail the device holds (see `Volume::resident`).
        let volume = volume.resident(&ctx.gpu).map_err(|e| NodeError::new(e.to_string()))?;
        let labels = labels.resident(&ctx.gpu).map_err(|e| NodeError::new(e.to_string()))?;
        let mut styles: Vec<ObjectStyle> =
            inputs.require("styles")?.object_styles("styles")?.to_vec();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let importance = importance_input(inputs, &camera, &mut styles)?;
        check_labels_grid(labels, volume)?;
        let v = &volume.data;
        if !styles.iter().any(|s| s.enabled) {
            ctx.warn("no object of the table is enabled: the picture is empty");
        }
        let kernel = Kernel::choose(params.kernel, &ctx.gpu);
        let options = RayOptions {
            shading: RayShading::Phong,
            phong: params.phong.values(),
            ..RayOptions::plain(
                params.step,
                params.jitter,
                params.early_termination,
                crate::raycast::light_direction(inputs, &camera)?,
                kernel,
            )
        };
        let info = TableInfo {
            shading: RayShading::Phong,
            skip_empty: params.skip_empty,
            ..TableInfo::plain()
        };
        let err = |e: GpuError| NodeError::new(e.to_string());
        let filtered = params.boundary != Boundary::Point;
        let [sparse_mode, sparse_local] =
            sparse_codes(params.sparse_mode, params.sparse_compositing);
        let object_normals = params.normals == Normals::Objects;
        // What the march needs as pipeline constants (shaders/two_level_raycast.wgsl): bricked
        // or not, the global mode, the importance method, the boundary filter, the normals, and
        // which rendering and compositing modes the drawn objects (and the sparse style) use —
        // the branches of the others are folded away.
        let bricked = volume.texture(&ctx.gpu).map_err(err)?.layout.is_some();
        let (mut modes, mut locals) = (0i32, 0i32);
        for s in styles.iter().filter(|s| s.enabled) {
            modes |= 1 << s.mode.code();
            locals |= 1 << s.compositing.code();
        }
        if importance.is_some() {
            modes |= 1 << sparse_mode;
            locals |= 1 << sparse_local;
        }
        let method = importance.as_ref().map_or(0, |i| i.method.code());
        let thinning = importance.is_some() && params.sparseness == Sparseness::Thinning;
        // The key's gradients from one fetch each, where the device keeps them (CPU adapters).
        // (Trilinear only: the B-spline takes its own derivatives.)
        let reconstruction = params.reconstruction.on(ctx, &volume.data);
        let trilinear = reconstruction == crate::reconstruction::Reconstruction::Trilinear;
        let thin_gradients = match thinning && trilinear {
            true => volume.gradient_texture(&ctx.gpu).map_err(err)?,
            false => None,
        };
        let (ids, id_quads) =
            crate::raycast::objects::object_id_texture(&ctx.gpu, labels, bricked).map_err(err)?;
        let constants = [
            ("RAY_BRICKED", f64::from(u8::from(bricked))),
            ("RAY_NO_DATA", f64::from(u8::from(volume.has_no_data()))),
            reconstruction.constant(),
            ("TL_GLOBAL", f64::from(params.global.code())),
            ("TL_METHOD", f64::from(method)),
            ("TL_FILTER", f64::from(u8::from(filtered))),
            ("TL_MASK_NORMALS", f64::from(u8::from(object_normals))),
            ("TL_MODES", f64::from(modes)),
            ("TL_LOCALS", f64::from(locals)),
            ("TL_THINNING", f64::from(u8::from(thinning))),
            ("TL_THIN_GRADIENTS", f64::from(u8::from(thin_gradients.is_some()))),
            id_quads,
        ];
        let key = constants.iter().map(|(_, v)| v.to_string()).collect::<Vec<_>>().join(".");
        let pipelines = ctx
            .cached(&format!("two_level_raycast.pipelines.{key}"), |gpu| {
                RayPipelines::specialised(gpu, "two_level_raycast", &constants)
            })
            .map_err(err)?;
        let sampler = crate::raycast::linear_clamp_sampler(ctx).map_err(err)?;
        let placeholders = ctx
            .cached("two_level.placeholders", |gpu| Ok(Placeholders::new(gpu)))
            .map_err(err)?;
        let min_spacing = v.spacing().iter().copied().fold(f32::INFINITY, f32::min);
        let tables = object_tables(&styles);
        let thin_ranks = thinning.then(|| {
            let key = hatchery_data::thinning::KeyParams {
                bands: params.thinning_levels as f32,
                inv_max_gradient: 1.0 / volume.max_gradient().max(1e-20),
                step: min_spacing,
            };
            let rows = tables.columns;
            if params.reconstruction == crate::reconstruction::Reconstruction::Bspline {
                ctx.warn(
                    "volume thinning ranks each object's voxels by keys from central differences; \
                     the B-spline's own keys order them slightly differently, so the kept fraction \
                     is close to the level of sparseness, not exact (trilinear: exact)",
                );
            }
            thinning_ranks(ctx, volume, labels, rows, key)
        });
        let gpu = &ctx.gpu;
        let volume_texture = volume.texture(gpu).map_err(err)?;
        let max_gradient =
            crate::raycast::objects::segmented_max_gradient(volume, &styles, object_normals);
        let uniforms = RayUniforms::new(
            &camera,
            v,
            &options,
            &info,
            max_gradient,
            volume_texture.texel_range,
        )
        .with_bricks(volume_texture.layout.as_ref());
        let limit = gpu.device.limits().max_texture_dimension_2d;
        if tables.rows > limit {
            return Err(NodeError::at_port(
                "styles",
                format!(
                    "{} objects are drawn, more than this adapter's limit of {limit} transfer functions",
                    tables.rows
                ),
            ));
        }
        let two_level = |first_pass: bool| TwoLevelUniforms {
            global_mode: params.global.code(),
            boundary_filter: filtered.into(),
            columns: tables.columns,
            mask_normals: object_normals.into(),
            method,
            level: importance.as_ref().map_or(0, |_| params.sparseness.code()),
            focus: importance.as_ref().map_or(0, |i| u32::from(i.focus)),
            first_pass: (importance.is_some() && first_pass).into(),
            sparse_mode,
            sparse_local,
            // A cut shades the context down to 1.5 voxels behind it.
            cut_band: 1.5 * min_spacing,
            surface_smoothing: if object_normals {
                params.surface_smoothing
            } else {
                0.0
            },
            thin_gradient: if thinning {
                1.0 / volume.max_gradient().max(1e-20)
            } else {
                0.0
            },
            thin_step: min_spacing,
            thin_bands: params.thinning_levels as f32,
            pad0: 0.0,
        };
        let ray_buffer = gpu.buffer_init(
            "two-level ray",
            bytemuck::bytes_of(&uniforms),
            wgpu::BufferUsages::UNIFORM,
        );
        let two_level_buffer = |first_pass| {
            gpu.buffer_init(
                "two-level",
                bytemuck::bytes_of(&two_level(first_pass)),
                wgpu::BufferUsages::UNIFORM,
            )
        };
        let tf_texture = gpu.texture_2d_init(
            "object tfs",
            LUT_SIZE as u32,
            tables.rows,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&tables.tf_rows),
        );
        let table_texture = gpu.texture_2d_init(
            "object table",
            TABLE_WIDTH,
            (tables.table.len() / 4) as u32 / TABLE_WIDTH,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&tables.table),
        );
        let mut drawn: Vec<u16> = styles.iter().filter(|s| s.enabled).map(|s| s.id).collect();
        drawn.sort_unstable();
        let drawn_mask = labels.drawn_mask(gpu, &drawn).map_err(err)?;
        let (brick_dims, brick_ranges) = brick_table(labels, &styles);
        let brick_texture = gpu.texture_3d_init(
            "object bricks",
            brick_dims,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&brick_ranges),
        );
        let views = [
            volume_texture.texture.create_view(&Default::default()),
            tf_texture.create_view(&Default::default()),
            ids.create_view(&Default::default()),
            table_texture.create_view(&Default::default()),
            brick_texture.create_view(&Default::default()),
            drawn_mask.texture.create_view(&Default::default()),
            placeholders.zero.create_view(&Default::default()),
            volume_texture.page_table.create_view(&Default::default()),
        ];
        let one = || placeholders.one.create_view(&Default::default());
        let (importance_view, cut_view) = match &importance {
            Some(i) => (
                i.buffer.create_view(&Default::default()),
                i.cut.create_view(&Default::default()),
            ),
            None => (one(), one()),
        };
        let no_occluder = one();
        let ranks_view = thin_ranks
            .as_ref()
            .map_or_else(one, |t| t.create_view(&Default::default()));
        let gradients_view = thin_gradients
            .unwrap_or(&placeholders.grid)
            .create_view(&Default::default());
        let shared = RayBindings {
            ray: Some(&ray_buffer),
            volume: Some(&views[0]),
            linear_clamp: Some(&sampler),
            tf_table: Some(&views[1]),
            // The lighting TF of shade_surface's `lighting` branch, which two-level never takes.
            lighting_table: Some(&views[6]),
            bricks: Some(&views[4]),
            page_table: Some(&views[7]),
            ..Default::default()
        };
        // Group 1: the object tables, then this program's own bindings.
        let own = |two_level, occluder| {
            let objects = ObjectBindings {
                object_ids: Some(&views[2]),
                objects: Some(&views[3]),
                two_level: Some(two_level),
                drawn_mask: Some(&views[5]),
            };
            let importance = TwoLevelBindings {
                importance_buffer: Some(&importance_view),
                importance_cut: Some(&cut_view),
                occluder_stats: Some(occluder),
                thin_ranks: Some(&ranks_view),
                thin_gradients: Some(&gradients_view),
            };
            [shared.entries(), [objects.entries(), importance.entries()].concat()]
        };
        let final_uniforms = two_level_buffer(false);
        let first_uniforms = two_level_buffer(true);
        let occluder = match &importance {
            Some(i) if i.method == ImportanceMethod::Vpimc => {
                // VPImC, first pass: only the occluding context; its mean opacity is α_avg.
                let (occluding, _) = pipelines.run(
                    ctx,
                    &camera,
                    own(&first_uniforms, &no_occluder),
                    kernel,
                )?;
                Some(alpha_mean(ctx, &occluding).map_err(err)?)
            }
            _ => None,
        };
        let occluder_view = occluder
            .as_ref()
            .map(|t| t.create_view(&Default::default()));
        let (image, gbuffer) = pipelines.run(
            ctx,
            &camera,
            own(
                &final_uniforms,
                occluder_view.as_ref().unwrap_or(&no_occluder),
            ),
            kernel,
        )?;
        Ok(vec![
            Value::Image(Arc::new(Image { texture: image })),
            Value::GBuffer(Arc::new(gbuffer)),
        ])
    }
}

crate::bind_group! {
    /// TwoLevelRaycast's own bindings, after the object tables (shaders/two_level_raycast.wgsl).
    pub struct TwoLevelBindings in "two_level_raycast", group 1 from 4 {
        pub importance_buffer: TextureView,
        pub importance_cut: TextureView,
        pub occluder_stats: TextureView,
        pub thin_ranks: TextureView,
        pub thin_gradients: TextureView,
    }
}

/// Volume thinning's rank table (`hatchery_data::thinning`): per object id (rows) and key bin
/// (columns), the fraction of the object's voxels with a lower key, as an R32Float texture; kept
/// for the node's next run while the volume, labels and levels stay the same. Keys are taken at
/// up to 2 M voxels (a uniform sample).
fn thinning_ranks(
    ctx: &mut Ctx,
    volume: &crate::value::Volume,
    labels: &crate::value::Labels,
    rows: u32,
    key: hatchery_data::thinning::KeyParams,
) -> wgpu::Texture {
    use hatchery_data::thinning::{RANK_BINS, thinning_ranks};
    use std::hash::{Hash, Hasher};
    let mut h = std::hash::DefaultHasher::new();
    (Arc::as_ptr(&volume.data), Arc::as_ptr(&labels.data)).hash(&mut h);
    (volume.data.dims, rows, key.bands.to_bits(), key.step.to_bits()).hash(&mut h);
    // The kept ranks hold weak references to the data they were made of: the allocations stay
    // reserved, so new data can never reuse the addresses the key hashes.
    let kept = ctx.keep("thinning ranks", h.finish(), || {
        let ranks = thinning_ranks(&volume.data, &labels.data.ids, rows as usize, &key, 2_000_000);
        (Arc::downgrade(&volume.data), Arc::downgrade(&labels.data), ranks)
    });
    ctx.gpu.texture_2d_init(
        "thinning ranks",
        RANK_BINS as u32,
        rows,
        wgpu::TextureFormat::R32Float,
        bytemuck::cast_slice(&kept.2),
    )
}

/// VPImC's α_avg (eq. 3): the mean opacity of `picture` over its non-empty pixels, as a 1×1
/// Rgba32Float texture (mean, pixel count, 0, 0) on the GPU.
fn alpha_mean(ctx: &mut Ctx, picture: &wgpu::Texture) -> Result<wgpu::Texture, GpuError> {
    let pipelines = ctx.cached("importance.pipelines", ImportancePipelines::new)?;
    let gpu = &ctx.gpu;
    let stats = gpu.storage_target("occluder stats", 1, 1, wgpu::TextureFormat::Rgba32Float);
    let (picture_view, stats_view) = (
        picture.create_view(&Default::default()),
        stats.create_view(&Default::default()),
    );
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pipelines.dispatch(
        gpu,
        &mut encoder,
        "alpha_mean",
        [
            Vec::new(),
            ImportanceBindings {
                picture_in: Some(&picture_view),
                stats_out: Some(&stats_view),
                ..Default::default()
            }.entries(),
        ],
        (1, 1),
    );
    ctx.submit(encoder.finish());
    Ok(stats)
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(TwoLevelRaycastNode)
        .program("two_level_raycast", shaders::ray_objects_shape(shaders::part!("two_level_raycast.wgsl")))
        .uniform(TwoLevelUniforms::layout())
        .bind_group(TwoLevelBindings::layout())
        .bind_group(ObjectBindings::layout())
        .bind_group_in("two_level_raycast", RayBindings::layout())
        .bind_group_in("two_level_raycast", crate::raycast::RayOutputs::layout())
        .gpu_enum(Global::wgsl())
        .gpu_enum(Sparseness::wgsl())
        .gpu_enum(RenderMode::wgsl())
        .gpu_enum(Compositing::wgsl())
        .gpu_enum(ImportanceMethod::wgsl())
        .uniform_in("two_level_raycast", crate::raycast::RayUniforms::layout());
}
