//! Statistics of a volume's values that data-relative parameters resolve against (a percentile,
//! a fraction of the range, Otsu's threshold), so a preset's iso value or transfer function
//! fits data of another scanner, modality or value range.

use crate::volume::VolumeData;

/// The `p`-th percentile (0–100) of the volume's finite values, interpolated linearly between
/// the two nearest ranks (numpy's default `linear` method). `None` when no value is finite.
pub fn percentile(volume: &VolumeData, p: f64) -> Option<f32> {
    let values = volume.values_f32();
    let mut finite: Vec<f32> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if finite.is_empty() {
        return None;
    }
    let rank = p.clamp(0.0, 100.0) / 100.0 * (finite.len() - 1) as f64;
    let (lo, frac) = (rank.floor() as usize, rank - rank.floor());
    let (_, &mut below, above) = finite.select_nth_unstable_by(lo, f32::total_cmp);
    if frac == 0.0 || above.is_empty() {
        return Some(below);
    }
    // The next rank is the smallest value above the lower one's position.
    let next = above.iter().copied().fold(f32::INFINITY, f32::min);
    Some((below as f64 + frac * (next as f64 - below as f64)) as f32)
}

/// `min + f·(max − min)` of the finite values (`f` may lie outside [0, 1]).
pub fn range_fraction(volume: &VolumeData, f: f64) -> f32 {
    let [lo, hi] = volume.value_range;
    (lo as f64 + f * (hi as f64 - lo as f64)) as f32
}

/// Bins of the histogram Otsu's method searches.
const OTSU_BINS: usize = 256;

/// Otsu's threshold (Otsu 1979): the value that maximises the between-class variance of the
/// finite values' 256-bin histogram over their range; voxels at or above it form the upper
/// class. `None` when the volume is constant or holds no finite value.
pub fn otsu(volume: &VolumeData) -> Option<f32> {
    let [lo, hi] = volume.value_range;
    // (NaN bounds fail the comparison too.)
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let width = (hi - lo) as f64 / OTSU_BINS as f64;
    let mut hist = [0u64; OTSU_BINS];
    // Over the stored type: no f32 copy of the volume (2 × a uint16 volume's bytes).
    crate::with_voxels!(&volume.voxels, values => {
        for &x in values.iter() {
            let v = crate::voxels::Voxel::to_f32(x);
            if v.is_finite() {
                let bin = (((v - lo) as f64 / width) as usize).min(OTSU_BINS - 1);
                hist[bin] += 1;
            }
        }
    });
    let total: u64 = hist.iter().sum();
    let centre = |i: usize| lo as f64 + (i as f64 + 0.5) * width;
    let sum_all: f64 = hist
        .iter()
        .enumerate()
        .map(|(i, &n)| n as f64 * centre(i))
        .sum();
    let (mut w0, mut sum0) = (0u64, 0.0f64);
    let (mut best, mut best_var) = (1, -1.0f64);
    // Threshold between bin t-1 and bin t: class 0 is bins < t.
    for t in 1..OTSU_BINS {
        w0 += hist[t - 1];
        sum0 += hist[t - 1] as f64 * centre(t - 1);
        let w1 = total - w0;
        if w0 == 0 || w1 == 0 {
            continue;
        }
        let (m0, m1) = (sum0 / w0 as f64, (sum_all - sum0) / w1 as f64);
        let var = w0 as f64 * w1 as f64 * (m0 - m1) * (m0 - m1);
        if var > best_var {
            (best, best_var) = (t, var);
        }
    }
    Some((lo as f64 + best as f64 * width) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A volume of 4·k values (2 × 2 × k voxels).
    fn volume(values: Vec<f32>) -> VolumeData {
        let k = values.len() as u32 / 4;
        VolumeData::new([2, 2, k], [1.0; 3], [0.0; 3], values).unwrap()
    }

    #[test]
    fn percentiles_match_numpy_linear_interpolation() {
        // numpy.percentile([4, 1, 3, 2, 6, 5, 7], [0, 25, 50, 60, 100]) = 1, 2.5, 4, 4.6, 7
        let v = volume(vec![4.0, 1.0, f32::NAN, 3.0, 2.0, 6.0, 5.0, 7.0]);
        assert_eq!(percentile(&v, 0.0), Some(1.0));
        assert_eq!(percentile(&v, 25.0), Some(2.5));
        assert_eq!(percentile(&v, 50.0), Some(4.0));
        assert!((percentile(&v, 60.0).unwrap() - 4.6).abs() < 1e-6);
        assert_eq!(percentile(&v, 100.0), Some(7.0));
        assert_eq!(percentile(&volume(vec![f32::NAN; 8]), 50.0), None);
    }

    #[test]
    fn range_fraction_spans_min_to_max() {
        let v = volume(vec![10.0, 20.0, 30.0, 20.0, 15.0, 25.0, 20.0, 20.0]);
        assert_eq!(range_fraction(&v, 0.0), 10.0);
        assert_eq!(range_fraction(&v, 0.25), 15.0);
        assert_eq!(range_fraction(&v, 1.0), 30.0);
    }

    #[test]
    fn otsu_separates_two_clusters() {
        // Background near 0, tissue near 100: the threshold falls between them.
        let mut values = vec![0.0f32; 600];
        values.extend((0..400).map(|i| 95.0 + (i % 11) as f32));
        values.extend((0..52).map(|i| (i % 7) as f32));
        let t = otsu(&volume(values)).unwrap();
        // Every threshold in (6, 95] splits the two clusters alike; the first such is taken.
        assert!(t > 6.0 && t <= 95.0, "threshold {t}");
        assert_eq!(otsu(&volume(vec![5.0; 8])), None);
    }
}
