//! The pieces both ray casters of segmented volumes share (`TwoLevelRaycast` and
//! `ImportanceCompositing`): the `TwoLevel` uniform block, the object tables (per-object
//! transfer functions and modes) and the brick table of drawn objects, and the check that labels
//! and volume share one grid.

use crate::value::{Compositing, ImportanceMethod, Labels, ObjectStyle, RenderMode, Volume};
use hatchery_data::transfer_function::LUT_SIZE;
use hatchery_graph::NodeError;

crate::uniform_block! {
    /// `TwoLevel` of shaders/ray_objects.wgsl (its comments say what each field holds).
    pub struct TwoLevelUniforms in "two_level_raycast" as "TwoLevel" {
        /// A [`Global`](crate::two_level_raycast::Global) code.
        pub global_mode: u32,
        pub boundary_filter: u32,
        pub columns: u32,
        pub mask_normals: u32,
        /// An [`ImportanceMethod`] code, 0 for none.
        pub method: u32,
        /// A [`Sparseness`](crate::two_level_raycast::Sparseness) code.
        pub level: u32,
        pub focus: u32,
        pub first_pass: u32,
        /// A [`RenderMode`] and a [`Compositing`] code.
        pub sparse_mode: u32,
        pub sparse_local: u32,
        pub cut_band: f32,
        /// Spacing (voxels) of the smoothed mask gradient at iso-surfaces; 0 for none.
        pub surface_smoothing: f32,
        /// Volume thinning (sparseness `thinning`): 1 / the volume's largest gradient
        /// magnitude, the smallest spacing (world: the Hessian's step and the curvature unit),
        /// and the number of gradient-magnitude levels B.
        pub thin_gradient: f32,
        pub thin_step: f32,
        pub thin_bands: f32,
        pub pad0: f32,
    }
}

crate::bind_group! {
    /// The object tables of shaders/ray_objects.wgsl, first in group 1 of both casters of
    /// segmented volumes.
    pub struct ObjectBindings in "two_level_raycast", group 1 from 0 {
        pub object_ids: TextureView,
        pub objects: TextureView,
        pub two_level: Buffer,
        pub drawn_mask: TextureView,
    }
}

crate::wgsl_constants! {
    RenderMode in "two_level_raycast" {
        Dvr = "MODE_DVR",
        ShadedDvr = "MODE_SHADED",
        Tone = "MODE_TONE",
        Contours = "MODE_CONTOURS",
        Mip = "MODE_MIP",
        Iso = "MODE_ISO",
    }
}

crate::wgsl_constants! {
    Compositing in "two_level_raycast" {
        Over = "LOCAL_OVER",
        Mip = "LOCAL_MIP",
        Iso = "LOCAL_ISO",
        Sum = "LOCAL_SUM",
    }
}

crate::wgsl_constants! {
    ImportanceMethod in "two_level_raycast" {
        Mimp = "IMP_MIMP",
        AimcImage = "IMP_AIMC_IMAGE",
        AimcObject = "IMP_AIMC_OBJECT",
        Vpimc = "IMP_VPIMC",
    }
}

/// The object table as textures: the TF rows (LUT_SIZE × drawn objects, RGBA) and, per id,
/// (row + 1 or 0, mode, compositing, iso) / (domain lo, hi, importance, 0).
pub(crate) struct ObjectTables {
    pub tf_rows: Vec<f32>,
    pub rows: u32,
    /// Largest id + 1.
    pub columns: u32,
    /// TABLE_WIDTH × (2 · ceil(columns / TABLE_WIDTH)) texels.
    pub table: Vec<f32>,
}

/// Ids per row pair of the object table: id → column id % 256, rows 2 · (id / 256) (modes) and
/// the one after (TF domain), so every u16 id fits any adapter's 2-D texture limit.
pub(crate) const TABLE_WIDTH: u32 = 256;

/// The gradient magnitude the segmented ray casters normalise by: with normals from object
/// masks, a mask's central difference across a 0 → 1 step (at most 0.5 per voxel of the
/// smallest spacing); else the volume's largest gradient where a drawn object draws contours;
/// else 1.
pub(crate) fn segmented_max_gradient(
    volume: &Volume,
    styles: &[ObjectStyle],
    object_normals: bool,
) -> f32 {
    let contours = styles
        .iter()
        .any(|s| s.enabled && s.mode == RenderMode::Contours);
    let min_spacing = volume
        .data
        .spacing()
        .iter()
        .copied()
        .fold(f32::INFINITY, f32::min);
    match (object_normals, contours) {
        (true, _) => 0.5 / min_spacing,
        (false, true) => volume.max_gradient(),
        (false, false) => 1.0,
    }
}

pub(crate) fn object_tables(styles: &[ObjectStyle]) -> ObjectTables {
    let columns = styles
        .iter()
        .map(|s| s.id as u32 + 1)
        .max()
        .unwrap_or(1)
        .max(1);
    let height = 2 * columns.div_ceil(TABLE_WIDTH);
    let mut table = vec![0.0f32; (TABLE_WIDTH * height) as usize * 4];
    let texel = |id: u16, which: u32| {
        let (x, y) = (id as u32 % TABLE_WIDTH, id as u32 / TABLE_WIDTH * 2 + which);
        (y * TABLE_WIDTH + x) as usize * 4
    };
    let mut tf_rows = Vec::new();
    let mut rows = 0u32;
    for s in styles.iter().filter(|s| s.enabled) {
        rows += 1;
        tf_rows.extend(s.tf.lut.iter().flatten().copied());
        let at = texel(s.id, 0);
        table[at..at + 4].copy_from_slice(&[
            rows as f32,
            s.mode.code() as f32,
            s.compositing.code() as f32,
            s.iso,
        ]);
        let at = texel(s.id, 1);
        table[at..at + 4].copy_from_slice(&[s.tf.domain[0], s.tf.domain[1], s.importance, 0.0]);
    }
    if rows == 0 {
        rows = 1;
        tf_rows = vec![0.0; LUT_SIZE * 4];
    }
    ObjectTables {
        tf_rows,
        rows,
        columns,
        table,
    }
}

/// Per 8³-voxel brick: (0, 1, id, rows) where a sample in the brick can belong to a drawn
/// object, (1, 0, id, rows) (an empty range: "skip") elsewhere; id = the one object every sample
/// in the brick sees, or −1 where there are several (then each sample filters its 8 voxels);
/// rows = the bits of the table rows of the drawn objects in the brick (−1: a row past 23).
pub(crate) fn brick_table(labels: &Labels, styles: &[ObjectStyle]) -> ([u32; 3], Vec<[f32; 4]>) {
    // Each drawn id's table row (its slot among the enabled styles), None if not drawn.
    let mut row = vec![None; u16::MAX as usize + 1];
    for (slot, s) in styles.iter().filter(|s| s.enabled).enumerate() {
        row[s.id as usize] = Some(slot);
    }
    let bricks = labels.brick_objects();
    let table = bricks
        .ids
        .iter()
        .map(|ids| {
            let single = if ids.len() == 1 {
                f32::from(ids[0])
            } else {
                -1.0
            };
            // The rows of the drawn objects the brick holds, as bits (exact in an f32 up to
            // slot 23; −1 when a later slot is among them).
            let rows = ids.iter().filter_map(|&id| row[id as usize]);
            let mask = rows
                .clone()
                .try_fold(0u32, |m, slot| (slot < 24).then(|| m | 1 << slot));
            let mask = mask.map_or(-1.0, |m| m as f32);
            if rows.count() > 0 {
                [0.0, 1.0, single, mask]
            } else {
                [1.0, 0.0, single, mask]
            }
        })
        .collect();
    (bricks.dims, table)
}

/// Labels and volume must share one grid: the same voxel counts and voxel → world transform.
pub(crate) fn check_labels_grid(
    labels: &Labels,
    volume: &crate::value::Volume,
) -> Result<(), NodeError> {
    let (l, v) = (&labels.data, &volume.data);
    if l.dims != v.dims {
        return Err(NodeError::at_port(
            "labels",
            format!(
                "the labels are {:?} voxels, the volume {:?}: they must share the grid",
                l.dims, v.dims
            ),
        ));
    }
    let tolerance = 1e-3 * v.geometry.spacing.min_element();
    if !l
        .geometry
        .to_world()
        .abs_diff_eq(v.geometry.to_world(), tolerance)
    {
        return Err(NodeError::at_port(
            "labels",
            format!(
                "the labels lie elsewhere in the world ({}) than the volume ({})",
                l.geometry.describe(),
                v.geometry.describe()
            ),
        ));
    }
    Ok(())
}

/// The texture to bind as `object_ids` (shaders/ray_objects.wgsl) and the `TL_ID_QUADS`
/// constant that goes with it: the labels' 2×2 id quads where they are made (CPU adapters,
/// value/id_quads.rs) and the pipeline reads an unbricked grid, else the one-id texture.
/// Errors: the uploads'.
pub(crate) fn object_id_texture<'l>(
    gpu: &hatchery_gpu::GpuContext,
    labels: &'l Labels,
    bricked: bool,
) -> Result<(&'l wgpu::Texture, (&'static str, f64)), hatchery_gpu::GpuError> {
    let quads = if bricked { None } else { labels.id_quads(gpu)? };
    Ok(match quads {
        Some(t) => (t, ("TL_ID_QUADS", 1.0)),
        None => (&labels.texture(gpu)?.texture, ("TL_ID_QUADS", 0.0)),
    })
}
