//! Gradient statistics of volumes.

use rayon::prelude::*;

use crate::VolumeData;
use crate::voxels::Voxel;

/// The largest world-space gradient magnitude over all voxels, with the gradient taken by
/// central differences on the voxel grid (one-sided at the borders), i.e. the magnitude of
/// [`VolumeData::gradient`] at every voxel centre. Used to normalise gradient magnitudes to
/// [0, 1]. 0 for a constant volume.
pub fn max_gradient_magnitude(volume: &VolumeData) -> f32 {
    let nz = volume.dims[2];
    (0..nz)
        .into_par_iter()
        .map(|z| {
            let mut max2 = 0.0f32;
            slice_gradients(volume, z, |_, g| {
                let m2 = g.length_squared();
                // Differences across "no data" are not gradients.
                if m2.is_finite() {
                    max2 = max2.max(m2);
                }
            });
            max2
        })
        .reduce(|| 0.0, f32::max)
        .sqrt()
}

/// The world-space gradients at the voxel centres of slices `z0..z1` (x fastest), as
/// [`max_gradient_magnitude`] takes them; 0 where a difference crosses "no data". One rayon
/// task per slice.
pub fn voxel_gradients(volume: &VolumeData, z0: u32, z1: u32) -> Vec<glam::Vec3> {
    let slice = volume.dims[0] as usize * volume.dims[1] as usize;
    let mut out = vec![glam::Vec3::ZERO; slice * (z1 - z0) as usize];
    out.par_chunks_mut(slice.max(1))
        .zip(z0..z1)
        .for_each(|(chunk, z)| {
            slice_gradients(volume, z, |i, g| {
                chunk[i] = if g.is_finite() { g } else { glam::Vec3::ZERO };
            })
        });
    out
}

/// Calls `f(i, ∇f)` for every voxel `i` of slice `z` (index within the slice): central
/// differences on the grid (one-sided at the borders) mapped to world units.
fn slice_gradients(volume: &VolumeData, z: u32, mut f: impl FnMut(usize, glam::Vec3)) {
    let [nx, ny, nz] = volume.dims.map(|d| d as usize);
    let slice = nx * ny;
    // Voxel-step differences → world gradient: M^-T of the voxel → world linear part.
    let to_world = {
        let g = &volume.geometry;
        (g.direction * glam::DMat3::from_diagonal(g.spacing))
            .inverse()
            .transpose()
            .as_mat3()
    };
    let z = z as usize;
    // Neighbour offsets and voxel distances per axis at index i of n.
    let span = |i: usize, n: usize, stride: usize| {
        let lo = i.saturating_sub(1);
        let hi = (i + 1).min(n - 1);
        ((i - lo) * stride, (hi - i) * stride, (hi - lo) as f32)
    };
    let (zl, zh, zd) = span(z, nz, slice);
    crate::with_voxels!(&volume.voxels, values => {
        for y in 0..ny {
            let (yl, yh, yd) = span(y, ny, nx);
            for x in 0..nx {
                let (xl, xh, xd) = span(x, nx, 1);
                let i = x + nx * (y + ny * z);
                let g = to_world
                    * glam::Vec3::new(
                        (values[i + xh].to_f32() - values[i - xl].to_f32()) / xd,
                        (values[i + yh].to_f32() - values[i - yl].to_f32()) / yd,
                        (values[i + zh].to_f32() - values[i - zl].to_f32()) / zd,
                    );
                f(x + nx * y, g);
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    #[test]
    fn matches_the_volume_gradient_everywhere() {
        // A non-linear field on an anisotropic grid.
        let dims = [5u32, 6, 7];
        let mut values = Vec::new();
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let (x, y, z) = (x as f32, y as f32, z as f32);
                    values.push((x * 0.7).sin() * 3.0 + y * y * 0.5 - z * x * 0.25);
                }
            }
        }
        let v = VolumeData::new(dims, [0.5, 2.0, 1.5], [1.0, 2.0, 3.0], values).unwrap();
        let mut want = 0.0f32;
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let g = v.gradient(Vec3::new(x as f32, y as f32, z as f32));
                    want = want.max(g.length());
                }
            }
        }
        let got = max_gradient_magnitude(&v);
        assert!((got - want).abs() <= 1e-5 * want, "{got} vs {want}");
    }

    #[test]
    fn linear_and_constant_fields() {
        let dims = [4u32, 3, 2];
        let mut values = Vec::new();
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    values.push(x as f32 * 2.0 + y as f32 - z as f32 * 3.0);
                }
            }
        }
        let v = VolumeData::new(dims, [1.0, 0.5, 2.0], [0.0; 3], values).unwrap();
        // d/dx = 2, d/dy = 1 / 0.5, d/dz = -3 / 2.
        let want = (4.0f32 + 4.0 + 2.25).sqrt();
        assert!((max_gradient_magnitude(&v) - want).abs() < 1e-5);
        let c = VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], vec![3.0; 8]).unwrap();
        assert_eq!(max_gradient_magnitude(&c), 0.0);
    }
}
