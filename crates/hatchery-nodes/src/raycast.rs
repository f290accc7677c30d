//! `Raycast` and `IsoSurfaceRaycast`: GPU volume ray casting (see shaders/raycast.wgsl).

use crate::camera::Camera;
use crate::gbuffer::NORMAL_FORMAT;
use crate::mesh_pass::DEPTH_FORMAT;
use crate::screen_pass::IMAGE_FORMAT;
use crate::value::{GBuffer, Image, TransferFunction, Volume};
use crate::{Ctx, Value};
use glam::{Vec3, Vec4Swizzles};
use hatchery_data::{VolumeData, bricks, lighting};
use hatchery_gpu::{GpuContext, GpuError};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

const MODES: &[&str] = &["dvr", "mip", "iso"];
const SHADINGS: &[&str] = &["none", "phong", "lighting", "context_preserving"];

/// The static GPU objects of the ray caster.
struct Statics {
    pipeline: wgpu::RenderPipeline,
    sampler: wgpu::Sampler,
    /// Stand-ins for the tables a mode does not use.
    blank_table: wgpu::Texture,
    blank_styles: wgpu::Texture,
    blank_index: wgpu::Texture,
    blank_labels: wgpu::Texture,
    blank_label_rows: wgpu::Texture,
}

fn statics(gpu: &GpuContext) -> Result<Statics, GpuError> {
    let source = crate::shaders::source("raycast").expect("registered program");
    let module = gpu.shader("raycast", &source)?;
    let pipeline = gpu.checked("pipeline raycast", |device| {
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("raycast"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &module,
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
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(IMAGE_FORMAT.into()), Some(NORMAL_FORMAT.into())],
            }),
            multiview_mask: None,
            cache: None,
        })
    })?;
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
    Ok(Statics {
        pipeline,
        sampler,
        blank_table,
        blank_styles,
        blank_index,
        blank_labels,
        blank_label_rows,
    })
}

/// The style tables of §4.1 as textures, one row per object (§4.2): row 0 is the function for
/// every object, rows 1.. the per-label ones.
struct StyleTables {
    rows: u32,
    /// LUT_SIZE × rows of (i, α_u, 0, 0).
    tft: Vec<f32>,
    ift_width: u32,
    /// ift_width × rows of style indices.
    ift: Vec<f32>,
    label_width: u32,
    /// label_width × 2: row 0 = table row of each label (x); row 1 = (domain lo, hi, N, 0) per row.
    label_rows: Vec<f32>,
}

impl StyleTables {
    fn new(
        function: &hatchery_data::style::StyleTransferFunction,
        per_label: &[(i64, hatchery_data::style::StyleTransferFunction)],
    ) -> Self {
        let functions: Vec<&hatchery_data::style::StyleTransferFunction> =
            std::iter::once(function)
                .chain(per_label.iter().map(|(_, f)| f))
                .collect();
        let rows = functions.len() as u32;
        let ift_width = functions
            .iter()
            .map(|f| f.ift.len())
            .max()
            .unwrap_or(1)
            .max(1) as u32;
        let mut tft = Vec::new();
        let mut ift = Vec::new();
        for f in &functions {
            tft.extend(f.tft.iter().flat_map(|e| [e[0], e[1], 0.0, 0.0]));
            let mut row: Vec<f32> = f.ift.iter().map(|&j| j as f32).collect();
            row.resize(ift_width as usize, *row.last().unwrap_or(&0.0));
            ift.extend(row);
        }
        // Labels up to the largest listed one, plus one slot for every larger label (row 0).
        let max_label = per_label
            .iter()
            .map(|(l, _)| *l)
            .max()
            .unwrap_or(0)
            .clamp(0, 65_534);
        let label_width = (max_label as u32 + 2).max(rows);
        let mut label_rows = vec![0.0f32; label_width as usize * 8];
        for (row, (label, _)) in per_label.iter().enumerate() {
            if (0..=max_label).contains(label) {
                label_rows[*label as usize * 4] = (row + 1) as f32;
            }
        }
        for (row, f) in functions.iter().enumerate() {
            let at = (label_width as usize + row) * 4;
            label_rows[at..at + 4].copy_from_slice(&[
                f.domain[0],
                f.domain[1],
                f.ift.len() as f32,
                0.0,
            ]);
        }
        Self {
            rows,
            tft,
            ift_width,
            ift,
            label_width,
            label_rows,
        }
    }
}

fn floats_texture(
    gpu: &GpuContext,
    label: &str,
    width: u32,
    format: wgpu::TextureFormat,
    data: &[f32],
) -> wgpu::Texture {
    gpu.texture_2d_init(label, width, 1, format, bytemuck::cast_slice(data))
}

/// What one ray-casting pass needs besides the volume and the camera.
pub struct RayOptions<'a> {
    pub mode: usize,
    pub iso: f32,
    pub step_voxels: f32,
    pub shading: usize,
    pub lighting_model: &'a str,
    pub phong: [f32; 4],
    pub kappa: [f32; 2],
    pub contours: bool,
    pub thickness: f32,
    pub transparency: bool,
    pub mip_bias: f32,
    pub jitter: bool,
    pub early_termination: f32,
    pub hit_opacity: f32,
    pub light_view: Vec3,
    /// Jump over bricks no visible value can be sampled in (DVR; the picture is unchanged).
    pub skip_empty: bool,
}

/// Nearest and farthest distance from the eye (perspective) or the near plane (orthographic) to
/// the corners of the volume's box: the normalisation of ‖P − E‖ in eq. 5.
fn corner_distances(camera: &Camera, data: &VolumeData) -> [f32; 2] {
    let mut range = [f32::INFINITY, 0.0f32];
    let last = Vec3::new(
        (data.dims[0] - 1) as f32,
        (data.dims[1] - 1) as f32,
        (data.dims[2] - 1) as f32,
    );
    for i in 0..8 {
        // The corners of the (possibly rotated) box of voxel centres.
        let corner = data.voxel_to_world(Vec3::new(
            if i & 1 == 0 { 0.0 } else { last.x },
            if i & 2 == 0 { 0.0 } else { last.y },
            if i & 4 == 0 { 0.0 } else { last.z },
        ));
        let d = if camera.orthographic {
            -(camera.view * corner.extend(1.0)).z - camera.near
        } else {
            (corner - camera.eye).length()
        };
        range = [range[0].min(d), range[1].max(d)];
    }
    [range[0].max(0.0), range[1]]
}

/// Runs the ray caster; returns the image and the G-buffer of the first hit.
pub fn cast(
    ctx: &mut Ctx,
    volume: &Volume,
    camera: &Camera,
    tf: Option<&TransferFunction>,
    labels: Option<&Volume>,
    o: &RayOptions,
) -> Result<(wgpu::Texture, GBuffer), NodeError> {
    let err = |e: GpuError| NodeError::new(e.to_string());
    let st = ctx.cached("raycast.statics", statics).map_err(err)?;
    let gpu = &ctx.gpu;
    let data = &volume.data;
    let volume_texture = volume.texture(gpu).map_err(err)?;
    let texel_range = volume_texture.texel_range;
    let volume_texture = &volume_texture.texture;
    let min_spacing = data.spacing().iter().copied().fold(f32::INFINITY, f32::min);
    // Rays march in voxel space (through the world → voxel transform, so rotated and mirrored
    // grids work) against the box of voxel centres, widened a little so rays running exactly
    // along a face (axis-aligned orthographic views) still hit it; sampling clamps to the grid.
    let margin = Vec3::splat(1e-4);
    let last = Vec3::new(
        (data.dims[0] - 1) as f32,
        (data.dims[1] - 1) as f32,
        (data.dims[2] - 1) as f32,
    );
    let (lo, hi) = (-margin, last + margin);
    let step_world = o.step_voxels * min_spacing;

    // Tables: colour TF or style TF, lighting TF, styles, index function.
    let mut shading = o.shading as f32;
    let (mut domain, mut nodes, mut map_size) = ([0.0f32, 1.0f32], 0.0f32, 1.0f32);
    let mut style_view = None;
    let mut index_texture = None;
    let mut label_rows = None;
    let mut label_count = 0.0f32;
    let table = match tf {
        Some(TransferFunction::Color(f)) => {
            domain = f.domain;
            let flat: Vec<f32> = f.lut.iter().flatten().copied().collect();
            Some(floats_texture(
                gpu,
                "tf",
                f.lut.len() as u32,
                wgpu::TextureFormat::Rgba32Float,
                &flat,
            ))
        }
        Some(TransferFunction::Style {
            function,
            per_label,
            styles,
        }) => {
            domain = function.domain;
            shading = 4.0;
            nodes = function.ift.len() as f32;
            map_size = styles.maps.first().map_or(1, |m| m.size) as f32;
            style_view = Some(
                styles
                    .texture(gpu)
                    .create_view(&wgpu::TextureViewDescriptor {
                        dimension: Some(wgpu::TextureViewDimension::D2Array),
                        ..Default::default()
                    }),
            );
            if !per_label.is_empty() && labels.is_none() {
                return Err(NodeError::at_port(
                    "labels",
                    "the style transfer function has per-label rows (`label_nodes`): connect a label volume",
                ));
            }
            let tables = StyleTables::new(function, per_label);
            index_texture = Some(gpu.texture_2d_init(
                "ift",
                tables.ift_width,
                tables.rows,
                wgpu::TextureFormat::R32Float,
                bytemuck::cast_slice(&tables.ift),
            ));
            label_rows = Some(gpu.texture_2d_init(
                "label rows",
                tables.label_width,
                2,
                wgpu::TextureFormat::Rgba32Float,
                bytemuck::cast_slice(&tables.label_rows),
            ));
            label_count = tables.label_width as f32;
            Some(gpu.texture_2d_init(
                "tft",
                hatchery_data::transfer_function::LUT_SIZE as u32,
                tables.rows,
                wgpu::TextureFormat::Rgba32Float,
                bytemuck::cast_slice(&tables.tft),
            ))
        }
        None => None,
    };
    // Which values the transfer function shows, for empty-space skipping.
    let visible_rows: Vec<(Vec<f32>, [f32; 2])> = match tf {
        Some(TransferFunction::Color(f)) => vec![(f.lut.iter().map(|e| e[3]).collect(), f.domain)],
        Some(TransferFunction::Style {
            function,
            per_label,
            ..
        }) => std::iter::once(function)
            .chain(per_label.iter().map(|(_, f)| f))
            .map(|f| (f.tft.iter().map(|e| e[1]).collect(), f.domain))
            .collect(),
        None => Vec::new(),
    };
    let rows: Vec<bricks::OpacityRow> = visible_rows
        .iter()
        .map(|(opacity, domain)| bricks::OpacityRow {
            domain: *domain,
            opacity,
        })
        .collect();
    // DVR skips by the transfer function's visible values, so it needs one.
    let skip_empty = o.skip_empty && (o.mode != 0 || !rows.is_empty());
    let visibility = floats_texture(
        gpu,
        "visibility",
        bricks::VISIBILITY_BINS as u32,
        wgpu::TextureFormat::R32Float,
        &bricks::visibility_prefix(data.value_range, &rows),
    );
    let bricks_texture = volume.bricks(gpu);

    let lighting_model = lighting::lighting_tf(o.lighting_model)
        .ok_or_else(|| NodeError::new(format!("unknown lighting model `{}`", o.lighting_model)))?;
    let lighting_flat: Vec<f32> = lighting_model.table.iter().flatten().copied().collect();
    let size = lighting::LIGHTING_SIZE as u32;
    let lighting_texture = gpu.texture_2d_init(
        "lighting tf",
        size,
        size,
        wgpu::TextureFormat::Rgba32Float,
        bytemuck::cast_slice(&lighting_flat),
    );

    let distances = corner_distances(camera, data);
    let view_proj = camera.view_proj();
    let bool_f = |b: bool| if b { 1.0 } else { 0.0 };
    let mut u: Vec<f32> = Vec::with_capacity(104);
    u.extend_from_slice(&view_proj.inverse().to_cols_array());
    u.extend_from_slice(&camera.view.to_cols_array());
    u.extend_from_slice(&view_proj.to_cols_array());
    u.extend_from_slice(&[lo.x, lo.y, lo.z, step_world]);
    u.extend_from_slice(&[hi.x, hi.y, hi.z, o.step_voxels]);
    u.extend_from_slice(&[
        data.origin()[0],
        data.origin()[1],
        data.origin()[2],
        data.value_range[0],
    ]);
    u.extend_from_slice(&[
        data.spacing()[0],
        data.spacing()[1],
        data.spacing()[2],
        data.value_range[1],
    ]);
    let max_gradient = if shading >= 2.0 {
        volume.max_gradient()
    } else {
        1.0
    };
    u.extend_from_slice(&[
        data.dims[0] as f32,
        data.dims[1] as f32,
        data.dims[2] as f32,
        max_gradient,
    ]);
    let l = o.light_view.normalize_or(Vec3::Z);
    u.extend_from_slice(&[l.x, l.y, l.z, bool_f(camera.orthographic)]);
    u.extend_from_slice(&[
        camera.width as f32,
        camera.height as f32,
        bool_f(o.jitter),
        o.early_termination,
    ]);
    u.extend_from_slice(&[o.mode as f32, o.iso, shading, o.hit_opacity]);
    u.extend_from_slice(&o.phong);
    u.extend_from_slice(&[o.kappa[0], o.kappa[1], distances[0], distances[1]]);
    u.extend_from_slice(&[domain[0], domain[1], nodes, o.thickness]);
    u.extend_from_slice(&[
        bool_f(o.contours),
        bool_f(o.transparency),
        o.mip_bias,
        map_size,
    ]);
    let eye = camera.view.inverse().w_axis.xyz();
    u.extend_from_slice(&[eye.x, eye.y, eye.z, 0.0]);
    let label_range = match labels {
        Some(l) => l.texture(gpu).map_err(err)?.texel_range,
        None => [0.0, 1.0],
    };
    let use_labels = labels.is_some() && label_rows.is_some();
    u.extend_from_slice(&[
        bool_f(use_labels),
        label_range[0],
        label_range[1],
        label_count,
    ]);
    u.extend_from_slice(&[
        bool_f(skip_empty),
        bricks::BRICK as f32,
        bricks::VISIBILITY_BINS as f32,
        0.0,
    ]);
    // World → voxel, and voxel-space gradients → world (M^-T of the linear part).
    u.extend_from_slice(&data.geometry.to_voxel().as_mat4().to_cols_array());
    let linear = data.geometry.to_world().as_mat4();
    let normal_matrix = glam::Mat4::from_mat3(glam::Mat3::from_mat4(linear).inverse().transpose());
    u.extend_from_slice(&normal_matrix.to_cols_array());
    u.extend_from_slice(&[texel_range[0], texel_range[1], 0.0, 0.0]);
    let uniform = gpu.buffer_init(
        "raycast",
        bytemuck::cast_slice(&u),
        wgpu::BufferUsages::UNIFORM,
    );

    let volume_view = volume_texture.create_view(&Default::default());
    let table_view = table
        .as_ref()
        .unwrap_or(&st.blank_table)
        .create_view(&Default::default());
    let lighting_view = lighting_texture.create_view(&Default::default());
    let styles_view = style_view.unwrap_or_else(|| {
        st.blank_styles.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        })
    });
    let index_view = index_texture
        .as_ref()
        .unwrap_or(&st.blank_index)
        .create_view(&Default::default());
    let labels_texture = match labels.filter(|_| use_labels) {
        Some(l) => {
            if l.data.dims != data.dims {
                return Err(NodeError::at_port(
                    "labels",
                    format!(
                        "label volume is {:?} voxels, the volume {:?}: they must share the grid",
                        l.data.dims, data.dims
                    ),
                ));
            }
            // Labels are read at the volume's voxels: the grids must lie in the same place.
            let (a, b) = (l.data.geometry.to_world(), data.geometry.to_world());
            let tolerance = 1e-3 * data.geometry.spacing.min_element();
            if !a.abs_diff_eq(b, tolerance) {
                return Err(NodeError::at_port(
                    "labels",
                    format!(
                        "label volume lies elsewhere in the world ({}) than the volume ({}): \
                         they must share the voxel → world transform",
                        l.data.geometry.describe(),
                        data.geometry.describe()
                    ),
                ));
            }
            &l.texture(gpu).map_err(err)?.texture
        }
        None => &st.blank_labels,
    };
    let labels_view = labels_texture.create_view(&Default::default());
    let label_rows_view = label_rows
        .as_ref()
        .unwrap_or(&st.blank_label_rows)
        .create_view(&Default::default());
    let bricks_view = bricks_texture.create_view(&Default::default());
    let visibility_view = visibility.create_view(&Default::default());
    let texture_views = [
        (1, &volume_view),
        (3, &table_view),
        (4, &lighting_view),
        (5, &styles_view),
        (6, &index_view),
        (7, &labels_view),
        (8, &label_rows_view),
        (9, &bricks_view),
        (10, &visibility_view),
    ];
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 2,
            resource: wgpu::BindingResource::Sampler(&st.sampler),
        },
    ];
    entries.extend(
        texture_views
            .iter()
            .map(|(binding, view)| wgpu::BindGroupEntry {
                binding: *binding,
                resource: wgpu::BindingResource::TextureView(view),
            }),
    );
    let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("raycast"),
        layout: &st.pipeline.get_bind_group_layout(0),
        entries: &entries,
    });

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
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        pass.set_pipeline(&st.pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.draw(0..3, 0..1);
    }
    let work = encoder.finish();
    ctx.submit(work);
    Ok((
        image,
        GBuffer {
            depth,
            normal,
            camera: camera.clone(),
        },
    ))
}

fn light_direction(inputs: &NodeInputs<Value>, camera: &Camera) -> Result<Vec3, NodeError> {
    Ok(match inputs.get("light") {
        Some(light) => light.light("light")?.view_direction(camera),
        None => Vec3::new(0.3, 0.4, 1.0).normalize(),
    })
}

pub struct RaycastNode;

impl Node<Value, Ctx> for RaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "Raycast",
            category: "Volume",
            doc: "GPU ray casting of a volume. Front-to-back compositing (eq. 1 of the context-preserving \
                  paper) with opacity correction for the sample distance, early ray termination, \
                  jittered start, trilinear sampling, gradients by central differences in voxel space \
                  (respecting spacing); perspective or orthographic. Modes: dvr, mip (maximum \
                  intensity), iso (first hit, refined linearly). Shading: none, phong (eq. 3), lighting \
                  (VolumeShop lighting transfer function, eq. 8), context_preserving (eq. 5; κt = 0 is \
                  plain DVR). A StyleTransferFunction on `tf` switches to style shading (Bruckner & \
                  Gröller 2007: lit spheres, style contours eq. 1, illustrative transparency eq. 2).",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input(
                    "tf",
                    PortType::TransferFunction,
                    "colour/opacity or style transfer function",
                ),
                PortSpec::optional("light", PortType::Light, "the light (default: a headlight)"),
                PortSpec::optional(
                    "labels",
                    PortType::Volume,
                    "object labels on the same grid (per-label style rows, §4.2)",
                ),
            ],
            outputs: vec![
                PortSpec::output("image", PortType::Image, "premultiplied colour"),
                PortSpec::output(
                    "gbuffer",
                    PortType::GBuffer,
                    "depth and normal where opacity first reaches `hit_opacity`",
                ),
            ],
            params: vec![
                ParamSpec::choice("mode", "dvr", MODES, "compositing"),
                ParamSpec::float("iso", 0.5, -1e12, 1e12, "iso value for mode iso"),
                ParamSpec::float(
                    "step",
                    0.5,
                    0.05,
                    8.0,
                    "sample distance in voxels (of the smallest spacing)",
                ),
                ParamSpec::choice(
                    "shading",
                    "phong",
                    SHADINGS,
                    "shading (style TFs always use their styles)",
                ),
                ParamSpec::choice(
                    "lighting_model",
                    "phong_contour",
                    lighting::LIGHTING_MODELS,
                    "lighting transfer function for `lighting`",
                ),
                ParamSpec::float("ambient", 0.15, 0.0, 1.0, "c_a of eq. 3"),
                ParamSpec::float("diffuse", 0.85, 0.0, 4.0, "c_d of eq. 3"),
                ParamSpec::float("specular", 0.4, 0.0, 4.0, "c_s of eq. 3"),
                ParamSpec::float("exponent", 32.0, 1.0, 512.0, "c_e of eq. 3"),
                ParamSpec::float(
                    "kappa_t",
                    0.0,
                    0.0,
                    1000.0,
                    "κt of eq. 5: how deep to look inside (0 = plain DVR)",
                ),
                ParamSpec::float(
                    "kappa_s",
                    0.5,
                    0.0,
                    100.0,
                    "κs of eq. 5: sharpness of the cut",
                ),
                ParamSpec::bool("contours", true, "style contours (§3.3)"),
                ParamSpec::float(
                    "thickness",
                    2.0,
                    0.0,
                    1000.0,
                    "contour thickness T, world units",
                ),
                ParamSpec::bool(
                    "transparency",
                    true,
                    "illustrative transparency (eq. 2) for styles",
                ),
                ParamSpec::float("mip_bias", 0.0, -4.0, 8.0, "bias of the style mip level"),
                ParamSpec::bool(
                    "jitter",
                    true,
                    "jitter the first sample per pixel (hides wood-grain artefacts)",
                ),
                ParamSpec::float(
                    "early_termination",
                    0.99,
                    0.5,
                    1.0,
                    "stop a ray at this opacity (1 = never)",
                ),
                ParamSpec::float(
                    "hit_opacity",
                    0.5,
                    0.001,
                    1.0,
                    "accumulated opacity that defines the G-buffer depth",
                ),
                ParamSpec::bool(
                    "skip_empty",
                    true,
                    "jump over 8³-voxel bricks that cannot change the picture (DVR: values the \
                     transfer function makes transparent; MIP: none above the maximum so far; \
                     iso: all below the iso value) — same picture, fewer samples",
                ),
            ],
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
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let tf = inputs.require("tf")?.transfer_function("tf")?.clone();
        let options = RayOptions {
            mode: MODES
                .iter()
                .position(|m| *m == p.choice("mode"))
                .unwrap_or(0),
            iso: p.f32("iso"),
            step_voxels: p.f32("step"),
            shading: SHADINGS
                .iter()
                .position(|s| *s == p.choice("shading"))
                .unwrap_or(0),
            lighting_model: p.choice("lighting_model"),
            phong: [
                p.f32("ambient"),
                p.f32("diffuse"),
                p.f32("specular"),
                p.f32("exponent"),
            ],
            kappa: [p.f32("kappa_t"), p.f32("kappa_s")],
            contours: p.bool("contours"),
            thickness: p.f32("thickness"),
            transparency: p.bool("transparency"),
            mip_bias: p.f32("mip_bias"),
            jitter: p.bool("jitter"),
            early_termination: p.f32("early_termination"),
            skip_empty: p.bool("skip_empty"),
            hit_opacity: p.f32("hit_opacity"),
            light_view: light_direction(inputs, &camera)?,
        };
        let labels = inputs
            .get("labels")
            .map(|l| l.volume("labels").cloned())
            .transpose()?;
        let (image, gbuffer) = cast(
            ctx,
            &volume,
            &camera,
            Some(&tf),
            labels.as_deref(),
            &options,
        )?;
        Ok(vec![
            Value::Image(Arc::new(Image { texture: image })),
            Value::GBuffer(Arc::new(gbuffer)),
        ])
    }
}

pub struct IsoSurfaceRaycastNode;

impl Node<Value, Ctx> for IsoSurfaceRaycastNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "IsoSurfaceRaycast",
            category: "Volume",
            doc: "First hit of an iso value along each ray (refined linearly between samples) as a \
                  G-buffer: window depth and the view-space normal −∇f/|∇f|. Feeds Silhouette, \
                  DiffuseIntensity, Halftone and the compositing nodes with no mesh at all.",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![PortSpec::output(
                "gbuffer",
                PortType::GBuffer,
                "depth + normal of the iso-surface",
            )],
            params: vec![
                ParamSpec::float("iso", 0.0, -1e12, 1e12, "iso value, in the volume's units"),
                ParamSpec::float("step", 0.25, 0.05, 8.0, "sample distance in voxels"),
            ],
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
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let options = RayOptions {
            mode: 2,
            iso: p.f32("iso"),
            step_voxels: p.f32("step"),
            shading: 0,
            lighting_model: "phong",
            phong: [0.0, 1.0, 0.0, 1.0],
            kappa: [0.0, 0.0],
            contours: false,
            thickness: 0.0,
            transparency: false,
            mip_bias: 0.0,
            jitter: false,
            early_termination: 1.0,
            hit_opacity: 1.0,
            light_view: Vec3::Z,
            skip_empty: true,
        };
        let (_, gbuffer) = cast(ctx, &volume, &camera, None, None, &options)?;
        Ok(vec![Value::GBuffer(Arc::new(gbuffer))])
    }
}
