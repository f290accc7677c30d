//! Built-in volumes that are always available and deterministic: signed distance fields on a
//! grid covering world [-1, 1]^3, positive inside, so iso 0 gives the exact shape; and one
//! density field, [`plume`], a subject for Schlieren photographs; and [`convection`]'s
//! temperature.

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

/// Centres (x) of the two vertical bores of [`engine_block`] and the pistons in them.
pub const BORE_X: [f32; 2] = [-0.4, 0.4];
/// Radius of the vertical bores of [`engine_block`].
pub const BORE_RADIUS: f32 = 0.25;

/// An engine-like block for hidden-structure illustration: the box |x| ≤ 0.85, |y| ≤ 0.55,
/// |z| ≤ 0.5 with two vertical bores (radius [`BORE_RADIUS`], axes along y at x = ±0.4, z = 0)
/// and one horizontal bore (radius 0.12 along x at y = -0.3, z = 0). Value = signed distance to
/// the material, positive inside (the minimum of the box's and the bores' complements).
pub fn engine_block(resolution: u32) -> Result<VolumeData, DataError> {
    field(resolution, |p| {
        let half = Vec3::new(0.85, 0.55, 0.5);
        let q = p.abs() - half;
        let box_outside = q.max(Vec3::ZERO).length() + q.max_element().min(0.0);
        let mut inside = -box_outside;
        for x in BORE_X {
            let bore = BORE_RADIUS - ((p.x - x).powi(2) + p.z * p.z).sqrt();
            inside = inside.min(-bore);
        }
        let crank = 0.12 - ((p.y + 0.3).powi(2) + p.z * p.z).sqrt();
        inside.min(-crank)
    })
}

/// Two pistons that sit inside the bores of [`engine_block`]: capped cylinders of radius 0.17
/// around x = ±0.4, z = 0, spanning y ∈ [-0.05, 0.35] (left) and [-0.2, 0.2] (right).
/// Value = signed distance, positive inside.
pub fn pistons(resolution: u32) -> Result<VolumeData, DataError> {
    field(resolution, |p| {
        let piston = |x: f32, y_centre: f32| {
            let radial = 0.17 - ((p.x - x).powi(2) + p.z * p.z).sqrt();
            let axial = 0.2 - (p.y - y_centre).abs();
            radial.min(axial)
        };
        piston(BORE_X[0], 0.15).max(piston(BORE_X[1], 0.0))
    })
}

/// Height (y) of the source of [`plume`].
pub const PLUME_SOURCE_Y: f32 = -0.8;

/// The density of air around a hot plume rising along +y from a small heated ball at
/// (0, [`PLUME_SOURCE_Y`], 0), as a Schlieren photograph of a candle or a heater shows it
/// (Svakhine et al. 2005 §4): 1 in the still air, lower in the ball and in the column above it.
/// The column widens as it rises, its centre line sways more and more, its edge ripples in
/// eddies around and along it, and its density deficit pulses in puffs and fades with height.
/// Not a distance field: values lie in about [0.45, 1].
pub fn plume(resolution: u32) -> Result<VolumeData, DataError> {
    field(resolution, |p| {
        let h = ((p.y - PLUME_SOURCE_Y) / (1.0 - PLUME_SOURCE_Y)).clamp(0.0, 1.0);
        // The column starts at the ball, rises laminar, and turns turbulent from a third up.
        let above = ((p.y - PLUME_SOURCE_Y) / 0.08).clamp(0.0, 1.0);
        let t = ((h - 0.2) / 0.45).clamp(0.0, 1.0);
        let t = t * t * (3.0 - 2.0 * t);
        let sway = 0.12 * t;
        let cx = sway * ((5.0 * p.y).sin() + 0.3 * (13.0 * p.y + 2.0).sin());
        let cz = sway * (0.7 * (4.0 * p.y + 1.0).cos() + 0.3 * (11.0 * p.y).sin());
        let (dx, dz) = (p.x - cx, p.z - cz);
        let around = dz.atan2(dx);
        // Eddies: the edge ripples around and along the column in several modes.
        let modes = [
            (2.0, 11.0, 0.18, 0.0),
            (3.0, -17.0, 0.14, 1.0),
            (5.0, 29.0, 0.1, 2.0),
        ];
        let eddies: f32 = modes
            .iter()
            .map(|(m, f, a, phase)| a * (m * around + f * p.y + phase).sin())
            .sum::<f32>()
            + 0.06 * (7.0 * around - 43.0 * p.y).sin();
        // Puffs: the column bulges where the instability rolls it up.
        let puffs = 1.0 + 0.3 * t * (19.0 * p.y).sin();
        let width = (0.03 + 0.22 * h) * puffs * (1.0 + t * eddies);
        let deficit = 0.3 / (1.0 + 2.0 * h) * (1.0 + 0.25 * t * (31.0 * p.y + 3.0 * around).sin());
        let column = deficit * above * above * (3.0 - 2.0 * above);
        // A flat-topped profile: the hot core mixes into still air over a thin layer.
        let radial = ((dx * dx + dz * dz) / (width * width)).powi(2);
        let ball = (p - Vec3::new(0.0, PLUME_SOURCE_Y, 0.0)).length_squared() / (0.05 * 0.05);
        1.0 - column * (-0.5 * radial).exp() - 0.3 * (-0.5 * ball).exp()
    })
}

/// The temperature of the Rayleigh–Bénard convection rolls of
/// [`crate::vector_field::convection_rolls`] (Svakhine et al. 2005, Figure 4's subject): the
/// conduction profile from 1 at the hot floor (y = −1) to 0 at the cold lid (y = 1), plus the
/// rolls' perturbation, warm where the fluid rises: T = (1 − y)/2 − 0.25·a(z)·cos(k(x + 1))·
/// sin(π(y + 1)/2). Values lie in about [0, 1] (the perturbation vanishes at floor and lid).
pub fn convection(resolution: u32) -> Result<VolumeData, DataError> {
    use crate::vector_field::{ROLL_WAVENUMBER, roll_amplitude};
    field(resolution, |p| {
        let rolls = (ROLL_WAVENUMBER * (p.x + 1.0)).cos()
            * (std::f32::consts::FRAC_PI_2 * (p.y + 1.0)).sin();
        (1.0 - p.y) / 2.0 - 0.25 * roll_amplitude(p.z) * rolls
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
    if (resolution as u64).pow(3) > crate::voxels::MAX_VOXELS {
        return Err(DataError::Invalid(format!(
            "procedural volume resolution {resolution} is too large (limit {} voxels)",
            crate::voxels::MAX_VOXELS
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
        assert_eq!(v.spacing(), [0.5; 3]);
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

    #[test]
    fn engine_block_is_material_outside_the_bores_and_pistons_sit_inside_them() {
        let block = engine_block(41).unwrap();
        let pistons = pistons(41).unwrap();
        // Index 20 is the origin, spacing 0.05: x = 0.4 is index 28; (0, 0.2, 0) is index (20, 24, 20),
        // 0.15 from both bore walls and farther from every other face.
        assert!(block.value(28, 20, 20) < 0.0, "bore axis must be empty");
        assert!(
            block.value(20, 24, 20) > 0.0,
            "between the bores is material"
        );
        assert!(
            (block.value(20, 24, 20) - 0.15).abs() < 1e-5,
            "0.15 to the nearest bore wall"
        );
        assert!(block.value(2, 20, 20) < 0.0, "outside the box");
        assert!(
            pistons.value(28, 20, 20) > 0.0,
            "right piston on its bore axis"
        );
        assert!(pistons.value(12, 23, 20) > 0.0, "left piston (y = 0.15)");
        assert!(
            pistons.value(20, 20, 20) < 0.0,
            "nothing between the pistons"
        );
        // Pistons never intersect the block's material.
        for (b, p) in block.values_f32().iter().zip(pistons.values_f32().iter()) {
            assert!(!(*b > 0.01 && *p > 0.01));
        }
    }
}
