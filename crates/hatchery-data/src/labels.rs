//! Label volumes (hard segmentations): per-label masks, smoothed for iso-surfacing, and label
//! statistics.

use std::collections::{BTreeMap, HashMap};

use rayon::prelude::*;

use crate::voxels::Voxel;
use crate::{DataError, VolumeData};

/// Ranges in label lists longer than this are refused, so a typo cannot allocate gigabytes.
const MAX_RANGE_LEN: i64 = 1 << 16;

/// Elements per inner block of the y and z passes: small enough to stay in L1 while the
/// kernel taps are summed into it.
const BLOCK: usize = 2048;

/// A volume on the same grid with 1.0 where the voxel value, rounded to the nearest integer, is
/// one of `labels` and 0.0 elsewhere.
///
/// With `smooth_sigma > 0` the mask is then blurred with a Gaussian of that standard deviation
/// in voxels (radius `ceil(3 sigma)`, edges clamped), so that marching cubes at iso 0.5 gives a
/// smooth surface instead of voxel stairs. Values stay in [0, 1].
///
/// Labels that do not occur give an all-zero mask, not an error; see [`label_counts`].
pub fn label_mask(
    volume: &VolumeData,
    labels: &[i64],
    smooth_sigma: f32,
) -> Result<VolumeData, DataError> {
    if labels.is_empty() {
        return Err(DataError::Invalid("no labels given for the mask".into()));
    }
    if !smooth_sigma.is_finite() {
        return Err(DataError::Invalid(format!(
            "smoothing sigma must be finite, got {smooth_sigma}"
        )));
    }
    let wanted = Membership::new(labels, volume.value_range);
    let [nx, ny, _] = volume.dims.map(|d| d as usize);
    let slice = nx * ny;
    let mut mask = vec![0.0f32; volume.voxel_count()];
    // Per z slice, in parallel: the mask and the bounding box of its hits.
    let bounds = crate::with_voxels!(&volume.voxels, values => mask
        .par_chunks_mut(slice)
        .zip(values.par_chunks(slice))
        .enumerate()
        .map(|(z, (out, input))| {
            let mut b: Option<Bounds> = None;
            for (y, (out, input)) in out.chunks_mut(nx).zip(input.chunks(nx)).enumerate() {
                let mut xs: Option<(usize, usize)> = None;
                for (x, (o, &v)) in out.iter_mut().zip(input).enumerate() {
                    if wanted.contains(round_label(v.to_f32())) {
                        *o = 1.0;
                        xs = Some(xs.map_or((x, x), |(first, _)| (first, x)));
                    }
                }
                if let Some((x0, x1)) = xs {
                    let row = Bounds {
                        min: [x0, y, z],
                        max: [x1, y, z],
                    };
                    b = Some(row.union(b));
                }
            }
            b
        })
        .reduce(|| None, |a, b| a.map_or(b, |a| Some(a.union(b)))));
    if let Some(bounds) = bounds
        && smooth_sigma > 0.0
    {
        mask = blur_within(mask, volume.dims, bounds, smooth_sigma);
    }
    volume.with_values(mask)
}

/// The nearest integer, ties away from zero: `v.round() as i64` without the libm call that
/// `round` is on baseline x86-64, which dominated the mask time.
#[inline]
fn round_label(v: f32) -> i64 {
    let i = v as i64;
    // Exact: below 2^23 the difference of two nearby floats is representable; above it every
    // float is an integer (or out of i64 range and saturated), and this is 0 or ignored.
    let f = v - i as f32;
    if v.abs() >= 8_388_608.0 {
        i
    } else if f >= 0.5 {
        i + 1
    } else if f <= -0.5 {
        i - 1
    } else {
        i
    }
}

/// Which labels a mask selects: a lookup table over the volume's label range when that is
/// small (the usual 8- or 16-bit labels), else a sorted list.
enum Membership {
    Table { first: i64, selected: Vec<bool> },
    Sorted(Vec<i64>),
}

impl Membership {
    fn new(labels: &[i64], value_range: [f32; 2]) -> Self {
        let [first, last] = value_range.map(round_label);
        if last.saturating_sub(first) < 1 << 16 {
            let mut selected = vec![false; (last - first + 1) as usize];
            for &l in labels {
                if let Some(s) = l
                    .checked_sub(first)
                    .and_then(|i| usize::try_from(i).ok())
                    .and_then(|i| selected.get_mut(i))
                {
                    *s = true;
                }
            }
            Membership::Table { first, selected }
        } else {
            let mut sorted = labels.to_vec();
            sorted.sort_unstable();
            sorted.dedup();
            Membership::Sorted(sorted)
        }
    }

    #[inline]
    fn contains(&self, label: i64) -> bool {
        match self {
            // Labels come from the same value range, so the index is in the table.
            Membership::Table { first, selected } => selected
                .get(label.wrapping_sub(*first) as usize)
                .copied()
                .unwrap_or(false),
            Membership::Sorted(sorted) => sorted.binary_search(&label).is_ok(),
        }
    }
}

/// Inclusive voxel bounding box.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    min: [usize; 3],
    max: [usize; 3],
}

impl Bounds {
    fn union(self, other: Option<Bounds>) -> Self {
        match other {
            None => self,
            Some(o) => Self {
                min: std::array::from_fn(|a| self.min[a].min(o.min[a])),
                max: std::array::from_fn(|a| self.max[a].max(o.max[a])),
            },
        }
    }
}

/// Blurs a 0/1 mask that is zero outside `bounds`. Only the box grown by the kernel radius can
/// become non-zero, and blurring that box alone gives the same values as blurring the whole
/// grid (its faces are either grid borders, clamped alike, or lie in the zero region), so a
/// small object in a large volume costs little.
fn blur_within(mut mask: Vec<f32>, dims: [u32; 3], bounds: Bounds, sigma: f32) -> Vec<f32> {
    let radius = gaussian_kernel(sigma).len() / 2;
    let n = dims.map(|d| d as usize);
    let lo: [usize; 3] = std::array::from_fn(|a| bounds.min[a].saturating_sub(radius));
    let hi: [usize; 3] = std::array::from_fn(|a| (bounds.max[a] + radius).min(n[a] - 1));
    let sub = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
    let (slice, sub_slice) = (n[0] * n[1], sub[0] * sub[1]);
    // Cropping copies twice; for a box covering most of the grid that costs more than it saves.
    if sub_slice * sub[2] * 2 > mask.len() {
        return gaussian_blur(mask, dims, sigma);
    }

    let mut crop = vec![0.0f32; sub_slice * sub[2]];
    crop.par_chunks_mut(sub_slice)
        .enumerate()
        .for_each(|(z, out)| {
            for (y, row) in out.chunks_mut(sub[0]).enumerate() {
                let start = (lo[2] + z) * slice + (lo[1] + y) * n[0] + lo[0];
                row.copy_from_slice(&mask[start..start + sub[0]]);
            }
        });
    let crop = gaussian_blur(crop, sub.map(|d| d as u32), sigma);
    mask[lo[2] * slice..(hi[2] + 1) * slice]
        .par_chunks_mut(slice)
        .zip(crop.par_chunks(sub_slice))
        .for_each(|(out, blurred)| {
            for (y, row) in blurred.chunks(sub[0]).enumerate() {
                let start = (lo[1] + y) * n[0] + lo[0];
                out[start..start + sub[0]].copy_from_slice(row);
            }
        });
    mask
}

/// How many voxels have each label (voxel value rounded to the nearest integer).
pub fn label_counts(volume: &VolumeData) -> BTreeMap<i64, u64> {
    let [lo, hi] = volume.value_range.map(round_label);
    let span = hi.saturating_sub(lo);
    const CHUNK: usize = 1 << 16;
    if (0..1 << 16).contains(&span) {
        // The usual case (8- or 16-bit labels): dense per-thread histograms.
        let bins = span as usize + 1;
        let counts = crate::with_voxels!(&volume.voxels, values => values
        .par_chunks(CHUNK)
        .fold(
            || vec![0u64; bins],
            |mut counts, chunk| {
                for &v in chunk {
                    let v = v.to_f32();
                    // No data counts as no label.
                    if v.is_finite() {
                        counts[(round_label(v) - lo) as usize] += 1;
                    }
                }
                counts
            },
        )
        .reduce(
            || vec![0u64; bins],
            |mut a, b| {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
                a
            },
        ));
        counts
            .into_iter()
            .enumerate()
            .filter(|&(_, n)| n > 0)
            .map(|(i, n)| (lo + i as i64, n))
            .collect()
    } else {
        let counts = crate::with_voxels!(&volume.voxels, values => values
        .par_chunks(CHUNK)
        .fold(HashMap::new, |mut counts, chunk| {
            for &v in chunk {
                let v = v.to_f32();
                if v.is_finite() {
                    *counts.entry(round_label(v)).or_insert(0u64) += 1;
                }
            }
            counts
        })
        .reduce(HashMap::new, |mut a, b| {
            for (k, n) in b {
                *a.entry(k).or_insert(0) += n;
            }
            a
        }));
        counts.into_iter().collect()
    }
}

/// Parses a label list such as `3`, `3,4, 7`, `1-5` or `2-4,9` (ranges inclusive, negative
/// labels allowed: `-2--1`). Returns the labels sorted and without duplicates.
pub fn parse_label_list(text: &str) -> Result<Vec<i64>, DataError> {
    if text.trim().is_empty() {
        return Err("no labels given".into());
    }
    let mut labels = Vec::new();
    for token in text.split(',').map(str::trim) {
        if token.is_empty() {
            return Err(format!("`{text}`: empty entry in the label list").into());
        }
        if let Ok(label) = token.parse::<i64>() {
            labels.push(label);
            continue;
        }
        // A range: the separator is the first `-` that is not a leading minus sign.
        let split = token
            .char_indices()
            .skip(1)
            .find(|&(_, c)| c == '-')
            .map(|(i, _)| i);
        let Some((a, b)) = split.map(|i| (token[..i].trim(), token[i + 1..].trim())) else {
            return Err(format!("`{token}`: not a label number").into());
        };
        let parse = |s: &str| {
            s.parse::<i64>()
                .map_err(|_| format!("`{token}`: `{s}` is not a label number"))
        };
        let (a, b) = (parse(a)?, parse(b)?);
        if a > b {
            return Err(format!("`{token}`: range start is after its end").into());
        }
        if b.saturating_sub(a) >= MAX_RANGE_LEN {
            return Err(format!("`{token}`: range is longer than {MAX_RANGE_LEN} labels").into());
        }
        labels.extend(a..=b);
    }
    labels.sort_unstable();
    labels.dedup();
    Ok(labels)
}

/// Normalised Gaussian weights for offsets `-r..=r`, `r = ceil(3 sigma)`.
fn gaussian_kernel(sigma: f32) -> Vec<f32> {
    let radius = (3.0 * sigma).ceil() as i64;
    let weights: Vec<f64> = (-radius..=radius)
        .map(|k| (-(k * k) as f64 / (2.0 * sigma as f64 * sigma as f64)).exp())
        .collect();
    let sum: f64 = weights.iter().sum();
    weights.iter().map(|w| (w / sum) as f32).collect()
}

/// Separable Gaussian blur with clamped edges: one 1-D pass per axis. Inner loops run over
/// contiguous memory so they vectorise.
fn gaussian_blur(values: Vec<f32>, dims: [u32; 3], sigma: f32) -> Vec<f32> {
    let kernel = gaussian_kernel(sigma);
    let radius = kernel.len() / 2;
    let [nx, ny, nz] = dims.map(|d| d as usize);
    let a = values;
    let mut b = vec![0.0f32; a.len()];

    // x: rows are contiguous; each is copied into an edge-padded buffer first.
    b.par_chunks_mut(nx)
        .zip(a.par_chunks(nx))
        .for_each_init(Vec::new, |padded, (out, row)| {
            padded.clear();
            padded.extend(std::iter::repeat_n(row[0], radius));
            padded.extend_from_slice(row);
            padded.extend(std::iter::repeat_n(row[nx - 1], radius));
            out.fill(0.0);
            for (k, &w) in kernel.iter().enumerate() {
                for (o, &p) in out.iter_mut().zip(&padded[k..k + nx]) {
                    *o += w * p;
                }
            }
        });

    // The input is not reused as the next output: a mask written only where it is 1 has
    // pages mapped to the shared zero page, and writing them would copy-on-write fault at
    // twice the cost of touching a fresh buffer.
    let len = a.len();
    drop(a);
    let mut c = vec![0.0f32; len];

    // y: within each z slice, an output row is a weighted sum of whole input rows.
    let slice = nx * ny;
    c.par_chunks_mut(slice)
        .zip(b.par_chunks(slice))
        .for_each(|(out, input)| {
            for y in 0..ny {
                let out_row = &mut out[y * nx..(y + 1) * nx];
                sum_taps(out_row, &kernel, |k| {
                    let src = (y + k).saturating_sub(radius).min(ny - 1);
                    &input[src * nx..(src + 1) * nx]
                });
            }
        });

    // z: an output slice is a weighted sum of whole input slices.
    b.par_chunks_mut(slice).enumerate().for_each(|(z, out)| {
        sum_taps(out, &kernel, |k| {
            let src = (z + k).saturating_sub(radius).min(nz - 1);
            &c[src * slice..(src + 1) * slice]
        });
        // Rounding can overshoot 1 by an ulp; keep the documented range exact.
        out.iter_mut().for_each(|v| *v = v.clamp(0.0, 1.0));
    });
    b
}

/// `out = sum_k kernel[k] * source(k)`, blocked so the partial sums stay in cache.
fn sum_taps<'s>(out: &mut [f32], kernel: &[f32], source: impl Fn(usize) -> &'s [f32]) {
    for start in (0..out.len()).step_by(BLOCK) {
        let end = (start + BLOCK).min(out.len());
        let out = &mut out[start..end];
        out.fill(0.0);
        for (k, &w) in kernel.iter().enumerate() {
            for (o, &s) in out.iter_mut().zip(&source(k)[start..end]) {
                *o += w * s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 20^3 voxels: label 1 in a ball of radius 6 at the centre, 2 in a box, 0 elsewhere,
    /// stored with a little noise so rounding matters.
    fn labelled() -> VolumeData {
        let n = 20u32;
        let mut values = Vec::new();
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    let d2 = [x, y, z]
                        .map(|c| (c as f32 - 10.0).powi(2))
                        .iter()
                        .sum::<f32>();
                    let label = if d2 <= 36.0 {
                        1.0
                    } else if x < 4 && y < 4 {
                        2.0
                    } else {
                        0.0
                    };
                    values.push(label + 0.3 * ((x + y + z) % 3) as f32 - 0.3);
                }
            }
        }
        VolumeData::new([n; 3], [1.0, 2.0, 0.5], [1.0, 2.0, 3.0], values).unwrap()
    }

    fn expected(volume: &VolumeData, labels: &[i64]) -> Vec<f32> {
        let v = labelled();
        assert_eq!(v.dims, volume.dims);
        v.values_f32()
            .iter()
            .map(|x| {
                if labels.contains(&(x.round() as i64)) {
                    1.0
                } else {
                    0.0
                }
            })
            .collect()
    }

    #[test]
    fn exact_mask_without_smoothing() {
        let v = labelled();
        for labels in [&[1][..], &[2], &[1, 2], &[0], &[2, 2, 1]] {
            let m = label_mask(&v, labels, 0.0).unwrap();
            assert_eq!(m.values_f32(), expected(&v, labels), "{labels:?}");
            assert_eq!((m.dims, m.geometry), (v.dims, v.geometry));
        }
        let ball = label_mask(&v, &[1], 0.0).unwrap();
        assert_eq!(
            ball.values_f32().iter().sum::<f32>() as u64,
            label_counts(&v)[&1]
        );
        // Absent labels: all zero, not an error.
        let none = label_mask(&v, &[7, 9], 0.0).unwrap();
        assert_eq!(none.value_range, [0.0, 0.0]);
        assert!(label_mask(&v, &[], 0.0).is_err());
        assert!(label_mask(&v, &[1], f32::NAN).is_err());
    }

    #[test]
    fn smoothing_preserves_the_sum_and_the_range() {
        let v = labelled();
        // The ball is at least 3 voxels from every border, more than radius ceil(3 * 1.0).
        for sigma in [0.5f32, 1.0] {
            let m = label_mask(&v, &[1], sigma).unwrap();
            let sharp: f64 = expected(&v, &[1]).iter().map(|&x| x as f64).sum();
            let smooth: f64 = m.values_f32().iter().map(|&x| x as f64).sum();
            assert!(
                ((smooth - sharp) / sharp).abs() < 1e-3,
                "{sigma}: {smooth} vs {sharp}"
            );
            assert!(m.value_range[0] >= 0.0 && m.value_range[1] <= 1.0);
            // Blurred: the centre stays inside, the surface is no longer a 0/1 step.
            assert!(m.value(10, 10, 10) > 0.99);
            assert!(m.values_f32().iter().any(|&x| x > 0.1 && x < 0.9));
            // Symmetric kernel on a symmetric ball.
            let a = m.value(10, 4, 10);
            assert!((a - m.value(10, 16, 10)).abs() < 1e-5);
            assert!((a - m.value(4, 10, 10)).abs() < 1e-5);
        }
        // The box touches the border: clamped edges keep the corner inside.
        let m = label_mask(&v, &[2], 1.0).unwrap();
        assert!(m.value(0, 0, 0) > 0.9);
    }

    #[test]
    fn blurring_the_bounding_box_equals_blurring_everything() {
        let v = labelled();
        // The ball is inside, the box touches three borders.
        for labels in [&[1][..], &[2], &[1, 2]] {
            for sigma in [0.4f32, 1.0, 2.5] {
                let full = gaussian_blur(expected(&v, labels), v.dims, sigma);
                let m = label_mask(&v, labels, sigma).unwrap();
                let diff = full
                    .iter()
                    .zip(m.values_f32().iter())
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f32::max);
                assert_eq!(diff, 0.0, "{labels:?} sigma {sigma}");
            }
        }
    }

    #[test]
    fn rounding_matches_round() {
        for v in [
            0.0f32, 0.49999997, 0.5, 1.5, 2.5, -0.5, -1.5, -2.4, -2.6, 7.0, 1e9, -1e9, 8388607.5,
            4194303.5, 3e38, -3e38,
        ] {
            assert_eq!(round_label(v), v.round() as i64, "{v}");
        }
    }

    #[test]
    fn counts() {
        let v = VolumeData::new(
            [2, 2, 2],
            [1.0; 3],
            [0.0; 3],
            vec![0.0, 0.4, 1.0, 1.2, -3.0, 7.0, 6.6, 0.0],
        )
        .unwrap();
        let c = label_counts(&v);
        assert_eq!(
            c.into_iter().collect::<Vec<_>>(),
            [(-3, 1), (0, 3), (1, 2), (7, 2)]
        );
        // Values too far apart for a dense histogram.
        let v = VolumeData::new(
            [2, 2, 2],
            [1.0; 3],
            [0.0; 3],
            vec![0.0, 1e9, 0.0, 0.0, 5.0, 0.0, 0.0, 1e9],
        )
        .unwrap();
        let c = label_counts(&v);
        assert_eq!(
            c.into_iter().collect::<Vec<_>>(),
            [(0, 5), (5, 1), (1_000_000_000, 2)]
        );
    }

    #[test]
    fn frog_largest_label_mask() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/data/volumes/frog_tissues.vti"
        );
        let frog = crate::vti_file::load_vti(std::path::Path::new(path), None).unwrap();
        let counts = label_counts(&frog);
        let (&largest, &count) = counts
            .iter()
            .filter(|&(&l, _)| l != 0)
            .max_by_key(|&(_, &n)| n)
            .unwrap();
        assert_eq!((largest, count), (13, 438_052));
        let start = std::time::Instant::now();
        let sharp = label_mask(&frog, &[largest], 0.0).unwrap();
        let t_sharp = start.elapsed();
        let start = std::time::Instant::now();
        let smooth = label_mask(&frog, &[largest], 1.0).unwrap();
        let t_smooth = start.elapsed();
        eprintln!("frog label {largest}: mask {t_sharp:?}, mask + blur sigma 1: {t_smooth:?}");
        assert_eq!(
            sharp.values_f32().iter().filter(|&&x| x == 1.0).count() as u64,
            count
        );
        assert!(smooth.value_range[1] > 0.999);
        let sum: f64 = smooth.values_f32().iter().map(|&x| x as f64).sum();
        assert!((sum / count as f64 - 1.0).abs() < 1e-2, "{sum}");
    }

    #[test]
    fn label_lists() {
        let parse = |text: &str| parse_label_list(text).map_err(|e| e.to_string());
        assert_eq!(parse("3"), Ok(vec![3]));
        assert_eq!(parse("3,4, 7"), Ok(vec![3, 4, 7]));
        assert_eq!(parse("1-5"), Ok(vec![1, 2, 3, 4, 5]));
        assert_eq!(parse(" 2-4 ,9"), Ok(vec![2, 3, 4, 9]));
        assert_eq!(parse("9,2-4,3"), Ok(vec![2, 3, 4, 9]));
        assert_eq!(parse("-2--1, 5 - 6"), Ok(vec![-2, -1, 5, 6]));
        assert_eq!(parse("4-4"), Ok(vec![4]));
        assert_eq!(parse("x"), Err("`x`: not a label number".into()));
        assert_eq!(parse("1,x"), Err("`x`: not a label number".into()));
        assert_eq!(parse("2.5"), Err("`2.5`: not a label number".into()));
        assert_eq!(parse("1-b"), Err("`1-b`: `b` is not a label number".into()));
        assert_eq!(
            parse("5-1"),
            Err("`5-1`: range start is after its end".into())
        );
        assert!(
            parse("1,,2")
                .unwrap_err()
                .to_string()
                .contains("empty entry")
        );
        assert!(parse("1-").is_err());
        assert!(parse("").is_err());
        assert!(parse(" ").is_err());
        assert!(
            parse("0-1000000000")
                .unwrap_err()
                .to_string()
                .contains("longer than")
        );
    }
}
