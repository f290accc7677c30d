//! Levels of detail (issue 30): a volume or label map at half the resolution, placed where the
//! original lies. Level k + 1 voxel `i` covers the level-k voxels `2i` and `2i + 1` along every
//! halved axis, so its centre lies at level-k coordinate `2i + 0.5`: the voxel → world transform
//! doubles the spacing and moves the origin half a voxel along the grid's own axes. Axes of
//! fewer than 4 voxels are kept (every level has at least 2 voxels per axis).

use crate::geometry::Geometry;
use crate::segmentation::LabelData;
use crate::voxels::Voxels;
use crate::{DataError, VolumeData};

/// Which axes of a grid of `dims` a coarser level halves.
pub fn halved(dims: [u32; 3]) -> [bool; 3] {
    dims.map(|d| d >= 4)
}

/// Whether a grid of `dims` has a coarser level.
pub fn has_coarser(dims: [u32; 3]) -> bool {
    halved(dims).iter().any(|&h| h)
}

/// The dims of the coarser level of a grid of `dims`.
pub fn coarser_dims(dims: [u32; 3]) -> [u32; 3] {
    halve_dims(dims, halved(dims))
}

fn halve_dims(dims: [u32; 3], h: [bool; 3]) -> [u32; 3] {
    [0, 1, 2].map(|a| if h[a] { dims[a].div_ceil(2) } else { dims[a] })
}

/// The transform of the coarser level of a grid of `dims` on `geometry`.
pub fn coarser_geometry(dims: [u32; 3], geometry: &Geometry) -> Geometry {
    let h = halved(dims);
    let factor = glam::DVec3::from_array(h.map(|x| if x { 2.0 } else { 1.0 }));
    let shift = glam::DVec3::from_array(h.map(|x| if x { 0.5 } else { 0.0 }));
    let mut g = *geometry;
    g.origin = geometry.origin + geometry.direction * (geometry.spacing * shift);
    g.spacing = geometry.spacing * factor;
    g
}

/// Errors for a grid of `dims` without a coarser level (`what`: "volume", "label map").
fn no_coarser_is_an_error(dims: [u32; 3], what: &str) -> Result<(), DataError> {
    if has_coarser(dims) {
        Ok(())
    } else {
        Err(DataError::Invalid(format!(
            "a {dims:?} {what} has no coarser level"
        )))
    }
}

/// The coarser level of `v` holding `voxels`, with `v`'s stored type and placement.
fn coarser_of(v: &VolumeData, voxels: Voxels) -> Result<VolumeData, DataError> {
    let mut coarse = VolumeData::from_voxels(
        coarser_dims(v.dims),
        coarser_geometry(v.dims, &v.geometry),
        voxels,
    )?;
    coarse.stored_type = v.stored_type;
    coarse.placement.clone_from(&v.placement);
    Ok(coarse)
}

/// The level-k voxel indices (per axis, up to 2) a coarse voxel `i` covers.
fn children(i: u32, halve: bool, n: u32) -> std::ops::Range<u32> {
    if halve {
        2 * i..(2 * i + 2).min(n)
    } else {
        i..i + 1
    }
}

/// Calls `f(coarse index, fine indices)` for every coarse voxel of a grid of `dims`.
fn for_each_block(dims: [u32; 3], f: impl FnMut(usize, &[usize])) {
    for_each_block_halving(dims, halved(dims), f)
}

/// [`for_each_block`] halving the axes `h` (a box of a grid halves the grid's axes).
fn for_each_block_halving(dims: [u32; 3], h: [bool; 3], mut f: impl FnMut(usize, &[usize])) {
    let c = halve_dims(dims, h);
    let [nx, ny, nz] = dims;
    let mut fine = Vec::with_capacity(8);
    let mut at = 0;
    for z in 0..c[2] {
        for y in 0..c[1] {
            for x in 0..c[0] {
                fine.clear();
                for fz in children(z, h[2], nz) {
                    for fy in children(y, h[1], ny) {
                        for fx in children(x, h[0], nx) {
                            fine.push((fx + nx * (fy + ny * fz)) as usize);
                        }
                    }
                }
                f(at, &fine);
                at += 1;
            }
        }
    }
}

/// The volume at half the resolution: each voxel the mean of the finite values it covers
/// (rounded for integer types, which are kept), "no data" where it covers none. Errors: a grid
/// with no coarser level ([`has_coarser`]).
pub fn coarser_volume(v: &VolumeData) -> Result<VolumeData, DataError> {
    no_coarser_is_an_error(v.dims, "volume")?;
    let voxels = mean_blocks(&v.voxels, v.dims, halved(v.dims));
    coarser_of(v, voxels)
}

/// The coarser level of a box of `dims` voxels of a grid whose coarser level halves axes `h`
/// ([`halved`] of the grid's dims), the box starting at an even voxel along them: the same
/// voxels as the matching box of the grid's coarser level — by mean ([`coarser_volume`]) or,
/// for label ids, by majority ([`coarser_label_volume`]). Returns the voxels, x fastest.
pub fn coarser_box(voxels: &Voxels, dims: [u32; 3], h: [bool; 3], labels: bool) -> Voxels {
    if labels {
        majority_blocks(voxels, dims, h)
    } else {
        mean_blocks(voxels, dims, h)
    }
}

fn mean_blocks(voxels: &Voxels, dims: [u32; 3], h: [bool; 3]) -> Voxels {
    let count = halve_dims(dims, h).iter().map(|&d| d as usize).product();
    // Mean of the finite values of a block, as f64.
    fn mean<T: Copy>(values: &[T], block: &[usize], f: impl Fn(T) -> f64) -> Option<f64> {
        let (mut sum, mut n) = (0.0, 0);
        for &i in block {
            let x = f(values[i]);
            if x.is_finite() {
                sum += x;
                n += 1;
            }
        }
        (n > 0).then(|| sum / n as f64)
    }
    macro_rules! integer {
        ($values:expr, $variant:ident, $t:ty) => {{
            let mut out = vec![0 as $t; count];
            for_each_block_halving(dims, h, |at, block| {
                out[at] = mean($values, block, |x| x as f64).unwrap_or(0.0).round() as $t;
            });
            Voxels::$variant(out)
        }};
    }
    match voxels {
        Voxels::U8(x) => integer!(x, U8, u8),
        Voxels::I8(x) => integer!(x, I8, i8),
        Voxels::U16(x) => integer!(x, U16, u16),
        Voxels::I16(x) => integer!(x, I16, i16),
        Voxels::F32(x) => {
            let mut out = vec![0.0f32; count];
            for_each_block_halving(dims, h, |at, block| {
                out[at] = mean(x, block, |x| x as f64).map_or(f32::NAN, |m| m as f32);
            });
            Voxels::F32(out)
        }
    }
}

/// A volume of labels (ids stored as voxel values, e.g. a style TF's per-label rows) at half the
/// resolution: each voxel the value most of its block holds (ties: the smaller), never a mean,
/// which would invent ids between two objects. Errors: a grid with no coarser level.
pub fn coarser_label_volume(v: &VolumeData) -> Result<VolumeData, DataError> {
    no_coarser_is_an_error(v.dims, "volume")?;
    let voxels = majority_blocks(&v.voxels, v.dims, halved(v.dims));
    coarser_of(v, voxels)
}

fn majority_blocks(voxels: &Voxels, dims: [u32; 3], h: [bool; 3]) -> Voxels {
    let count = halve_dims(dims, h).iter().map(|&d| d as usize).product();
    fn majority<T: Copy + PartialEq + PartialOrd>(values: &[T], block: &[usize]) -> T {
        let mut best = (0, values[block[0]]);
        for &i in block {
            let x = values[i];
            let n = block.iter().filter(|&&j| values[j] == x).count();
            if n > best.0 || (n == best.0 && x < best.1) {
                best = (n, x);
            }
        }
        best.1
    }
    macro_rules! by_majority {
        ($values:expr, $variant:ident) => {{
            let mut out = Vec::with_capacity(count);
            for_each_block_halving(dims, h, |_, block| out.push(majority($values, block)));
            Voxels::$variant(out)
        }};
    }
    match voxels {
        Voxels::U8(x) => by_majority!(x, U8),
        Voxels::I8(x) => by_majority!(x, I8),
        Voxels::U16(x) => by_majority!(x, U16),
        Voxels::I16(x) => by_majority!(x, I16),
        Voxels::F32(x) => by_majority!(x, F32),
    }
}

/// The label map at half the resolution: each voxel the id most of its block holds (ties: the
/// smaller id, so background loses to no object only by count). Object names are kept.
/// Errors: a grid with no coarser level.
pub fn coarser_labels(l: &LabelData) -> Result<LabelData, DataError> {
    no_coarser_is_an_error(l.dims, "label map")?;
    let count = coarser_dims(l.dims).iter().map(|&d| d as usize).product();
    let mut ids = vec![0u16; count];
    for_each_block(l.dims, |at, block| {
        let mut best = (0usize, u16::MAX);
        for &i in block {
            let id = l.ids[i];
            let n = block.iter().filter(|&&j| l.ids[j] == id).count();
            if n > best.0 || (n == best.0 && id < best.1) {
                best = (n, id);
            }
        }
        ids[at] = best.1;
    });
    Ok(LabelData {
        dims: coarser_dims(l.dims),
        geometry: coarser_geometry(l.dims, &l.geometry),
        ids,
        objects: l.objects.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn a_coarser_level_averages_blocks_and_lies_where_they_lie() {
        // 5 × 4 × 2 voxels of value x + 10 y, spacing (1, 2, 3), origin (10, 20, 30).
        let values: Vec<f32> = (0..40)
            .map(|i| ((i % 5) + 10 * ((i / 5) % 4)) as f32)
            .collect();
        let v = VolumeData::new([5, 4, 2], [1.0, 2.0, 3.0], [10.0, 20.0, 30.0], values).unwrap();
        let c = coarser_volume(&v).unwrap();
        assert_eq!(c.dims, [3, 2, 2], "z (2 voxels) is kept");
        // Coarse (0, 0, z) covers x 0..1, y 0..1: mean 5.5; (2, 1, z) covers x 4, y 2..3: 29.
        assert_eq!(c.value(0, 0, 0), 5.5);
        assert_eq!(c.value(2, 1, 1), 29.0);
        // Its centre lies at the centre of the fine voxels it covers.
        let centre = v.voxel_to_world(Vec3::new(0.5, 0.5, 1.0));
        assert!(
            c.voxel_to_world(Vec3::new(0.0, 0.0, 1.0))
                .abs_diff_eq(centre, 1e-5)
        );
        assert_eq!(c.spacing(), [2.0, 4.0, 3.0]);
    }

    #[test]
    fn integer_types_are_kept_and_no_data_stays_where_nothing_is_known() {
        let v = VolumeData::from_voxels(
            [4, 2, 2],
            Geometry::axis_aligned([1.0; 3], [0.0; 3]),
            Voxels::U8(vec![
                1, 2, 200, 201, 1, 2, 200, 201, 1, 2, 200, 201, 1, 2, 200, 201,
            ]),
        )
        .unwrap();
        let c = coarser_volume(&v).unwrap();
        // x is halved (y and z have 2 voxels): each row 1, 2, 200, 201 becomes 2, 201.
        assert_eq!(
            c.voxels,
            Voxels::U8([2, 201].repeat(4)),
            "means 1.5 and 200.5 round up"
        );
        let mut values = vec![f32::NAN; 64];
        values[0] = 4.0;
        let f = VolumeData::new([4, 4, 4], [1.0; 3], [0.0; 3], values).unwrap();
        let c = coarser_volume(&f).unwrap();
        assert_eq!(c.value(0, 0, 0), 4.0, "the mean of the finite values");
        assert!(c.value(1, 1, 1).is_nan(), "no finite value: no data");
    }

    #[test]
    fn coarser_labels_keep_the_majority_and_the_names() {
        let mut l = LabelData::new(
            [4, 2, 2],
            Geometry::axis_aligned([1.0; 3], [0.0; 3]),
            vec![3, 3, 0, 5, 3, 0, 0, 5, 3, 3, 0, 5, 3, 0, 5, 5],
        );
        l.objects.insert(3, "liver".into());
        let c = coarser_labels(&l).unwrap();
        assert_eq!(c.dims, [2, 2, 2]);
        // Block (0, 0, 0) holds x 0..1 of y 0 and z 0: ids 3, 3 → 3.
        assert_eq!(c.id(0, 0, 0), 3);
        // Block (1, 0, 0): ids 0, 5 → a tie, the smaller id.
        assert_eq!(c.id(1, 0, 0), 0);
        assert_eq!(c.objects[&3], "liver");
        assert!(!has_coarser([3, 2, 2]));
        // The same ids as a volume (a style TF's label input): the majority, not the mean.
        let ids: Vec<f32> = l.ids.iter().map(|&i| i as f32).collect();
        let v = VolumeData::with_geometry(l.dims, l.geometry, ids).unwrap();
        let c = coarser_label_volume(&v).unwrap();
        assert_eq!(c.value(0, 0, 0), 3.0);
        assert_eq!(
            c.value(1, 0, 0),
            0.0,
            "a tie of 0 and 5: the smaller, never 2.5"
        );
        assert!(coarser_labels(&LabelData::new([2, 2, 2], l.geometry, vec![0; 8])).is_err());
    }
}
