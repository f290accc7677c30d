//! `SelectionRender`: VolumeShop's selective illustration (Bruckner & Gröller; the tutorial's
//! VolumeShop chapter §4 eq. 1–5, §6.2 cutaways and ghosting, §6.3 placement): background,
//! ghost and a movable selection of one volume, with cutaways of the background and a ghosting
//! factor (see shaders/selection_render.wgsl).

use crate::annotations::Annotations;
use crate::camera::Camera;
use crate::raycast::{Kernel, KernelChoice, RayOptions, RayPipelines, RayUniforms, TableInfo};
use crate::value::{Image, Labels, TransferFunction};
use crate::{Ctx, Value};
use glam::{EulerRot, Mat3, Mat4, Vec3, Vec4Swizzles};
use hatchery_data::lighting;
use hatchery_data::transfer_function::{LUT_SIZE, TransferFunction1D};
use hatchery_gpu::GpuError;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

crate::uniform_block! {
    /// `Selection` of shaders/selection_render.wgsl.
    pub struct SelectionUniforms in "selection_render" as "Selection" {
        pub to_source: [[f32; 4]; 4],
        pub rotation: [[f32; 4]; 4],
        pub background_domain: [f32; 2],
        pub ghost_domain: [f32; 2],
        pub selection_domain: [f32; 2],
        pub ghosting: f32,
        /// A [`Cutaway`] code.
        pub cutaway: u32,
        pub shaded: u32,
        pub skip_empty: u32,
        /// Spacing (voxels) of the smoothed mask gradient shading the selection; 0 for none.
        pub surface_smoothing: f32,
        pub pad2: f32,
        /// The selected voxels' box widened by one voxel (voxel space): f_S is 0 outside it.
        pub mask_min: [f32; 3],
        pub pad3: f32,
        pub mask_max: [f32; 3],
        pub pad4: f32,
    }
}

hatchery_graph::param_choice! {
    /// How the selection is placed (§6.3).
    pub enum Placement {
        /// Moved by `translate`/`rotate` in the world: it follows the view like the scene.
        Integrated = "integrated",
        /// Its centre stays at the screen point `pin`; it turns with the view like the scene.
        Pinned = "pinned",
        /// Its centre stays at `pin` and its orientation is fixed relative to the viewer.
        Decoupled = "decoupled",
    }
}

/// The selection transform T (world → world, the source selection to where it is shown) for
/// `camera`: rotation `rotate` (XYZ Euler degrees; world axes, or view axes when decoupled)
/// about the selection's centre `centre`, then the centre moved to `centre + translate`
/// (integrated), or to the point under the frame fraction `pin` (x right, y down) at the view
/// depth of `centre + translate` (pinned) or of the camera's target (decoupled).
pub fn selection_transform(
    camera: &Camera,
    placement: Placement,
    centre: Vec3,
    translate: Vec3,
    rotate_deg: Vec3,
    pin: [f32; 2],
) -> Mat4 {
    let r = Mat3::from_euler(
        EulerRot::XYZ,
        rotate_deg.x.to_radians(),
        rotate_deg.y.to_radians(),
        rotate_deg.z.to_radians(),
    );
    let view_depth = |p: Vec3| -(camera.view * p.extend(1.0)).z;
    let pinned_at = |depth: f32| {
        // The ray through the pin point, to the given view depth.
        let inverse = camera.view_proj().inverse();
        let ndc = glam::Vec2::new(pin[0] * 2.0 - 1.0, 1.0 - pin[1] * 2.0);
        let unproject = |z: f32| {
            let h = inverse * ndc.extend(z).extend(1.0);
            h.xyz() / h.w
        };
        let (near, far) = (unproject(0.0), unproject(1.0));
        let (dn, df) = (view_depth(near), view_depth(far));
        near + (far - near) * ((depth - dn) / (df - dn))
    };
    let (position, rotation) = match placement {
        Placement::Integrated => (centre + translate, r),
        Placement::Pinned => (pinned_at(view_depth(centre + translate)), r),
        Placement::Decoupled => {
            let view_rotation = Mat3::from_mat4(camera.view);
            (
                pinned_at(view_depth(camera.target)),
                view_rotation.inverse() * r,
            )
        }
    };
    Mat4::from_translation(position) * Mat4::from_mat3(rotation) * Mat4::from_translation(-centre)
}

/// Parses "10" or "10, 11 12" into label ids.
fn parse_ids(text: &str) -> Result<Vec<u16>, NodeError> {
    let mut ids = Vec::new();
    for word in text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
    {
        match word.parse::<u64>() {
            Ok(id @ 1..=65535) => ids.push(id as u16),
            Ok(id) => {
                return Err(NodeError::new(format!(
                    "parameter `objects`: label id {id} is out of range (1–65535; 0 is the \
                     background)"
                )));
            }
            Err(_) => {
                return Err(NodeError::new(format!(
                    "parameter `objects`: `{word}` is not a label id (e.g. \"10\" or \"10, 11\")"
                )));
            }
        }
    }
    if ids.is_empty() {
        return Err(NodeError::new(
            "parameter `objects`: no label id given (e.g. \"10\" or \"10, 11\")",
        ));
    }
    Ok(ids)
}

/// Where the voxels holding `ids` are: their world-space centre (mean voxel position), their
/// world box (of voxel centres) and their voxel-index box; None when there are none.
struct Extent {
    centre: Vec3,
    bounds: [Vec3; 2],
    voxels: [Vec3; 2],
}

/// The extent of no voxel: a point at the grid's centre (the selection's box is empty there).
fn empty_extent(labels: &Labels) -> Extent {
    let l = &labels.data;
    let middle = Vec3::from(l.dims.map(|d| (d.max(1) - 1) as f32 * 0.5));
    let centre = l.geometry.voxel_to_world(middle);
    Extent {
        centre,
        bounds: [centre, centre],
        voxels: [middle, middle],
    }
}

fn extent_of(labels: &Labels, ids: &[u16]) -> Option<Extent> {
    let l = &labels.data;
    let [nx, ny, _] = l.dims.map(|d| d as usize);
    let (mut sum, mut count) = (glam::DVec3::ZERO, 0u64);
    let (mut lo, mut hi) = (glam::DVec3::splat(f64::MAX), glam::DVec3::splat(f64::MIN));
    for (i, id) in l.ids.iter().enumerate() {
        if ids.contains(id) {
            let v = glam::DVec3::new(
                (i % nx) as f64,
                (i / nx % ny) as f64,
                (i / (nx * ny)) as f64,
            );
            sum += v;
            lo = lo.min(v);
            hi = hi.max(v);
            count += 1;
        }
    }
    if count == 0 {
        return None;
    }
    let world = |v: Vec3| l.geometry.voxel_to_world(v);
    let corners = hatchery_annotation::box_corners(lo.as_vec3(), hi.as_vec3()).map(world);
    let min = corners.iter().copied().fold(Vec3::INFINITY, Vec3::min);
    let max = corners.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max);
    Some(Extent {
        centre: world((sum / count as f64).as_vec3()),
        bounds: [min, max],
        voxels: [lo.as_vec3(), hi.as_vec3()],
    })
}

/// The ghost (anchor 0, where the selection was) and the selection (anchor 1, where it is
/// shown), with their world boxes: what Arrow, Fan and BoundingBox draw (§6.3).
fn ghost_and_selection(
    name: String,
    centre: Vec3,
    bounds: [Vec3; 2],
    transform: Mat4,
) -> Annotations {
    let moved = hatchery_annotation::box_corners(bounds[0], bounds[1])
        .map(|c| transform.transform_point3(c));
    let moved_box = [
        moved.iter().copied().fold(Vec3::INFINITY, Vec3::min),
        moved.iter().copied().fold(Vec3::NEG_INFINITY, Vec3::max),
    ];
    let anchor = |position, text: String, priority| hatchery_annotation::Anchor {
        position,
        text,
        object: 0,
        priority,
    };
    Annotations {
        anchors: vec![
            anchor(centre, format!("{name} (original place)"), 0.5),
            anchor(transform.transform_point3(centre), name, 1.0),
        ],
        bounds: vec![Some(bounds), Some(moved_box)],
        placed: None,
    }
}

fn color_tf(
    inputs: &NodeInputs<Value>,
    port: &str,
) -> Result<Option<TransferFunction1D>, NodeError> {
    let Some(value) = inputs.get(port) else {
        return Ok(None);
    };
    match value.transfer_function(port)?.as_ref() {
        TransferFunction::Color(f) => Ok(Some(f.clone())),
        TransferFunction::Style { .. } => Err(NodeError::at_port(
            port,
            "a style transfer function; SelectionRender takes colour transfer functions",
        )),
        TransferFunction::TwoD(_) => Err(NodeError::at_port(
            port,
            "a 2-D transfer function; SelectionRender takes 1-D colour transfer functions",
        )),
    }
}

hatchery_graph::param_choice! {
    /// Whose far side the background is cut in front of.
    pub enum Cutaway {
        Ghost = "ghost",
        Selection = "selection",
        Both = "both",
        None = "none",
    }
}

crate::wgsl_constants! {
    Cutaway in "selection_render" {
        Ghost = "CUT_GHOST",
        Selection = "CUT_SELECTION",
        Both = "CUT_BOTH",
        None = "CUT_NONE",
    }
}

hatchery_graph::param_choice! {
    /// Lighting transfer function (eq. 8) or none (its names are the lighting models').
    pub enum Shading {
        PhongContour = "phong_contour",
        Phong = "phong",
        Cartoon = "cartoon",
        Metal = "metal",
        None = "none",
    }
}

hatchery_graph::node_params! {
    /// Parameters of `SelectionRender`.
    pub struct SelectionRenderParams {
        /// label ids of the selection, e.g. "10" or "10, 11"
        pub objects: String = "1";
        /// integrated: the selection's move, world units
        pub translate: [f32; 3] = [0.0, 0.0, 0.0];
        /// rotation about the selection's centre, XYZ Euler degrees (world axes; view axes when
        /// decoupled)
        pub rotate: [f32; 3] = [0.0, 0.0, 0.0];
        /// where the selection is drawn: in place in the volume (integrated), moved with its
        /// ghost left behind (pinned), or in a view of its own (decoupled) (§6.3)
        pub placement: Placement = Placement::Integrated;
        /// pinned/decoupled: the centre's screen position, fraction of the width from the left
        pub pin_x: f32 = 0.75, range(0.0, 1.0);
        /// pinned/decoupled: fraction of the height from the top
        pub pin_y: f32 = 0.3, range(0.0, 1.0);
        /// whose far side the background is cut in front of
        pub cutaway: Cutaway = Cutaway::Ghost;
        /// 0: no ghosting … 1: full cutaway
        pub ghosting: f32 = 0.7, range(0.0, 1.0);
        /// how the selection is lit: a lighting transfer function that darkens it where it
        /// faces away from the light (eq. 8), or none
        pub shading: Shading = Shading::PhongContour;
        /// sample distance in voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// reconstruction of the data between voxels: trilinear, or the tricubic B-spline's
        /// values and gradients (Hadwiger §1.3)
        pub reconstruction: crate::reconstruction::Reconstruction =
            crate::reconstruction::Reconstruction::Trilinear;
        /// shade the selection and its ghost with the selection mask's gradient averaged over
        /// ±this many voxels (the 3-D Sobel operator at this spacing) instead of the data's: for
        /// label maps given as the data, whose gradient steps at every slice; 0: the data's
        pub surface_smoothing: f32 = 0.0, range(0.0, 4.0);
        /// jitter the first sample per pixel
        pub jitter: bool = true;
        /// stop a ray at this opacity (1 = never)
        pub early_termination: f32 = 0.99, range(0.5, 1.0);
        /// GPU path: fragment shader or compute kernel (same picture)
        pub kernel: KernelChoice = KernelChoice::Auto;
    }
}

pub struct SelectionRenderNode;

impl Node<Value, Ctx> for SelectionRenderNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "SelectionRender",
            category: "Volume",
            doc: "VolumeShop selective illustration (Bruckner & Gröller, the tutorial's §4, \
                  §6.2–6.3): the labels listed in `objects` form the selection; the volume is \
                  drawn as background (tf), ghost (the selection where it was, tf_ghost) and \
                  selection (moved by translate/rotate, tf_selection), combined by eq. 1–5 \
                  (fuzzy sets: membership = min(selection degree, opacity); colour = \
                  membership-weighted mean, opacity = max). Cutaways act on the background in \
                  front of the ghost and/or the selection; `ghosting` goes from 0 (no ghosting) \
                  to 1 (full cutaway), combined with the lighting transfer function's opacity \
                  enhancement (eq. 8) so that enhanced contours survive ghosting. Placement: \
                  integrated (moves with the scene), pinned (its centre fixed on screen at \
                  `pin`, turning with the view) or decoupled (fixed on screen and in \
                  orientation).",
            inputs: vec![
                PortSpec::input("volume", PortType::Volume, "the scalar field f_V"),
                PortSpec::input(
                    "labels",
                    PortType::Labels,
                    "object ids on the volume's grid; `objects` picks the selection",
                ),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::input(
                    "tf",
                    PortType::TransferFunction,
                    "the background's colour TF",
                ),
                PortSpec::optional(
                    "tf_ghost",
                    PortType::TransferFunction,
                    "the ghost's (default: tf)",
                ),
                PortSpec::optional(
                    "tf_selection",
                    PortType::TransferFunction,
                    "the selection's (default: tf)",
                ),
                PortSpec::optional("light", PortType::Light, "the light (default: a headlight)"),
            ],
            outputs: vec![
                PortSpec::output("image", PortType::Image, "premultiplied colour"),
                PortSpec::output(
                    "gbuffer",
                    PortType::GBuffer,
                    "depth and normal where opaque",
                ),
                PortSpec::output(
                    "annotations",
                    PortType::Annotations,
                    "anchor 0: the ghost's centre, anchor 1: the selection's, with their boxes \
                     (for Arrow, Fan, BoundingBox and labels)",
                ),
            ],
            params: SelectionRenderParams::specs(),
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
        let params = SelectionRenderParams::read(p)?;
        let volume = inputs.require("volume")?.volume("volume")?.clone();
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        // The level of detail the device holds (see `Volume::resident`).
        let volume = volume.resident(&ctx.gpu).map_err(|e| NodeError::new(e.to_string()))?;
        let labels = labels.resident(&ctx.gpu).map_err(|e| NodeError::new(e.to_string()))?;
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        crate::raycast::objects::check_labels_grid(labels, volume)?;
        let background = color_tf(inputs, "tf")?.expect("a required input");
        let ghost = color_tf(inputs, "tf_ghost")?.unwrap_or_else(|| background.clone());
        let selected = color_tf(inputs, "tf_selection")?.unwrap_or_else(|| background.clone());
        let text = hatchery_data::segmentation::ids_for_names(
            params.objects.as_str(),
            ',',
            None,
            &labels.data.objects,
        )
        .map_err(|e| NodeError::new(format!("parameter `objects`: {e}")))?;
        let ids = parse_ids(&text)?;
        // An empty selection (a painting not begun yet) draws the background alone.
        let extent = match extent_of(labels, &ids) {
            Some(extent) => extent,
            None => {
                ctx.warn(format!(
                    "parameter `objects`: no voxel of the labels holds {ids:?} (ids present: {}): \
                     nothing is selected, the background alone is drawn",
                    labels
                        .data
                        .objects
                        .keys()
                        .map(|id| id.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
                empty_extent(labels)
            }
        };
        let (centre, bounds) = (extent.centre, extent.bounds);
        let placement = params.placement;
        let transform = selection_transform(
            &camera,
            placement,
            centre,
            Vec3::from(params.translate),
            Vec3::from(params.rotate),
            [params.pin_x, params.pin_y],
        );
        let v = &volume.data;
        let shading = params.shading.name();
        let shaded = params.shading != Shading::None;
        let kernel = Kernel::choose(params.kernel, &ctx.gpu);
        let options = RayOptions::plain(
            params.step,
            params.jitter,
            params.early_termination,
            crate::raycast::light_direction(inputs, &camera)?,
            kernel,
        );
        let info = TableInfo {
            domain: background.domain,
            ..TableInfo::plain()
        };
        let err = |e: GpuError| NodeError::new(e.to_string());
        // Bricked or not and the reconstruction as pipeline constants (shaders/ray_common.wgsl).
        let bricked = volume.texture(&ctx.gpu).map_err(err)?.layout.is_some();
        let reconstruction = params.reconstruction.on(ctx, &volume.data);
        let pipelines = ctx
            .cached(
                &format!("selection_render.pipelines.{bricked}.{}", reconstruction.code()),
                |gpu| {
                    let constants = [("RAY_BRICKED", bricked.into()), reconstruction.constant()];
                    RayPipelines::specialised(gpu, "selection_render", &constants)
                },
            )
            .map_err(err)?;
        let sampler = crate::raycast::linear_clamp_sampler(ctx).map_err(err)?;
        let gpu = &ctx.gpu;
        let volume_texture = volume.texture(gpu).map_err(err)?;
        let max_gradient = if shaded { volume.max_gradient() } else { 1.0 };
        let uniforms = RayUniforms::new(
            &camera,
            v,
            &options,
            &info,
            max_gradient,
            volume_texture.texel_range,
        )
        .with_bricks(volume_texture.layout.as_ref());
        let to_voxel = v.geometry.to_voxel().as_mat4();
        let selection = SelectionUniforms {
            to_source: (to_voxel * transform.inverse()).to_cols_array_2d(),
            rotation: Mat4::from_mat3(Mat3::from_mat4(transform)).to_cols_array_2d(),
            background_domain: background.domain,
            ghost_domain: ghost.domain,
            selection_domain: selected.domain,
            ghosting: params.ghosting,
            cutaway: params.cutaway.code(),
            shaded: shaded.into(),
            skip_empty: 1,
            surface_smoothing: params.surface_smoothing,
            pad2: 0.0,
            // One voxel for the trilinear footprint, a little more for rounding.
            mask_min: (extent.voxels[0] - 1.01).to_array(),
            pad3: 0.0,
            mask_max: (extent.voxels[1] + 1.01).to_array(),
            pad4: 0.0,
        };
        // Which values the background shows, for skipping the bricks it hides (ray_skip).
        let visibility = gpu.texture_2d_init(
            "selection visibility",
            hatchery_data::bricks::VISIBILITY_ENTRIES as u32,
            1,
            wgpu::TextureFormat::R32Float,
            bytemuck::cast_slice(&hatchery_data::bricks::visibility_prefix(
                v.value_range,
                &[hatchery_data::bricks::OpacityRow {
                    domain: background.domain,
                    opacity: &background.lut.iter().map(|e| e[3]).collect::<Vec<_>>(),
                }],
            )),
        );
        let bricks = volume.bricks(gpu, reconstruction).map_err(err)?;
        let tf_rows: Vec<f32> = [&background, &ghost, &selected]
            .iter()
            .flat_map(|f| f.lut.iter().flatten().copied())
            .collect();
        let lighting_model = lighting::lighting_tf(if shaded { shading } else { "phong" })
            .ok_or_else(|| NodeError::new(format!("unknown lighting model `{shading}`")))?;
        let lighting_flat: Vec<f32> = lighting_model.table.iter().flatten().copied().collect();
        let size = lighting::LIGHTING_SIZE as u32;
        let ray_buffer = gpu.buffer_init(
            "selection ray",
            bytemuck::bytes_of(&uniforms),
            wgpu::BufferUsages::UNIFORM,
        );
        let selection_buffer = gpu.buffer_init(
            "selection",
            bytemuck::bytes_of(&selection),
            wgpu::BufferUsages::UNIFORM,
        );
        let tf_texture = gpu.texture_2d_init(
            "selection tfs",
            LUT_SIZE as u32,
            3,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&tf_rows),
        );
        let lighting_texture = gpu.texture_2d_init(
            "selection lighting tf",
            size,
            size,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&lighting_flat),
        );
        let mut sorted = ids.clone();
        sorted.sort_unstable();
        let mask = labels.selection_mask(gpu, &sorted).map_err(err)?;
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let views = [
            view(&volume_texture.texture),
            view(&tf_texture),
            view(&lighting_texture),
            view(&mask.texture),
            view(&volume_texture.page_table),
            view(bricks),
            view(&visibility),
        ];
        let shared = crate::raycast::RayBindings {
            ray: Some(&ray_buffer),
            volume: Some(&views[0]),
            linear_clamp: Some(&sampler),
            tf_table: Some(&views[1]),
            lighting_table: Some(&views[2]),
            page_table: Some(&views[4]),
            bricks: Some(&views[5]),
            visibility: Some(&views[6]),
            ..Default::default()
        };
        let own = SelectionBindings {
            selection: Some(&selection_buffer),
            selection_mask: Some(&views[3]),
        };
        let groups = [shared.entries(), own.entries()];
        let (image, gbuffer) = pipelines.run(ctx, &camera, groups, kernel)?;
        let name = ids
            .iter()
            .map(|id| {
                labels
                    .data
                    .objects
                    .get(id)
                    .cloned()
                    .unwrap_or_else(|| format!("object {id}"))
            })
            .collect::<Vec<_>>()
            .join(", ");
        Ok(vec![
            Value::Image(Arc::new(Image { texture: image })),
            Value::GBuffer(Arc::new(gbuffer)),
            Value::Annotations(Arc::new(ghost_and_selection(
                name, centre, bounds, transform,
            ))),
        ])
    }
}


crate::bind_group! {
    /// SelectionRender's own bindings (shaders/selection_render.wgsl).
    pub struct SelectionBindings in "selection_render", group 1 from 0 {
        pub selection: Buffer,
        pub selection_mask: TextureView,
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(SelectionRenderNode)
        .program("selection_render", shaders::ray(shaders::part!("selection_render.wgsl")))
        .uniform(SelectionUniforms::layout())
        .bind_group(SelectionBindings::layout())
        .bind_group_in("selection_render", crate::raycast::RayBindings::layout())
        .bind_group_in("selection_render", crate::raycast::RayOutputs::layout())
        .gpu_enum(Cutaway::wgsl())
        .uniform_in("selection_render", crate::raycast::RayUniforms::layout());
}
