//! Volume thinning's order as a rank within each object (Viola, Kanitsar & Gröller, importance-
//! driven feature enhancement, §V.C: "Voxels of an object are sorted according to two sorting
//! keys. The first sorting key is gradient magnitude, the second sorting key is curvature
//! magnitude of the iso-surface through the voxel."). A level of sparseness S keeps the fraction
//! S of an object's voxels that come last in that order; the ray caster computes each sample's
//! key and looks up, per object, the fraction of the object's voxels whose key is lower
//! ([`thinning_ranks`]), keeping the sample where that fraction is at least 1 − S.
//!
//! The key — (L + κ̂) / B, L the level of gradient magnitude out of B, κ̂ the curvature
//! magnitude in units of the smallest spacing — is the one shaders/two_level_raycast.wgsl's
//! `thinning_key` computes, here at the voxel centres on the CPU.

use crate::VolumeData;
use glam::{Mat3, Vec3};
use rayon::prelude::*;

/// Bins of the key in [0, 1] per object: a rank table row.
pub const RANK_BINS: usize = 256;

/// What the key depends on besides the field: B levels of gradient magnitude, 1 / the largest
/// gradient magnitude (world units) and the Hessian's difference step w (world units, the
/// smallest spacing).
#[derive(Clone, Copy, Debug)]
pub struct KeyParams {
    pub bands: f32,
    pub inv_max_gradient: f32,
    pub step: f32,
}

/// Volume thinning's sort key at voxel-space point `q`, in [0, 1]: (L + κ̂) / B with
/// L = min(⌊B·|∇f|/|∇f|max⌋, B − 1) and κ̂ = min(√(κ1² + κ2²)·w, 1), κ1, κ2 the principal
/// curvatures of the iso-surface through `q` from the Hessian by central differences of the world
/// gradient at ±w along the world axes. 0 where the gradient vanishes (sorted first).
pub fn thinning_key(volume: &VolumeData, q: Vec3, k: &KeyParams) -> f32 {
    let g = volume.gradient(q);
    let length = g.length();
    // NaN (no data nearby) sorts first too.
    if length.is_nan() || length < 1e-12 {
        return 0.0;
    }
    let bands = k.bands.max(1.0);
    let level = (bands * (length * k.inv_max_gradient).min(1.0))
        .floor()
        .min(bands - 1.0);
    let p = volume.voxel_to_world(q);
    let w = k.step;
    let gradient_at = |p: Vec3| volume.gradient(volume.world_to_voxel(p));
    let columns = [Vec3::X, Vec3::Y, Vec3::Z]
        .map(|e| (gradient_at(p + e * w) - gradient_at(p - e * w)) / (2.0 * w));
    let h = Mat3::from_cols(columns[0], columns[1], columns[2]);
    let h = (h + h.transpose()) * 0.5;
    // √(κ1² + κ2²) is the Frobenius norm of the shape operator, the Hessian projected onto the
    // tangent plane over |∇f| (no tangent basis needed).
    let n = g / length;
    let tangent = Mat3::IDENTITY - Mat3::from_cols(n * n.x, n * n.y, n * n.z);
    let shape = tangent * h * tangent;
    let frobenius = [shape.x_axis, shape.y_axis, shape.z_axis]
        .iter()
        .map(|c| c.length_squared())
        .sum::<f32>()
        .sqrt();
    let kappa = (frobenius / length * w).min(1.0);
    ((level + kappa) / bands).clamp(0.0, 1.0)
}

/// The bin of a key in [0, 1] (as the shader finds it).
pub fn key_bin(key: f32) -> usize {
    ((key * RANK_BINS as f32) as usize).min(RANK_BINS - 1)
}

/// Per object id 0 … `ids_count` − 1 (rows, id-major), for each key bin b, the fraction of that
/// object's voxels whose key falls in a lower bin: the object's rank of a key in bin b. Objects
/// without voxels get 0 rows. `ids` is the label map on `volume`'s grid (x fastest).
///
/// Keys are taken at every `stride`-th voxel along each axis (a uniform sample: the fractions
/// are those of the object's voxels up to sampling); `stride` is chosen so that about
/// `max_samples` voxels are keyed (at least 1).
pub fn thinning_ranks(
    volume: &VolumeData,
    ids: &[u16],
    ids_count: usize,
    k: &KeyParams,
    max_samples: usize,
) -> Vec<f32> {
    let [nx, ny, nz] = volume.dims.map(|d| d as usize);
    let voxels = nx * ny * nz;
    let stride = ((voxels as f64 / max_samples.max(1) as f64).cbrt().ceil() as usize).max(1);
    let histograms = (0..nz)
        .into_par_iter()
        .step_by(stride)
        .fold(
            || vec![0u64; ids_count * RANK_BINS],
            |mut h, z| {
                for y in (0..ny).step_by(stride) {
                    for x in (0..nx).step_by(stride) {
                        let id = ids[x + nx * (y + ny * z)] as usize;
                        if id < ids_count {
                            let q = Vec3::new(x as f32, y as f32, z as f32);
                            h[id * RANK_BINS + key_bin(thinning_key(volume, q, k))] += 1;
                        }
                    }
                }
                h
            },
        )
        .reduce(
            || vec![0u64; ids_count * RANK_BINS],
            |mut a, b| {
                a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
                a
            },
        );
    let mut ranks = vec![0.0f32; ids_count * RANK_BINS];
    for (row, counts) in ranks
        .chunks_exact_mut(RANK_BINS)
        .zip(histograms.chunks_exact(RANK_BINS))
    {
        let total = counts.iter().sum::<u64>().max(1) as f64;
        let mut below = 0u64;
        for (r, &c) in row.iter_mut().zip(counts) {
            *r = (below as f64 / total) as f32;
            below += c;
        }
    }
    ranks
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params(volume: &VolumeData, bands: f32) -> KeyParams {
        KeyParams {
            bands,
            inv_max_gradient: 1.0 / crate::gradient::max_gradient_magnitude(volume),
            step: 1.0,
        }
    }

    /// Planes of three slopes (levels 0, 2 and 3 of 4, κ = 0) in three equal thirds of object 1:
    /// the ranks of their keys are 0, 1/3 and 2/3.
    #[test]
    fn ranks_of_three_equal_layers_are_thirds() {
        let (nx, ny, nz) = (30usize, 4usize, 4usize);
        let slope = |x: usize| match x / 10 {
            0 => 1.0,
            1 => 5.0,
            _ => 7.0,
        };
        let mut row = vec![0.0f32; nx];
        for x in 1..nx {
            row[x] = row[x - 1] + slope(x);
        }
        let values = (0..nx * ny * nz).map(|i| row[i % nx]).collect();
        let v = VolumeData::new(
            [nx as u32, ny as u32, nz as u32],
            [1.0; 3],
            [0.0; 3],
            values,
        )
        .unwrap();
        let k = params(&v, 4.0);
        // Layer interiors (central differences within one slope).
        let keys: Vec<f32> = [5.0, 15.0, 25.0]
            .map(|x| thinning_key(&v, Vec3::new(x, 2.0, 2.0), &k))
            .to_vec();
        assert_eq!(keys, vec![0.0, 0.5, 0.75], "{keys:?}");
        let ids = vec![1u16; nx * ny * nz];
        let ranks = thinning_ranks(&v, &ids, 2, &k, usize::MAX);
        let rank = |key: f32| ranks[RANK_BINS + key_bin(key)];
        assert_eq!(rank(0.0), 0.0);
        // Layer boundaries mix slopes: within a column of each third.
        assert!((rank(0.5) - 1.0 / 3.0).abs() < 0.04, "{}", rank(0.5));
        assert!((rank(0.75) - 2.0 / 3.0).abs() < 0.04, "{}", rank(0.75));
        assert!(
            ranks[..RANK_BINS].iter().all(|&r| r == 0.0),
            "object 0 has no voxels"
        );
    }

    /// On a sphere's distance field κ̂ = w·√2 / r (both principal curvatures 1/r).
    #[test]
    fn curvature_key_of_a_sphere() {
        let n = 48usize;
        let c = (n - 1) as f32 / 2.0;
        let values = (0..n * n * n)
            .map(|i| {
                let p = Vec3::new((i % n) as f32, ((i / n) % n) as f32, (i / (n * n)) as f32);
                (p - Vec3::splat(c)).length()
            })
            .collect();
        let v = VolumeData::new([n as u32; 3], [1.0; 3], [0.0; 3], values).unwrap();
        // One level, so the key is κ̂ alone.
        let k = params(&v, 1.0);
        for r in [8.0f32, 12.0, 20.0] {
            let q = Vec3::splat(c) + Vec3::new(0.6, -0.48, 0.64) * r;
            let key = thinning_key(&v, q, &k);
            let want = std::f32::consts::SQRT_2 / r;
            assert!((key - want).abs() < 0.05 * want, "r {r}: {key} vs {want}");
        }
    }
}
