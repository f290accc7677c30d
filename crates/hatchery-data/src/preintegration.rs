//! Pre-integrated transfer functions (Engel, Kraus & Ertl 2001, cited by the tutorial's
//! two-level rendering section): the colour and opacity of a whole ray segment whose data value
//! runs linearly from a front to a back value, looked up by the pair. A sharp opacity ramp that
//! falls between two samples is then still integrated, where post-classification of the samples
//! alone misses it or draws it as rings whose place depends on where the samples fall.
//!
//! The segment is integrated front to back in sub-steps of one table bin, each with the
//! step-corrected opacity `1 − (1 − α·ρ)^Δ` of its own length `Δ` (voxels) — so a constant
//! segment gets exactly the post-classified sample's `1 − (1 − α·ρ)^step` and colour, and the
//! opacity correction stays exact for any step. Within a bin the extinction `−ln(1 − α·ρ)` is
//! interpolated linearly (where post-classification interpolates α: the same at the entries).

use crate::transfer_function::{LUT_SIZE, TransferFunction1D};

/// The pre-integrated table of `tf` for segments `step_voxels` long (voxels of the smallest
/// spacing) with global alpha `rho` (each opacity × ρ): `LUT_SIZE × LUT_SIZE` entries, entry
/// `[front * LUT_SIZE + back]` for the segment from table position `front` to `back` (positions
/// as in [`TransferFunction1D::lut`]), each premultiplied `(r·a, g·a, b·a, a)`. Rows are
/// integrated in parallel (a 1024×768 orbit rebuilds it every frame).
///
/// `step_voxels` must be positive and finite (the Raycast parameter's range guarantees it).
pub fn preintegrated_table(tf: &TransferFunction1D, step_voxels: f32, rho: f32) -> Vec<[f32; 4]> {
    use rayon::prelude::*;
    let media = Media::new(tf, rho);
    let mut table = vec![[0.0; 4]; LUT_SIZE * LUT_SIZE];
    table
        .par_chunks_mut(LUT_SIZE)
        .enumerate()
        .for_each(|(front, row)| {
            for (back, entry) in row.iter_mut().enumerate() {
                *entry = media.segment(front as f32, back as f32, step_voxels);
            }
        });
    table
}

/// One segment from table position `front` to `back` (fractional positions allowed).
pub fn segment(
    tf: &TransferFunction1D,
    front: f32,
    back: f32,
    step_voxels: f32,
    rho: f32,
) -> [f32; 4] {
    Media::new(tf, rho).segment(front, back, step_voxels)
}

/// The table as emission and extinction: per entry the colour and `κ = −ln(1 − α·ρ)` per voxel
/// of path, so that a sub-step of length `Δ` has opacity `1 − e^(−κΔ)` = `1 − (1 − α·ρ)^Δ`.
struct Media {
    entries: Vec<[f32; 4]>,
}

impl Media {
    fn new(tf: &TransferFunction1D, rho: f32) -> Media {
        // An opaque entry would be infinitely dense: it stops any ray within 10⁻⁶ of a voxel.
        let kappa = |a: f32| -(1.0 - (a * rho).clamp(0.0, 1.0 - 1e-6)).ln();
        let entries = tf
            .lut
            .iter()
            .map(|&[r, g, b, a]| [r, g, b, kappa(a)])
            .collect();
        Media { entries }
    }

    fn segment(&self, front: f32, back: f32, step_voxels: f32) -> [f32; 4] {
        // A sub-step per table bin crossed: colour and extinction are linear within a bin.
        let substeps = (back - front).abs().ceil().max(1.0) as usize;
        let length = step_voxels / substeps as f32;
        let (mut colour, mut alpha) = ([0.0f32; 3], 0.0f32);
        for m in 0..substeps {
            let position = front + (back - front) * (m as f32 + 0.5) / substeps as f32;
            let [r, g, b, kappa] = self.at(position);
            let weight = (1.0 - alpha) * (1.0 - (-kappa * length).exp());
            for (c, v) in colour.iter_mut().zip([r, g, b]) {
                *c += weight * v;
            }
            alpha += weight;
        }
        [colour[0], colour[1], colour[2], alpha]
    }

    /// Colour and extinction at fractional table position `x` in `[0, LUT_SIZE − 1]`.
    fn at(&self, x: f32) -> [f32; 4] {
        let x = x.clamp(0.0, (LUT_SIZE - 1) as f32);
        let k = (x.floor() as usize).min(LUT_SIZE - 2);
        let f = x - k as f32;
        let (a, b) = (self.entries[k], self.entries[k + 1]);
        std::array::from_fn(|c| a[c] + (b[c] - a[c]) * f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::transfer_function::ControlPoint;

    fn ramp() -> TransferFunction1D {
        TransferFunction1D::from_points(&[
            ControlPoint {
                value: 0.0,
                rgba: [1.0, 0.0, 0.0, 0.0],
            },
            ControlPoint {
                value: 0.5,
                rgba: [1.0, 0.0, 0.0, 0.0],
            },
            ControlPoint {
                value: 0.52,
                rgba: [0.0, 1.0, 0.0, 0.9],
            },
            ControlPoint {
                value: 1.0,
                rgba: [0.0, 1.0, 0.0, 0.9],
            },
        ])
        .unwrap()
    }

    /// A constant segment is the post-classified sample, opacity corrected for the step.
    #[test]
    fn a_constant_segment_is_the_corrected_sample() {
        let tf = ramp();
        for (position, step) in [(200.0, 0.5), (200.0, 2.0), (10.0, 1.0), (130.0, 0.25)] {
            let [r, g, b, a] = tf.lut[position as usize];
            let want = 1.0 - (1.0 - a * 0.8).powf(step);
            let got = segment(&tf, position, position, step, 0.8);
            assert!((got[3] - want).abs() < 1e-6, "{got:?} vs {want}");
            for (c, v) in [r, g, b].iter().enumerate() {
                assert!((got[c] - v * want).abs() < 1e-6, "{got:?}");
            }
        }
    }

    /// A segment across the thin ramp is as opaque as the ramp's part of the path makes it,
    /// whichever way it is crossed, where a sample at either end sees nothing or everything.
    #[test]
    fn a_segment_across_a_thin_ramp_integrates_it() {
        let tf = ramp();
        let (low, high) = (100.0, 160.0); // 0.39 and 0.63 of the domain
        let step = 2.0;
        let up = segment(&tf, low, high, step, 1.0);
        let down = segment(&tf, high, low, step, 1.0);
        assert!((up[3] - down[3]).abs() < 1e-5, "{up:?} vs {down:?}");
        // The opaque part (0.52..0.63 of the domain) is (0.63 − 0.52) / 0.24 of 2 voxels,
        // plus half the ramp.
        let opaque = (high - 0.52 * 255.0) / (high - low) * step;
        let ramp_part = (0.02 * 255.0) / (high - low) * step;
        let lower = 1.0 - (1.0f32 - 0.9).powf(opaque);
        let upper = 1.0 - (1.0f32 - 0.9).powf(opaque + ramp_part);
        assert!(
            up[3] >= lower - 1e-4 && up[3] <= upper + 1e-4,
            "{} not in [{lower}, {upper}]",
            up[3]
        );
        // Mostly green: red is transparent, and shows only where the ramp mixes the colours.
        assert!(up[0] < 0.1 && up[1] > 0.5, "{up:?}");
        // Longer steps are more opaque, as the table is built per step.
        let long = segment(&tf, low, high, 4.0, 1.0);
        assert!(long[3] > up[3]);
    }

    #[test]
    fn the_table_is_indexed_front_then_back() {
        let tf = ramp();
        let table = preintegrated_table(&tf, 1.0, 1.0);
        assert_eq!(table.len(), LUT_SIZE * LUT_SIZE);
        assert_eq!(
            table[100 * LUT_SIZE + 160],
            segment(&tf, 100.0, 160.0, 1.0, 1.0)
        );
        assert_eq!(
            table[160 * LUT_SIZE + 100],
            segment(&tf, 160.0, 100.0, 1.0, 1.0)
        );
    }
}
