//! The pieces both ray casters of segmented volumes share (`TwoLevelRaycast` and
//! `ImportanceCompositing`): the `TwoLevel` uniform block, the object tables (per-object
//! transfer functions and modes) and the brick table of drawn objects, and the check that labels
//! and volume share one grid.

use crate::value::{Compositing, Labels, ObjectStyle, RenderMode};
use hatchery_data::transfer_function::LUT_SIZE;
use hatchery_graph::NodeError;

crate::uniform_block! {
    /// `TwoLevel` of shaders/two_level_raycast.wgsl: (global compositing 0 over / 1 mip /
    /// 2 sum, 1 for boundary filtering, columns of the object table, 1 for normals from the
    /// objects' masks).
    pub struct TwoLevelUniforms in "two_level_raycast" as "TwoLevel" {
        pub options: [f32; 4],
        /// Importance-driven rendering: (method 0 none / 1 MImP / 2 AImC image / 3 AImC
        /// object / 4 VPImC, level of sparseness 0 opacity / 1 saturation / 2 screen door /
        /// 3 style, focus id, 1 in VPImC's first pass).
        pub importance: [f32; 4],
        /// (sparse style's rendering mode, its local compositing, depth band shaded with the
        /// countersink's normal in world units, 0).
        pub sparse: [f32; 4],
    }
}

pub(crate) fn mode_code(mode: RenderMode) -> f32 {
    match mode {
        RenderMode::Dvr => 0.0,
        RenderMode::ShadedDvr => 1.0,
        RenderMode::Tone => 2.0,
        RenderMode::Contours => 3.0,
        RenderMode::Mip => 4.0,
        RenderMode::Iso => 5.0,
    }
}

pub(crate) fn compositing_code(c: Compositing) -> f32 {
    match c {
        Compositing::Over => 0.0,
        Compositing::Mip => 1.0,
        Compositing::Iso => 2.0,
        Compositing::Sum => 3.0,
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
            mode_code(s.mode),
            compositing_code(s.compositing),
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

/// Per 8³-voxel brick: (0, 1, id, 0) where a sample in the brick can belong to a drawn object,
/// (1, 0, id, 0) (an empty range: "skip") elsewhere; id = the one object every sample in the
/// brick sees, or −1 where there are several (then each sample filters its 8 voxels).
pub(crate) fn brick_table(labels: &Labels, styles: &[ObjectStyle]) -> ([u32; 3], Vec<[f32; 4]>) {
    let mut drawn = vec![false; u16::MAX as usize + 1];
    for s in styles.iter().filter(|s| s.enabled) {
        drawn[s.id as usize] = true;
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
            if ids.iter().any(|&id| drawn[id as usize]) {
                [0.0, 1.0, single, 0.0]
            } else {
                [1.0, 0.0, single, 0.0]
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
