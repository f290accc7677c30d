//! `ExplodedView`: exploded views of a segmented volume (Viola et al., the Vis 2005 tutorial's
//! §3 "Exploded views and deformations": volume splitting, logical and geometrical). Parts of
//! the volume — objects, halves of objects, halves of the whole volume — are moved apart along
//! their explosion directions and ray cast with the object table's transfer functions; guides
//! (arrows from each part's original centre to its moved one) keep the original placement
//! readable (see shaders/exploded_view.wgsl and docs/exploded.md).

use crate::annotations::Annotations;
use crate::overlay::{Canvas, pixels};
use crate::raycast::objects::{
    ObjectBindings, TABLE_WIDTH, TwoLevelUniforms, brick_table, check_labels_grid, object_tables,
};
use crate::raycast::{
    Kernel, KernelChoice, PhongParams, RayBindings, RayOptions, RayPipelines, RayShading,
    RayUniforms, TableInfo,
};
use crate::two_level_raycast::{Boundary, Normals};
use crate::value::{Compositing, Image, ObjectStyle, RenderMode};
use crate::{Ctx, Value};
use glam::{DVec3, Vec3};
use hatchery_data::segmentation::LabelData;
use hatchery_data::transfer_function::LUT_SIZE;
use hatchery_gpu::GpuError;
use hatchery_graph::{
    Group, NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// At most this many parts (a split counts two): the shader keeps each part's span per ray.
pub const MAX_PARTS: usize = 16;

/// One entry of `parts` as written: the object (0 = the whole volume), its name, and either a
/// split (world axis, distance each half moves) or a move (world displacement).
#[derive(Clone, Debug, PartialEq)]
pub struct PartSpec {
    pub id: u16,
    pub name: String,
    pub split: Option<(Vec3, f32)>,
    pub displacement: Vec3,
}

/// A part as drawn: object (0 = whole volume), side of the plane through the object's centre
/// normal to `axis` (+1, −1, or 0 for the whole object), and its displacement (world units).
#[derive(Clone, Debug, PartialEq)]
pub struct Part {
    pub id: u16,
    pub name: String,
    pub axis: Vec3,
    pub side: f32,
    pub displacement: Vec3,
}

fn axis_of(word: &str) -> Option<Vec3> {
    match word.to_ascii_lowercase().as_str() {
        "x" => Some(Vec3::X),
        "y" => Some(Vec3::Y),
        "z" => Some(Vec3::Z),
        _ => None,
    }
}

/// Parses `parts` ("skeleton: split x 40; liver: move 0 30 0; volume: split z 20"): entries
/// separated by `;`, each `OBJECT: split AXIS DISTANCE` (the halves on either side of the plane
/// through the object's centre normal to world axis x, y or z, moved ±DISTANCE along it) or
/// `OBJECT: move DX DY DZ` (world units, or with `%` percent of `size`, the largest side of the
/// labelled objects' box). OBJECT is a label id, an object's name (case ignored) or `volume`
/// (the whole volume: geometrical splitting). Errors name the entry.
pub(crate) fn parse_parts(
    text: &str,
    objects: &std::collections::BTreeMap<u16, String>,
    size: f32,
) -> Result<Vec<PartSpec>, String> {
    let mut parts = Vec::new();
    for entry in text.split(';').map(str::trim).filter(|e| !e.is_empty()) {
        let bad = |why: String| format!("part `{entry}`: {why}");
        let (key, action) = entry.split_once(':').ok_or_else(|| {
            bad("expected `OBJECT: split AXIS DISTANCE` or `OBJECT: move DX DY DZ`".into())
        })?;
        let key = key.trim();
        let id = if key.eq_ignore_ascii_case("volume") {
            0
        } else if let Ok(id) = key.parse::<u16>() {
            if id == 0 {
                return Err(bad(
                    "id 0 is the background; `volume` is the whole volume".into()
                ));
            }
            id
        } else {
            objects
                .iter()
                .find(|(_, name)| name.trim().eq_ignore_ascii_case(key))
                .map(|(id, _)| *id)
                .ok_or_else(|| {
                    let names: Vec<&str> = objects.values().map(String::as_str).collect();
                    bad(format!(
                        "no object is named `{key}` (the labels name: {})",
                        names.join(", ")
                    ))
                })?
        };
        let name = if id == 0 {
            "volume".to_owned()
        } else {
            objects
                .get(&id)
                .cloned()
                .unwrap_or_else(|| format!("object {id}"))
        };
        let words: Vec<&str> = action.split_whitespace().collect();
        let number = |w: &str| {
            let (digits, scale) = match w.strip_suffix('%') {
                Some(d) => (d, size / 100.0),
                None => (w, 1.0),
            };
            digits
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .map(|v| v * scale)
                .ok_or_else(|| bad(format!("`{w}` is not a number (or a percentage)")))
        };
        let spec = match words.as_slice() {
            ["split", axis, distance] => {
                let axis =
                    axis_of(axis).ok_or_else(|| bad(format!("axis `{axis}` is not x, y or z")))?;
                PartSpec {
                    id,
                    name,
                    split: Some((axis, number(distance)?)),
                    displacement: Vec3::ZERO,
                }
            }
            ["move", dx, dy, dz] => PartSpec {
                id,
                name,
                split: None,
                displacement: Vec3::new(number(dx)?, number(dy)?, number(dz)?),
            },
            _ => {
                return Err(bad(
                    "expected `split AXIS DISTANCE` (axis x, y or z) or `move DX DY DZ`".into(),
                ));
            }
        };
        if parts.iter().any(|p: &PartSpec| p.id == spec.id) {
            return Err(bad("the object is named twice".into()));
        }
        parts.push(spec);
    }
    Ok(parts)
}

/// The parts as drawn, in order: a split gives its positive half, then its negative one.
pub fn expand(specs: &[PartSpec]) -> Vec<Part> {
    let mut parts = Vec::new();
    for s in specs {
        match s.split {
            Some((axis, distance)) => {
                for (side, sign) in [(1.0, "+"), (-1.0, "−")] {
                    let letter = ["x", "y", "z"][axis.abs().max_position()];
                    parts.push(Part {
                        id: s.id,
                        name: format!("{} ({sign}{letter} half)", s.name),
                        axis,
                        side,
                        displacement: axis * distance * side,
                    });
                }
            }
            None => parts.push(Part {
                id: s.id,
                name: s.name.clone(),
                axis: Vec3::X,
                side: 0.0,
                displacement: s.displacement,
            }),
        }
    }
    parts
}

/// Where an object (0: every labelled voxel) lies: its centre (mean voxel position, world) and
/// voxel-index box; None when no voxel holds it.
#[derive(Clone, Copy, Debug)]
pub struct Extent {
    pub centre: Vec3,
    pub lo: Vec3,
    pub hi: Vec3,
}

fn voxel_at(i: usize, nx: usize, ny: usize) -> DVec3 {
    DVec3::new(
        (i % nx) as f64,
        (i / nx % ny) as f64,
        (i / (nx * ny)) as f64,
    )
}

/// The extent of each id in `ids` (0: all labelled voxels), in one pass over the labels.
pub fn extents(labels: &LabelData, ids: &[u16]) -> Vec<Option<Extent>> {
    let [nx, ny, _] = labels.dims.map(|d| d as usize);
    let mut acc = vec![
        (
            DVec3::ZERO,
            0u64,
            DVec3::splat(f64::MAX),
            DVec3::splat(f64::MIN)
        );
        ids.len()
    ];
    for (i, &id) in labels.ids.iter().enumerate() {
        if id == 0 {
            continue;
        }
        let mut v = None;
        for (slot, &want) in ids.iter().enumerate() {
            if want == 0 || want == id {
                let p = *v.get_or_insert_with(|| voxel_at(i, nx, ny));
                let a = &mut acc[slot];
                a.0 += p;
                a.1 += 1;
                a.2 = a.2.min(p);
                a.3 = a.3.max(p);
            }
        }
    }
    acc.into_iter()
        .map(|(sum, count, lo, hi)| {
            (count > 0).then(|| Extent {
                centre: labels
                    .geometry
                    .voxel_to_world((sum / count as f64).as_vec3()),
                lo: lo.as_vec3(),
                hi: hi.as_vec3(),
            })
        })
        .collect()
}

/// The centre (world) of each half part: the mean of its object's voxels on its side of the
/// plane through the object's centre; the object's centre for whole parts.
fn part_centres(labels: &LabelData, parts: &[Part], whole: &[Vec3]) -> Vec<Vec3> {
    let [nx, ny, _] = labels.dims.map(|d| d as usize);
    let g = &labels.geometry;
    let mut acc = vec![(DVec3::ZERO, 0u64); parts.len()];
    if parts.iter().any(|p| p.side != 0.0) {
        for (i, &id) in labels.ids.iter().enumerate() {
            if id == 0 {
                continue;
            }
            for (k, part) in parts.iter().enumerate() {
                if part.side == 0.0 || (part.id != 0 && part.id != id) {
                    continue;
                }
                let p = voxel_at(i, nx, ny);
                let s = part.axis.dot(g.voxel_to_world(p.as_vec3()) - whole[k]);
                if (part.side > 0.0) == (s >= 0.0) {
                    acc[k].0 += p;
                    acc[k].1 += 1;
                }
            }
        }
    }
    acc.iter()
        .zip(whole)
        .map(|(&(sum, count), &centre)| {
            if count == 0 {
                centre
            } else {
                g.voxel_to_world((sum / count as f64).as_vec3())
            }
        })
        .collect()
}

/// The largest side of the world box around every labelled voxel (0 for none): what `%`
/// displacements are percentages of.
fn labelled_size(labels: &LabelData) -> f32 {
    let Some((lo, hi)) = labels.object_voxel_bounds() else {
        return 0.0;
    };
    let corners = hatchery_annotation::box_corners(
        Vec3::from(lo.map(|v| v as f32)),
        Vec3::from(hi.map(|v| v as f32)),
    )
    .map(|c| labels.geometry.voxel_to_world(c));
    let min = corners.iter().copied().fold(Vec3::INFINITY, Vec3::min);
    let max = corners.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
    (max - min).max_element()
}

hatchery_graph::node_params! {
    /// Parameters of `ExplodedView`.
    pub struct ExplodedViewParams {
        /// the parts and how they move, `;`-separated: `OBJECT: split AXIS DISTANCE` (its
        /// halves either side of the plane through its centre normal to x, y or z, moved
        /// ±DISTANCE along it) or `OBJECT: move DX DY DZ`; world units, or `%` of the labelled
        /// objects' largest extent; OBJECT a label id, an object's name or `volume` (the whole
        /// volume); earlier parts own overlapping samples
        pub parts: String = "volume: split x 20";
        /// draw guides: an arrow from each moved part's original centre (a dot) to its moved one
        pub guides: bool = true;
        /// colour of the guides
        pub guide_color: [f32; 4] = [0.15, 0.15, 0.15, 0.9];
        /// width of the guides, pixels
        pub guide_width: f32 = 1.5, range(0.1, 32.0), unit(pixels);
        /// boundary filtering of the object ids (as TwoLevelRaycast) or the nearest voxel's id
        pub boundary: Boundary = Boundary::Filtered;
        /// shading normals from the data's gradient or each object's own filtered mask (label
        /// maps without intensities)
        pub normals: Normals = Normals::Data;
        /// with normals = objects: smooth iso-surfaces' mask gradient over ±this many voxels
        pub surface_smoothing: f32 = 0.0, range(0.0, 4.0);
        /// sample distance in voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// reconstruction of the data between voxels
        pub reconstruction: crate::reconstruction::Reconstruction =
            crate::reconstruction::Reconstruction::Trilinear;
        /// Blinn–Phong coefficients of shaded_dvr and iso objects
        pub phong: PhongParams = Group;
        /// jitter the first sample per pixel
        pub jitter: bool = true;
        /// stop a ray at this opacity (1 = never)
        pub early_termination: f32 = 0.99, range(0.5, 1.0);
        /// GPU path: fragment shader or compute kernel (same picture)
        pub kernel: KernelChoice = KernelChoice::Auto;
    }
}

/// Objects drawn with what ExplodedView does not composite (MIP, sum): an error naming them.
fn check_styles(styles: &[ObjectStyle]) -> Result<(), NodeError> {
    for s in styles.iter().filter(|s| s.enabled) {
        let what = if s.mode == RenderMode::Mip {
            "rendering mode mip"
        } else if matches!(s.compositing, Compositing::Mip | Compositing::Sum) {
            "local compositing mip or sum"
        } else {
            continue;
        };
        return Err(NodeError::at_port(
            "styles",
            format!(
                "object {} ({}) asks for {what}: ExplodedView composites every object front to \
                 back (over or iso; modes dvr, shaded_dvr, tone, contours, iso)",
                s.id, s.name
            ),
        ));
    }
    Ok(())
}

pub struct ExplodedViewNode;

impl Node<Value, Ctx> for ExplodedViewNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ExplodedView",
            category: "Volume",
            doc: "Exploded views of a segmented volume (Viola et al., the Vis 2005 tutorial §3, \
                  volume splitting): the `parts` — objects, halves of objects split by a plane \
                  through their centre (logical splitting) or halves of the whole volume \
                  (geometrical splitting) — are moved by their displacements; each sample is \
                  looked up in every part at its position minus the part's displacement, the \
                  first part (in the written order) holding a drawn object there owns it, and it \
                  is classified with that object's transfer function and rendering mode from \
                  ObjectStyles and composited front to back. Objects no part names stay in \
                  place. Guides: an arrow from each part's original centre to its moved one.",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field"),
                PortSpec::input(
                    "labels",
                    PortType::Labels,
                    "object ids on the volume's grid",
                ),
                PortSpec::input(
                    "styles",
                    PortType::ObjectStyles,
                    "the object table (over or iso compositing)",
                ),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::optional("light", PortType::Light, "the light (default: a headlight)"),
            ],
            outputs: vec![
                PortSpec::output(
                    "image",
                    PortType::Image,
                    "premultiplied colour, with the guides where `guides` is on",
                ),
                PortSpec::output(
                    "gbuffer",
                    PortType::GBuffer,
                    "depth and normal where opaque",
                ),
                PortSpec::output(
                    "annotations",
                    PortType::Annotations,
                    "per part its original centre (anchor 2k) and moved centre (2k + 1) with \
                     their boxes: anchors 0 and 1 are what Arrow and Fan draw",
                ),
            ],
            params: ExplodedViewParams::specs(),
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
        let params = ExplodedViewParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        let volume = volume
            .resident(&ctx.gpu)
            .map_err(|e| NodeError::new(e.to_string()))?;
        let labels = labels
            .resident(&ctx.gpu)
            .map_err(|e| NodeError::new(e.to_string()))?;
        let styles: Vec<ObjectStyle> = inputs.require("styles")?.object_styles("styles")?.to_vec();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        check_labels_grid(labels, volume)?;
        check_styles(&styles)?;
        let size = labelled_size(&labels.data);
        let specs = parse_parts(&params.parts, &labels.data.objects, size)
            .map_err(|e| NodeError::new(format!("parameter `parts`: {e}")))?;
        let parts = expand(&specs);
        if parts.len() > MAX_PARTS {
            return Err(NodeError::new(format!(
                "parameter `parts`: {} parts (a split is two), at most {MAX_PARTS}",
                parts.len()
            )));
        }
        let l = &labels.data;
        let ids: Vec<u16> = parts.iter().map(|p| p.id).collect();
        let found = extents(l, &ids);
        let mut whole = Vec::new();
        for (part, extent) in parts.iter().zip(&found) {
            let e = extent.ok_or_else(|| {
                NodeError::new(format!(
                    "parameter `parts`: no voxel of the labels holds `{}`",
                    part.name
                ))
            })?;
            whole.push(e.centre);
        }
        let centres = part_centres(l, &parts, &whole);
        let v = &volume.data;
        let to_world = v.geometry.to_world().as_mat4();
        let to_voxel = v.geometry.to_voxel().as_mat4();
        let origin = to_world.w_axis.truncate();
        let mut table = Vec::with_capacity(parts.len().max(1) * 16);
        for ((part, extent), &centre) in parts.iter().zip(&found).zip(&whole) {
            let e = extent.expect("checked above");
            let d = to_voxel.transform_vector3(part.displacement);
            // world(q) = M q + o; the plane n·(world − c) = 0 in voxel space: (Mᵀ n)·q + n·(o − c).
            let normal = to_world.transpose().transform_vector3(part.axis);
            let offset = part.axis.dot(origin - centre);
            let (lo, hi) = if part.id == 0 {
                (Vec3::splat(-1.0), Vec3::from(v.dims.map(|n| n as f32)))
            } else {
                (e.lo - 1.01, e.hi + 1.01)
            };
            table.extend_from_slice(&[
                d.x,
                d.y,
                d.z,
                f32::from(part.id),
                normal.x,
                normal.y,
                normal.z,
                offset,
                lo.x,
                lo.y,
                lo.z,
                part.side,
                hi.x,
                hi.y,
                hi.z,
                0.0,
            ]);
        }
        if table.is_empty() {
            table = vec![0.0; 16];
        }
        let whole_volume = parts.iter().any(|p| p.id == 0);
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
            skip_empty: true,
            ..TableInfo::plain()
        };
        let err = |e: GpuError| NodeError::new(e.to_string());
        let filtered = params.boundary != Boundary::Point;
        let object_normals = params.normals == Normals::Objects;
        let bricked = volume.texture(&ctx.gpu).map_err(err)?.layout.is_some();
        let (ids_texture, id_quads) =
            crate::raycast::objects::object_id_texture(&ctx.gpu, labels, bricked).map_err(err)?;
        let constants = [
            ("RAY_BRICKED", f64::from(u8::from(bricked))),
            ("RAY_NO_DATA", f64::from(u8::from(volume.has_no_data()))),
            params.reconstruction.on(ctx, &volume.data).constant(),
            ("TL_FILTER", f64::from(u8::from(filtered))),
            ("TL_MASK_NORMALS", f64::from(u8::from(object_normals))),
            ("EXPLODED_PARTS", parts.len() as f64),
            ("EXPLODED_REST", f64::from(u8::from(!whole_volume))),
            id_quads,
        ];
        let key = constants
            .iter()
            .map(|(_, v)| v.to_string())
            .collect::<Vec<_>>()
            .join(".");
        let pipelines = ctx
            .cached(&format!("exploded_view.pipelines.{key}"), |gpu| {
                RayPipelines::specialised(gpu, "exploded_view", &constants)
            })
            .map_err(err)?;
        let sampler = crate::raycast::linear_clamp_sampler(ctx).map_err(err)?;
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
        let tables = object_tables(&styles);
        let two_level = TwoLevelUniforms {
            boundary_filter: filtered.into(),
            columns: tables.columns,
            mask_normals: object_normals.into(),
            surface_smoothing: if object_normals {
                params.surface_smoothing
            } else {
                0.0
            },
            ..Default::default()
        };
        let buffer =
            |label, bytes: &[u8]| gpu.buffer_init(label, bytes, wgpu::BufferUsages::UNIFORM);
        let ray_buffer = buffer("exploded ray", bytemuck::bytes_of(&uniforms));
        let two_level_buffer = buffer("exploded objects", bytemuck::bytes_of(&two_level));
        let texture_2d = |label, w: u32, h: u32, data: &[f32]| {
            gpu.texture_2d_init(
                label,
                w,
                h,
                wgpu::TextureFormat::Rgba32Float,
                bytemuck::cast_slice(data),
            )
        };
        let tf_texture = texture_2d(
            "exploded tfs",
            LUT_SIZE as u32,
            tables.rows,
            &tables.tf_rows,
        );
        let table_texture = texture_2d(
            "exploded object table",
            TABLE_WIDTH,
            (tables.table.len() / 4) as u32 / TABLE_WIDTH,
            &tables.table,
        );
        let parts_texture = texture_2d("exploded part table", 4, (table.len() / 16) as u32, &table);
        let placeholder = texture_2d("exploded placeholder", 1, 1, &[0.0; 4]);
        let mut drawn: Vec<u16> = styles.iter().filter(|s| s.enabled).map(|s| s.id).collect();
        drawn.sort_unstable();
        let drawn_mask = labels.drawn_mask(gpu, &drawn).map_err(err)?;
        let (brick_dims, brick_ranges) = brick_table(labels, &styles);
        let brick_texture = gpu.texture_3d_init(
            "exploded object bricks",
            brick_dims,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&brick_ranges),
        );
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let views = [
            view(&volume_texture.texture),
            view(&tf_texture),
            view(ids_texture),
            view(&table_texture),
            view(&brick_texture),
            view(&drawn_mask.texture),
            view(&placeholder),
            view(&volume_texture.page_table),
            view(&parts_texture),
        ];
        let shared = RayBindings {
            ray: Some(&ray_buffer),
            volume: Some(&views[0]),
            linear_clamp: Some(&sampler),
            tf_table: Some(&views[1]),
            // The lighting TF of shade_surface's `lighting` branch, never taken here.
            lighting_table: Some(&views[6]),
            bricks: Some(&views[4]),
            page_table: Some(&views[7]),
            ..Default::default()
        };
        let own = [
            ObjectBindings {
                object_ids: Some(&views[2]),
                objects: Some(&views[3]),
                two_level: Some(&two_level_buffer),
                drawn_mask: Some(&views[5]),
            }
            .entries(),
            ExplodedBindings {
                parts: Some(&views[8]),
            }
            .entries(),
        ]
        .concat();
        let (image, gbuffer) = pipelines.run(ctx, &camera, [shared.entries(), own], kernel)?;

        // Guides and annotations: each part's original and moved centre, with their boxes.
        let mut annotations = Annotations {
            anchors: Vec::new(),
            bounds: Vec::new(),
            placed: None,
        };
        for ((part, extent), &centre) in parts.iter().zip(&found).zip(&centres) {
            let e = extent.expect("checked above");
            let corners =
                hatchery_annotation::box_corners(e.lo, e.hi).map(|c| v.geometry.voxel_to_world(c));
            let lo = corners.iter().copied().fold(Vec3::INFINITY, Vec3::min);
            let hi = corners.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
            let d = part.displacement;
            let anchor = |position, text: String, priority| hatchery_annotation::Anchor {
                position,
                text,
                object: part.id,
                priority,
            };
            annotations.anchors.push(anchor(
                centre,
                format!("{} (original place)", part.name),
                0.5,
            ));
            annotations
                .anchors
                .push(anchor(centre + d, part.name.clone(), 1.0));
            annotations.bounds.push(Some([lo, hi]));
            annotations.bounds.push(Some([lo + d, hi + d]));
        }
        let image = Arc::new(Image { texture: image });
        let image = if params.guides {
            draw_guides(ctx, &image, &annotations, &camera, &params)?
        } else {
            Value::Image(image)
        };
        Ok(vec![
            image,
            Value::GBuffer(Arc::new(gbuffer)),
            Value::Annotations(Arc::new(annotations)),
        ])
    }
}

/// An arrow from each moved part's original centre (a dot) to its moved centre, over `image`.
fn draw_guides(
    ctx: &mut Ctx,
    image: &Arc<Image>,
    annotations: &Annotations,
    camera: &crate::camera::Camera,
    params: &ExplodedViewParams,
) -> Result<Value, NodeError> {
    let width = pixels("guide_width", params.guide_width)?;
    let (w, h) = (image.texture.width(), image.texture.height());
    let mut canvas = Canvas::new(w, h);
    for pair in annotations.anchors.chunks_exact(2) {
        if pair[0].position.distance(pair[1].position) < 1e-6 {
            continue;
        }
        let one = Annotations {
            anchors: pair.to_vec(),
            bounds: Vec::new(),
            placed: None,
        };
        if let Some((shaft, head)) =
            crate::visual_conventions::arrow_shape(&one, camera, (w, h), width, 0.0)?
        {
            canvas.disc(shaft[0], 1.5 * width + 1.0, params.guide_color);
            canvas.polyline(&shaft, width, params.guide_color);
            canvas.triangle(head, params.guide_color);
        }
    }
    canvas.draw_over(ctx, image, "image")
}

crate::bind_group! {
    /// ExplodedView's own bindings, after the object tables (shaders/exploded_view.wgsl).
    pub struct ExplodedBindings in "exploded_view", group 1 from 4 {
        pub parts: TextureView,
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(ExplodedViewNode)
        .program(
            "exploded_view",
            shaders::ray_objects(shaders::part!("exploded_view.wgsl")),
        )
        .bind_group(ExplodedBindings::layout())
        .uniform_in("exploded_view", TwoLevelUniforms::layout())
        .uniform_in("exploded_view", RayUniforms::layout())
        .bind_group_in("exploded_view", ObjectBindings::layout())
        .bind_group_in("exploded_view", RayBindings::layout())
        .bind_group_in("exploded_view", crate::raycast::RayOutputs::layout());
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names() -> std::collections::BTreeMap<u16, String> {
        [(13, "skeleton".to_owned()), (10, "liver".to_owned())].into()
    }

    #[test]
    fn the_grammar_reads_splits_moves_names_and_the_volume() {
        let specs = parse_parts(
            "Skeleton: split x 40; 10: move 0 30% 0; volume: split z -5",
            &names(),
            200.0,
        )
        .unwrap();
        assert_eq!(specs.len(), 3);
        assert_eq!((specs[0].id, specs[0].split), (13, Some((Vec3::X, 40.0))));
        assert_eq!(
            (specs[1].id, specs[1].displacement),
            (10, Vec3::new(0.0, 60.0, 0.0))
        );
        assert_eq!((specs[2].id, specs[2].split), (0, Some((Vec3::Z, -5.0))));
        let parts = expand(&specs);
        assert_eq!(parts.len(), 5);
        assert_eq!(parts[0].displacement, Vec3::new(40.0, 0.0, 0.0));
        assert_eq!(parts[1].displacement, Vec3::new(-40.0, 0.0, 0.0));
        assert_eq!(parts[1].name, "skeleton (−x half)");
    }

    #[test]
    fn errors_name_the_part_that_does_not_parse() {
        for (text, needle) in [
            (
                "liver: move 0 x 0",
                "part `liver: move 0 x 0`: `x` is not a number",
            ),
            ("heart: move 1 2 3", "no object is named `heart`"),
            ("liver: split w 3", "axis `w`"),
            ("liver move 1 2 3", "part `liver move 1 2 3`"),
            ("liver: move 1 2 3; 10: split x 1", "named twice"),
        ] {
            let e = parse_parts(text, &names(), 1.0).unwrap_err();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }

    #[test]
    fn shader_codes_match_the_object_table() {
        let source = crate::shaders::shader_file!("exploded_view.wgsl");
        for (name, code) in [
            ("MODE_SHADED", RenderMode::ShadedDvr.code()),
            ("MODE_TONE", RenderMode::Tone.code()),
            ("MODE_CONTOURS", RenderMode::Contours.code()),
            ("MODE_ISO", RenderMode::Iso.code()),
            ("LOCAL_ISO", Compositing::Iso.code()),
        ] {
            assert!(
                source.contains(&format!("const {name}: u32 = {code}u;")),
                "{name} ≠ {code}"
            );
        }
    }
}
