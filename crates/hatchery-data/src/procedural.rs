//! Built-in volumes that are always available and deterministic: signed distance fields on a
//! grid covering world [-1, 1]^3, positive inside, so iso 0 gives the exact shape.

use glam::Vec3;
use rayon::prelude::*;

use crate::{DataError, VolumeData};

/// Centre radii of the three nested shells of [`shells`], outermost first.
pub const SHELL_RADII: [f32; 3] = [0.8, 0.5, 0.2];
/// Half the thickness of each shell of [`shells`].
pub const SHELL_HALF_THICKNESS: f32 = 0.05;

/// Three nested spherical shells: value = max over shells of
/// `SHELL_HALF_THICKNESS - |r - r_k|`, the signed distance to the nearest shell band (positive
/// inside a shell). Iso 0 gives the six spheres `r_k ± SHELL_HALF_THICKNESS`.
pub fn shells(resolution: u32) -> Result<VolumeData, DataError> {
    field(resolution, |p| {
        let r = p.length();
        SHELL_RADII
            .iter()
            .map(|rk| SHELL_HALF_THICKNESS - (r - rk).abs())
            .fold(f32::NEG_INFINITY, f32::max)
    })
}

/// A ball centred at the origin: value = `radius - r`.
pub fn sphere(resolution: u32, radius: f32) -> Result<VolumeData, DataError> {
    check_finite("radius", radius)?;
    field(resolution, |p| radius - p.length())
}

/// A torus around the z axis: value = `minor` minus the distance to the core circle of radius
/// `major` in the xy plane.
pub fn torus(resolution: u32, major: f32, minor: f32) -> Result<VolumeData, DataError> {
    check_finite("major radius", major)?;
    check_finite("minor radius", minor)?;
    field(resolution, |p| {
        let ring = Vec3::new(p.x, p.y, 0.0).length() - major;
        minor - (ring * ring + p.z * p.z).sqrt()
    })
}

fn check_finite(what: &str, v: f32) -> Result<(), DataError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(DataError::Invalid(format!(
            "{what} must be finite, got {v}"
        )))
    }
}

/// Samples `f` at the voxel centres of a `resolution`^3 grid spanning [-1, 1]^3, one z-slice
/// per rayon task.
fn field(resolution: u32, f: impl Fn(Vec3) -> f32 + Sync) -> Result<VolumeData, DataError> {
    if resolution < 2 {
        return Err(DataError::Invalid(format!(
            "procedural volume resolution must be at least 2, got {resolution}"
        )));
    }
    // Keep the allocation within what the NIfTI loader would accept too.
    if (resolution as u64).pow(3) > crate::nifti_file::MAX_VOXELS {
        return Err(DataError::Invalid(format!(
            "procedural volume resolution {resolution} is too large (limit {} voxels)",
            crate::nifti_file::MAX_VOXELS
        )));
    }
    let n = resolution as usize;
    let spacing = 2.0 / (resolution - 1) as f32;
    let coord = |i: usize| -1.0 + i as f32 * spacing;
    let mut values = vec![0.0f32; n * n * n];
    values
        .par_chunks_mut(n * n)
        .enumerate()
        .for_each(|(z, slice)| {
            for (i, v) in slice.iter_mut().enumerate() {
                *v = f(Vec3::new(coord(i % n), coord(i / n), coord(z)));
            }
        });
    VolumeData::new([resolution; 3], [spacing; 3], [-1.0; 3], values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_covers_unit_cube() {
        let v = sphere(5, 0.5).unwrap();
        assert_eq!(v.dims, [5, 5, 5]);
        assert_eq!(v.spacing, [0.5; 3]);
        assert_eq!(v.world_min(), Vec3::splat(-1.0));
        assert_eq!(v.world_max(), Vec3::splat(1.0));
        // Centre voxel is the origin.
        assert_eq!(v.value(2, 2, 2), 0.5);
        // Voxel (4, 2, 2) sits at x = 1.
        assert!((v.value(4, 2, 2) - (0.5 - 1.0)).abs() < 1e-6);
    }

    #[test]
    fn shells_values() {
        let v = shells(33).unwrap();
        assert!(v.value_range[1] <= SHELL_HALF_THICKNESS + 1e-6);
        assert!(v.value_range[1] > SHELL_HALF_THICKNESS - 0.02);
        assert!(v.value_range[0] < -0.8);
        // Voxel 16 is the origin: distance 0.2 to the innermost shell's centre radius.
        assert!((v.value(16, 16, 16) - (SHELL_HALF_THICKNESS - 0.2)).abs() < 1e-6);
        // x = 0.5 is on the middle shell's centre radius.
        assert!((v.value(24, 16, 16) - SHELL_HALF_THICKNESS).abs() < 1e-6);
    }

    #[test]
    fn torus_values() {
        let v = torus(21, 0.6, 0.2).unwrap();
        // (0.6, 0, 0) is on the core circle: index 10 + 0.6 / 0.1 = 16.
        assert!((v.value(16, 10, 10) - 0.2).abs() < 1e-5);
        assert!((v.value(10, 10, 10) - (0.2 - 0.6)).abs() < 1e-5);
    }

    #[test]
    fn bad_parameters_are_errors() {
        assert!(sphere(1, 0.5).is_err());
        assert!(shells(0).is_err());
        assert!(torus(8, f32::NAN, 0.1).is_err());
        assert!(sphere(100_000, 0.5).is_err());
    }

    #[test]
    fn deterministic() {
        assert_eq!(shells(17).unwrap(), shells(17).unwrap());
    }
}
