//! Empty-space skipping for ray casting: the value range of every brick of voxels, and which
//! data values a transfer function makes visible. A ray sample in a brick whose value range holds
//! no visible value contributes nothing, so the ray caster jumps over the whole brick — the
//! picture stays exactly the same (the samples it skips would all have been transparent).

use crate::transfer_function::LUT_SIZE;
use crate::volume::VolumeData;
use rayon::prelude::*;

/// Voxels per brick side.
pub const BRICK: u32 = 8;
/// Bins of the visibility table over the volume's value range.
pub const VISIBILITY_BINS: usize = 1024;
/// Entries of the visibility table: the bins' prefix counts, then whether the volume's lowest
/// value itself is visible (see [`visibility_prefix`]).
pub const VISIBILITY_ENTRIES: usize = VISIBILITY_BINS + 1;

/// `[min, max]` of the values a sample can take inside each brick.
#[derive(Clone, Debug, PartialEq)]
pub struct BrickRanges {
    /// Bricks along x, y, z: `ceil(dims / BRICK)`.
    pub dims: [u32; 3],
    /// Index = `x + dims[0] * (y + dims[1] * z)`.
    pub ranges: Vec<[f32; 2]>,
}

/// Brick grid dims of `volume`: `ceil(dims / BRICK)` per axis.
pub fn brick_dims(volume: &VolumeData) -> [u32; 3] {
    volume.dims.map(|n| n.div_ceil(BRICK))
}

/// The value ranges of the bricks of `volume`. A sample at voxel-space position `q` (clamped to
/// the grid) lies in brick `floor(q / BRICK)` and interpolates voxels `floor(q)` and
/// `floor(q) + 1` along each axis, so a brick's range covers its voxels plus one more layer on
/// its upper sides. `pad` (data units) widens every range, for a GPU that stores the volume in a
/// lower precision than the data — except above a brick holding only the volume's lowest value
/// (`value_range[0]`: air, padding, the background of a label map), whose range is
/// `[lo − pad, lo]`: that value is texel 0 in the normalised texture formats and an exact code
/// in the integer ones, so its samples are `lo` to within float rounding, and a transfer
/// function that starts transparent at `lo` and ramps up right after it still skips it.
/// Non-finite values ("no data") are left out; a brick of only no data gets the empty range
/// `[f32::MAX, f32::MIN]` (min > max).
pub fn brick_ranges(volume: &VolumeData, pad: f32) -> BrickRanges {
    let dims = brick_dims(volume);
    let ranges = brick_range_layers(volume, pad, 0..dims[2], 0);
    BrickRanges { dims, ranges }
}

/// [`brick_ranges`] for a filter that reaches `reach` voxels further than the trilinear one on
/// every side: a tricubic B-spline sample at `q` (reach 1) mixes voxels `floor(q) − 1 ..=
/// floor(q) + 2` with non-negative weights that sum to 1, so it stays inside their range.
pub fn brick_ranges_reaching(volume: &VolumeData, pad: f32, reach: u32) -> BrickRanges {
    let dims = brick_dims(volume);
    let ranges = brick_range_layers(volume, pad, 0..dims[2], reach);
    BrickRanges { dims, ranges }
}

/// [`brick_ranges_reaching`] of the brick layers `layers` (brick z indices) only, x fastest — so
/// a big volume's table can be built and uploaded a slab at a time.
pub fn brick_range_layers(
    volume: &VolumeData,
    pad: f32,
    layers: std::ops::Range<u32>,
    reach: u32,
) -> Vec<[f32; 2]> {
    let [nx, ny, nz] = volume.dims;
    let minimum = volume.value_range[0];
    let dims = brick_dims(volume);
    let per_layer = dims[0] as usize * dims[1] as usize;
    let count = per_layer * layers.len();
    // An indexed iterator collects straight into one vector of the exact size.
    (0..count)
        .into_par_iter()
        .map(|k| {
            let b = [
                (k % dims[0] as usize) as u32,
                (k / dims[0] as usize % dims[1] as usize) as u32,
                layers.start + (k / per_layer) as u32,
            ];
            let span = |axis: usize, n: u32| {
                let first = b[axis] * BRICK;
                first.saturating_sub(reach)..=((first + BRICK + reach).min(n - 1))
            };
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            for z in span(2, nz) {
                for y in span(1, ny) {
                    for x in span(0, nx) {
                        let v = volume.value(x, y, z);
                        if v.is_finite() {
                            lo = lo.min(v);
                            hi = hi.max(v);
                        }
                    }
                }
            }
            if lo > hi {
                // Only "no data": every sample in the brick is transparent.
                return [f32::MAX, f32::MIN];
            }
            if hi == minimum {
                return [lo - pad, hi];
            }
            [lo - pad, hi + pad]
        })
        .collect()
}

/// One table of a transfer function: its domain and the classified opacity of each of its
/// [`LUT_SIZE`] entries (a value between two entries is interpolated between them).
pub struct OpacityRow<'a> {
    pub domain: [f32; 2],
    pub opacity: &'a [f32],
}

/// Which values of `value_range` any of `rows` makes visible, as cumulative counts over
/// [`VISIBILITY_BINS`] equal bins: values in bins `a..=b` are all invisible when
/// `prefix[b] - prefix[a - 1]` is 0 (with `prefix[-1] = 0`). Conservative: a bin counts as
/// visible when any table entry its values interpolate between has opacity above 0. Values
/// outside a row's domain clamp to its end entry alone (so a transparent first entry hides
/// everything below the domain, as the ray caster's lookup does). One more entry follows the
/// bins ([`VISIBILITY_ENTRIES`] in all): 1 when the lowest value `value_range[0]` itself is
/// visible, else 0 — exact where the first bin is not, for the bricks of [`brick_ranges`] that
/// hold only that value.
pub fn visibility_prefix(value_range: [f32; 2], rows: &[OpacityRow]) -> Vec<f32> {
    let [lo, hi] = value_range;
    let width = (hi - lo) / VISIBILITY_BINS as f32;
    // A constant volume (no value range) counts as visible everywhere.
    let degenerate = width.is_nan() || width <= 0.0;
    // Whether any row shows a value in [a, b].
    let visible = |a: f32, b: f32| {
        degenerate
            || rows.iter().any(|row| {
                let span = row.domain[1] - row.domain[0];
                let entry = |v: f32| {
                    let u = if span > 0.0 {
                        ((v - row.domain[0]) / span).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    u * (LUT_SIZE - 1) as f32
                };
                // A value at table position x mixes entries floor(x) and floor(x) + 1 with
                // weight fract(x): positions in [x_a, x_b] reach entries floor(x_a) ..= ceil(x_b).
                let last_entry = row.opacity.len().saturating_sub(1);
                let first = (entry(a).floor() as usize).min(last_entry);
                let last = (entry(b).ceil() as usize).min(last_entry);
                row.opacity[first..=last].iter().any(|&o| o > 0.0)
            })
    };
    let mut prefix = Vec::with_capacity(VISIBILITY_ENTRIES);
    let mut count = 0.0f32;
    for bin in 0..VISIBILITY_BINS {
        let (a, b) = (lo + bin as f32 * width, lo + (bin + 1) as f32 * width);
        if visible(a, b) {
            count += 1.0;
        }
        prefix.push(count);
    }
    prefix.push(if visible(lo, lo) { 1.0 } else { 0.0 });
    prefix
}

#[cfg(test)]
mod tests {
    use super::*;

    fn volume() -> VolumeData {
        let dims = [19, 17, 13];
        let mut seed = 12345u32;
        let values = (0..dims.iter().product::<u32>())
            .map(|_| {
                seed = seed.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                (seed >> 16) as f32 / 65_536.0 * 100.0
            })
            .collect();
        VolumeData::new(dims, [1.0; 3], [0.0; 3], values).unwrap()
    }

    #[test]
    fn every_trilinear_sample_lies_in_its_bricks_range() {
        let v = volume();
        let bricks = brick_ranges(&v, 0.0);
        assert_eq!(bricks.dims, [3, 3, 2]);
        let mut seed = 7u32;
        let mut random = |n: u32| {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / 16_777_216.0 * (n - 1) as f32
        };
        for _ in 0..20_000 {
            let q = [random(v.dims[0]), random(v.dims[1]), random(v.dims[2])];
            let sample = v.sample_trilinear(glam::Vec3::from_array(q));
            let b = q.map(|c| (c / BRICK as f32).floor() as u32);
            let i = (b[0] + bricks.dims[0] * (b[1] + bricks.dims[1] * b[2])) as usize;
            let [lo, hi] = bricks.ranges[i];
            assert!(
                lo - 1e-4 <= sample && sample <= hi + 1e-4,
                "sample {sample} at {q:?} outside brick {b:?} range [{lo}, {hi}]"
            );
        }
    }

    #[test]
    fn visibility_marks_the_bins_a_transfer_function_shows() {
        // Opaque only over entries 128..=255 of a domain equal to the value range.
        let opacity: Vec<f32> = (0..LUT_SIZE)
            .map(|k| if k >= 128 { 1.0 } else { 0.0 })
            .collect();
        let rows = [OpacityRow {
            domain: [0.0, 100.0],
            opacity: &opacity,
        }];
        let prefix = visibility_prefix([0.0, 100.0], &rows);
        assert_eq!(prefix.len(), VISIBILITY_ENTRIES);
        // The lowest value is entry 0 exactly: transparent.
        assert_eq!(prefix[VISIBILITY_BINS], 0.0);
        let visible = |bin: usize| prefix[bin] - if bin > 0 { prefix[bin - 1] } else { 0.0 };
        // Values below entry 127 interpolate between invisible entries only.
        assert_eq!(visible(0), 0.0);
        assert_eq!(visible(VISIBILITY_BINS * 127 / 255 - 1), 0.0);
        // Past entry 127, interpolation reaches entry 128.
        assert_eq!(visible(VISIBILITY_BINS * 127 / 255 + 1), 1.0);
        assert_eq!(visible(VISIBILITY_BINS - 1), 1.0);
        // Below its domain a row is its first entry alone: transparent here.
        let prefix = visibility_prefix([-50.0, 100.0], &rows);
        assert_eq!(prefix[VISIBILITY_BINS / 3 - 1], 0.0);
        // A second row that shows low values makes those visible too.
        let low: Vec<f32> = (0..LUT_SIZE)
            .map(|k| if k < 10 { 0.5 } else { 0.0 })
            .collect();
        let both = [
            OpacityRow {
                domain: [0.0, 100.0],
                opacity: &opacity,
            },
            OpacityRow {
                domain: [0.0, 100.0],
                opacity: &low,
            },
        ];
        let prefix = visibility_prefix([0.0, 100.0], &both);
        assert_eq!(prefix[0], 1.0);
        assert_eq!(prefix[VISIBILITY_BINS], 1.0);
    }

    #[test]
    fn a_transfer_function_ramping_up_from_the_lowest_value_hides_only_that_value() {
        // Transparent at the lowest value, visible from the next entry on: the first bin is
        // visible, the lowest value itself is not.
        let opacity: Vec<f32> = (0..LUT_SIZE).map(|k| k as f32 / 255.0).collect();
        let rows = [OpacityRow {
            domain: [0.0, 29.0],
            opacity: &opacity,
        }];
        let prefix = visibility_prefix([0.0, 29.0], &rows);
        assert_eq!(prefix[0], 1.0);
        assert_eq!(prefix[VISIBILITY_BINS], 0.0);
        // Bricks of only the lowest value get no pad above it, others do.
        // (Voxel x = 8 lies in bricks 0 and 1: a brick reaches one voxel past its own.)
        let mut values = vec![0.0f32; 24 * 8 * 8];
        values[8] = 3.0;
        let v = VolumeData::new([24, 8, 8], [1.0; 3], [0.0; 3], values).unwrap();
        assert_eq!(
            brick_ranges(&v, 0.5).ranges,
            vec![[-0.5, 3.5], [-0.5, 3.5], [-0.5, 0.0]]
        );
    }
}
