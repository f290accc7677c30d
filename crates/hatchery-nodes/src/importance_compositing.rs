//! `ImportanceCompositing`: the importance compositing step of importance-driven volume
//! rendering (Viola et al.; the tutorial's "Importance Compositing", eq. 1–3). From the labels,
//! each object's importance and the camera it computes, per pixel, the focus object's footprint,
//! the countersink depth (eq. 1) and the footprint-weighted importance sum (eq. 2's denominator),
//! which `TwoLevelRaycast` turns into levels of sparseness (see shaders/importance.wgsl).
//!
//! The distance transform d_i of eq. 1 is jump flooding with one extra pass of step 1 (1+JFA,
//! Rong & Tan 2006) instead of the paper's chamfer transform: Euclidean, and exact except for
//! rare pixels whose nearest seed is lost between flooding steps (then off by a fraction of a
//! pixel; tests/importance.rs compares it with a brute-force EDT).

use crate::raycast::{Grid, Kernel, RayOptions, RayUniforms, TableInfo};
use crate::raycast::{ImportanceBindings, ImportancePipelines, PassUniforms, PingPong, RayBindings};
use crate::raycast::objects::{ObjectBindings, TABLE_WIDTH, TwoLevelUniforms, brick_table, object_tables};
use crate::value::{Importance, ImportanceMethod, ObjectStyle};
use crate::{Ctx, Value};
use hatchery_gpu::GpuError;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

/// Drawn objects that can take part in the importance sum (one bit each per pixel).
const MAX_OBJECTS: usize = 32;

crate::uniform_block! {
    /// `ImportanceParams` of shaders/importance.wgsl.
    pub struct ImportanceUniforms in "importance" as "ImportanceParams" {
        pub frame_size: [u32; 2],
        pub slope: f32,
        pub orthographic: u32,
        pub pixel_world: f32,
        pub focus: u32,
        /// The bits of every drawn object's table row (slots 0..32).
        pub all_rows: u32,
        /// The buffer's second channel: 0 Σ I, 1 MImP's highest importance behind the
        /// countersink, 2 zero (a cutaway).
        pub second_channel: u32,
        pub weights: [[f32; 4]; 8],
    }
}

/// The focus: `requested` if it is drawn, else (0) the drawn object of highest importance.
fn focus_object(styles: &[ObjectStyle], requested: u32) -> Result<u16, NodeError> {
    let drawn: Vec<&ObjectStyle> = styles.iter().filter(|s| s.enabled).collect();
    if requested > 0 {
        return match drawn.iter().find(|s| u32::from(s.id) == requested) {
            Some(s) => Ok(s.id),
            None => Err(NodeError::new(format!(
                "parameter `focus`: object {requested} is not drawn by the object table (drawn: {})",
                drawn
                    .iter()
                    .map(|s| s.id.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))),
        };
    }
    drawn
        .iter()
        .max_by(|a, b| a.importance.total_cmp(&b.importance))
        .map(|s| s.id)
        .ok_or_else(|| NodeError::at_port("styles", "no object of the table is drawn"))
}

hatchery_graph::param_choice! {
    /// Importance compositing: mimp, cutaway, aimc_image, aimc_object, vpimc.
    pub enum Method {
        Mimp = "mimp",
        Cutaway = "cutaway",
        AimcImage = "aimc_image",
        AimcObject = "aimc_object",
        Vpimc = "vpimc",
    }
}

hatchery_graph::param_choice! {
    /// Conical (eq. 1) or cylindrical (the footprint swept along the rays).
    pub enum Countersink { Conical = "conical", Cylindrical = "cylindrical" }
}

hatchery_graph::param_choice! {
    /// Object membership, as TwoLevelRaycast's.
    pub enum Boundary { Filtered = "filtered", Point = "point" }
}

hatchery_graph::node_params! {
    /// Parameters of `ImportanceCompositing`.
    pub struct ImportanceCompositingParams {
        /// how importance decides what is drawn: mimp (per ray only its most important object,
        /// the focus's countersink cut away), cutaway (only the countersink cut away, the other
        /// objects drawn as usual), aimc_image, aimc_object (levels of sparseness I_o / Σ I) or
        /// vpimc (the occluders' opacity kept constant)
        pub method: Method = Method::Mimp;
        /// the focus object's id (0: the drawn object of highest importance)
        pub focus: u32 = 0, range(0, 65535);
        /// conical (eq. 1) or cylindrical (the footprint swept along the rays)
        pub countersink: Countersink = Countersink::Conical;
        /// the cut-away's slope: how much deeper it gets per unit of distance from the focus on
        /// screen, a cone around the focus (s_c of eq. 1; both in world units)
        pub slope: f32 = 1.0, range(0.05, 20.0);
        /// image-space AImC: dilate and average the footprints over this radius (pixels) for smooth
        /// transitions between levels of sparseness
        pub transition: f32 = 0.0, range(0.0, 64.0), unit(pixels);
        /// sample distance along the rays in voxels (of the smallest spacing)
        pub step: f32 = 0.5, range(0.05, 8.0);
        /// object membership, as TwoLevelRaycast's
        pub boundary: Boundary = Boundary::Filtered;
    }
}

pub struct ImportanceCompositingNode;

impl Node<Value, Ctx> for ImportanceCompositingNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "ImportanceCompositing",
            category: "Volume",
            doc: "Importance compositing (Viola et al., importance-driven feature enhancement): \
                  per pixel, the focus object's footprint (its first and last hit along the \
                  ray), the countersink depth e_i = e_max − d_i·s_c (eq. 1; d_i the distance to \
                  the footprint by jump flooding, e_max the footprint's deepest last hit) and \
                  the importance sum Σ I of the objects the ray meets, their footprints dilated \
                  and averaged over `transition` pixels (image-space AImC, eq. 2). Feed it to \
                  TwoLevelRaycast's `importance` input with the same camera. Methods: mimp \
                  (maximum importance projection, §IV.A: per ray only the most important object \
                  it meets behind the countersink is drawn, so only the focus in its footprint, \
                  and the context cut away in front of the countersink), cutaway (the same cut, \
                  but every object behind it drawn as usual), aimc_image / aimc_object (average \
                  importance compositing: levels of sparseness S_o = I_o / Σ I for every sample, \
                  or for the context in front of the countersink only), vpimc (visibility \
                  preserving: the occluding context's opacity scaled by S_o / α_avg, eq. 3). \
                  Importance comes from ObjectStyles' `importance=`.",
            inputs: vec![
                PortSpec::input(
                    "labels",
                    PortType::Labels,
                    "object ids on the volume's grid",
                ),
                PortSpec::input(
                    "styles",
                    PortType::ObjectStyles,
                    "the object table: drawn objects and their importance",
                ),
                PortSpec::input("camera", PortType::Camera, "the view"),
            ],
            outputs: vec![PortSpec::output(
                "importance",
                PortType::Importance,
                "footprint, countersink and importance sums of this view",
            )],
            params: ImportanceCompositingParams::specs(),
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
        let params = ImportanceCompositingParams::read(p)?;
        let labels = inputs.require("labels")?.labels("labels")?.clone();
        // The level of detail the device holds (see `Labels::resident`).
        let labels = labels.resident(&ctx.gpu).map_err(|e| NodeError::new(e.to_string()))?;
        let styles = inputs.require("styles")?.object_styles("styles")?.clone();
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let method = match params.method {
            Method::Mimp | Method::Cutaway => ImportanceMethod::Mimp,
            Method::AimcImage => ImportanceMethod::AimcImage,
            Method::AimcObject => ImportanceMethod::AimcObject,
            Method::Vpimc => ImportanceMethod::Vpimc,
        };
        let focus = focus_object(&styles, params.focus)?;
        let drawn: Vec<&ObjectStyle> = styles.iter().filter(|s| s.enabled).collect();
        if drawn.len() > MAX_OBJECTS {
            ctx.warn(format!(
                "{} objects are drawn; only the first {MAX_OBJECTS} count in importance sums",
                drawn.len()
            ));
        }
        let mut weights = [[0.0f32; 4]; 8];
        for (i, s) in drawn.iter().take(MAX_OBJECTS).enumerate() {
            weights[i / 4][i % 4] = s.importance.max(0.0);
        }
        let err = |e: GpuError| NodeError::new(e.to_string());
        let bricked = labels.texture(&ctx.gpu).map_err(err)?.layout.is_some();
        let (ids_texture, id_quads) =
            crate::raycast::objects::object_id_texture(&ctx.gpu, labels, bricked).map_err(err)?;
        // Specialised on what this run reads (lavapipe folds `const`s, not uniforms).
        let constants = [
            id_quads,
            ("RAY_BRICKED", f64::from(u8::from(bricked))),
            ("TL_FILTER", f64::from(u8::from(params.boundary != Boundary::Point))),
        ];
        let key = constants.iter().map(|(_, v)| v.to_string()).collect::<Vec<_>>().join(".");
        let pipelines = ctx
            .cached(&format!("importance.pipelines.{key}"), |gpu| {
                ImportancePipelines::specialised(gpu, &constants)
            })
            .map_err(err)?;
        let sampler = crate::raycast::linear_clamp_sampler(ctx).map_err(err)?;
        let gpu = &ctx.gpu;
        let (w, h) = (camera.width, camera.height);
        let l = &labels.data;
        let grid = Grid {
            dims: l.dims,
            geometry: &l.geometry,
            value_range: [0.0, 1.0],
        };
        let options = RayOptions::plain(params.step, false, 1.0, glam::Vec3::Z, Kernel::Compute);
        let info = TableInfo {
            skip_empty: true,
            ..TableInfo::plain()
        };
        let ids = labels.texture(gpu).map_err(err)?;
        let ray = RayUniforms::for_grid(&camera, &grid, &options, &info, 1.0, [0.0, 1.0])
            .with_bricks(ids.layout.as_ref());
        let page_table = crate::brick_pool::page_table(gpu, ids.layout.as_ref());
        let tables = object_tables(&styles);
        let two_level = TwoLevelUniforms {
            boundary_filter: (params.boundary != Boundary::Point).into(),
            columns: tables.columns,
            ..Default::default()
        };
        let proj_y = camera.proj.y_axis.y;
        let slope = if params.countersink == Countersink::Cylindrical {
            0.0
        } else {
            params.slope
        };
        // Image-space AImC dilates and averages the footprints over this radius (pixels).
        let radius = if method == ImportanceMethod::AimcImage {
            params.transition.round() as u32
        } else {
            0
        };
        let params = ImportanceUniforms {
            frame_size: [w, h],
            slope,
            orthographic: camera.orthographic.into(),
            pixel_world: 2.0 / (proj_y * h as f32),
            focus: focus.into(),
            all_rows: match tables.rows {
                32.. => u32::MAX,
                n => (1 << n) - 1,
            },
            second_channel: match params.method {
                Method::Mimp => 1,
                Method::Cutaway => 2,
                _ => 0,
            },
            weights,
        };
        let uniform =
            |label, bytes: &[u8]| gpu.buffer_init(label, bytes, wgpu::BufferUsages::UNIFORM);
        let ray_buffer = uniform("importance ray", bytemuck::bytes_of(&ray));
        let two_level_buffer = uniform("importance objects", bytemuck::bytes_of(&two_level));
        let params_buffer = uniform("importance params", bytemuck::bytes_of(&params));
        let mut drawn_ids: Vec<u16> = drawn.iter().map(|s| s.id).collect();
        drawn_ids.sort_unstable();
        let drawn_mask = labels.drawn_mask(gpu, &drawn_ids).map_err(err)?;
        let (brick_dims, brick_ranges) = brick_table(labels, &styles);
        let brick_texture = gpu.texture_3d_init(
            "importance bricks",
            brick_dims,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&brick_ranges),
        );
        let table_texture = gpu.texture_2d_init(
            "importance object table",
            TABLE_WIDTH,
            (tables.table.len() / 4) as u32 / TABLE_WIDTH,
            wgpu::TextureFormat::Rgba32Float,
            bytemuck::cast_slice(&tables.table),
        );
        use wgpu::TextureFormat as F;
        let target = |label, format| gpu.storage_target(label, w, h, format);
        let footprint = target("focus footprint", F::Rgba32Float);
        let bits = [
            target("object bits", F::R32Uint),
            target("object bits'", F::R32Uint),
        ];
        let sums = [
            target("importance sum", F::R32Float),
            target("importance sum'", F::R32Float),
        ];
        let seeds = [
            target("jfa seeds", F::Rg32Float),
            target("jfa seeds'", F::Rg32Float),
        ];
        let stats = gpu.storage_target("importance stats", 1, 1, F::Rgba32Float);
        let buffer = target("importance buffer", F::Rgba32Float);
        let cut = target("countersink", F::Rgba32Float);
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let (footprint_v, stats_v, buffer_v, cut_v) =
            (view(&footprint), view(&stats), view(&buffer), view(&cut));
        let bits_v = [view(&bits[0]), view(&bits[1])];
        let sums_v = [view(&sums[0]), view(&sums[1])];
        let seeds_v = [view(&seeds[0]), view(&seeds[1])];
        let groups = (w.div_ceil(8), h.div_ceil(8));
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let (ids_v, drawn_v, bricks_v, table_v, pages_v) = (
            view(ids_texture),
            view(&drawn_mask.texture),
            view(&brick_texture),
            view(&table_texture),
            view(&page_table),
        );
        pipelines.dispatch(
            gpu,
            &mut encoder,
            "footprint",
            [
                RayBindings {
                    ray: Some(&ray_buffer),
                    linear_clamp: Some(&sampler),
                    bricks: Some(&bricks_v),
                    page_table: Some(&pages_v),
                    ..Default::default()
                }.entries(),
                [
                    ObjectBindings {
                        object_ids: Some(&ids_v),
                        objects: Some(&table_v),
                        two_level: Some(&two_level_buffer),
                        drawn_mask: Some(&drawn_v),
                    }
                    .entries(),
                    ImportanceBindings {
                        imp: Some(&params_buffer),
                        footprint_out: Some(&footprint_v),
                        bits_out: Some(&bits_v[0]),
                        ..Default::default()
                    }.entries(),
                ]
                .concat(),
            ],
            groups,
        );
        // Image-space AImC: dilate the footprints (OR of the bits), weigh, then average, each
        // separably (x, then y).
        let separable: &[[u32; 2]] = if radius > 0 {
            &[[0, radius], [1, radius]]
        } else {
            &[]
        };
        let bits_at = pipelines.ping_pong(
            gpu,
            &mut encoder,
            "dilate",
            &params_buffer,
            &bits_v,
            PingPong::Bits,
            separable,
            groups,
        );
        pipelines.dispatch(
            gpu,
            &mut encoder,
            "weigh",
            [
                Vec::new(),
                ImportanceBindings {
                    imp: Some(&params_buffer),
                    bits_in: Some(&bits_v[bits_at]),
                    sum_out: Some(&sums_v[0]),
                    ..Default::default()
                }.entries(),
            ],
            groups,
        );
        let sum_at = pipelines.ping_pong(
            gpu,
            &mut encoder,
            "box",
            &params_buffer,
            &sums_v,
            PingPong::Sums,
            separable,
            groups,
        );
        // 1+JFA: steps N/2, N/4, …, 1, then 1 again.
        pipelines.dispatch(
            gpu,
            &mut encoder,
            "jfa_init",
            [
                Vec::new(),
                ImportanceBindings {
                    imp: Some(&params_buffer),
                    footprint_in: Some(&footprint_v),
                    seed_out: Some(&seeds_v[0]),
                    ..Default::default()
                }.entries(),
            ],
            groups,
        );
        let mut steps = Vec::new();
        let mut k = w.max(h).next_power_of_two() / 2;
        while k >= 1 {
            steps.push([k, 0]);
            k /= 2;
        }
        steps.push([1, 0]);
        let seed_at = pipelines.ping_pong(
            gpu,
            &mut encoder,
            "jfa_step",
            &params_buffer,
            &seeds_v,
            PingPong::Seeds,
            &steps,
            groups,
        );
        pipelines.dispatch(
            gpu,
            &mut encoder,
            "reduce",
            [
                Vec::new(),
                ImportanceBindings {
                    imp: Some(&params_buffer),
                    footprint_in: Some(&footprint_v),
                    stats_out: Some(&stats_v),
                    ..Default::default()
                }.entries(),
            ],
            (1, 1),
        );
        // (MImP's per-ray rule marches the rays again behind the countersink.)
        pipelines.dispatch(
            gpu,
            &mut encoder,
            "finish",
            [
                RayBindings {
                    ray: Some(&ray_buffer),
                    linear_clamp: Some(&sampler),
                    bricks: Some(&bricks_v),
                    page_table: Some(&pages_v),
                    ..Default::default()
                }
                .entries(),
                [
                    ObjectBindings {
                        object_ids: Some(&ids_v),
                        objects: Some(&table_v),
                        two_level: Some(&two_level_buffer),
                        drawn_mask: Some(&drawn_v),
                    }
                    .entries(),
                    ImportanceBindings {
                    imp: Some(&params_buffer),
                    sum_in: Some(&sums_v[sum_at]),
                    footprint_in: Some(&footprint_v),
                    seed_in: Some(&seeds_v[seed_at]),
                    stats_in: Some(&stats_v),
                    buffer_out: Some(&buffer_v),
                    cut_out: Some(&cut_v),
                    ..Default::default()
                }.entries(),
                ]
                .concat(),
            ],
            groups,
        );
        ctx.submit(encoder.finish());
        let importance = drawn
            .iter()
            .map(|s| (s.id, s.importance.max(0.0)))
            .collect();
        Ok(vec![Value::Importance(Arc::new(Importance {
            method,
            focus,
            importance,
            buffer,
            cut,
            stats,
            camera: (*camera).clone(),
        }))])
    }
}


/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    use crate::shaders;
    k.node(ImportanceCompositingNode)
        .program("importance", shaders::ray_objects(shaders::part!("importance.wgsl")))
        .uniform(ImportanceUniforms::layout())
        .uniform(PassUniforms::layout())
        .uniform_in(
            "importance",
            TwoLevelUniforms::layout(),
        )
        .uniform_in("importance", crate::raycast::RayUniforms::layout())
        .bind_group(ImportanceBindings::layout())
        .bind_group_in("importance", ObjectBindings::layout())
        .bind_group_in("importance", crate::raycast::RayBindings::layout())
        // In the module through ray_common.wgsl; the kernels write their own outputs.
        .bind_group_in("importance", crate::raycast::RayOutputs::layout());
}
