//! Scalar volumes on a regular, axis-aligned grid.

use glam::Vec3;
use rayon::prelude::*;

use crate::DataError;

/// A scalar field sampled on a regular grid, x fastest.
#[derive(Debug, Clone, PartialEq)]
pub struct VolumeData {
    /// Voxel counts along x, y, z.
    pub dims: [u32; 3],
    /// World units (mm for NIfTI) per voxel along x, y, z.
    pub spacing: [f32; 3],
    /// World position of the centre of voxel (0, 0, 0).
    pub origin: [f32; 3],
    /// `dims[0] * dims[1] * dims[2]` values, index = `x + dims[0] * (y + dims[1] * z)`.
    pub values: Vec<f32>,
    /// `[min, max]` of `values`.
    pub value_range: [f32; 2],
}

impl VolumeData {
    /// Checks the invariants (length, every dim >= 2, positive finite spacing, finite origin and
    /// values) and computes the value range.
    pub fn new(
        dims: [u32; 3],
        spacing: [f32; 3],
        origin: [f32; 3],
        values: Vec<f32>,
    ) -> Result<Self, DataError> {
        if dims.iter().any(|&d| d < 2) {
            return Err(DataError::Invalid(format!(
                "volume dims must be at least 2 along every axis, got {dims:?}"
            )));
        }
        let expected = dims
            .iter()
            .try_fold(1usize, |acc, &d| acc.checked_mul(d as usize));
        if expected != Some(values.len()) {
            return Err(DataError::Invalid(format!(
                "volume dims {dims:?} need {} values, got {}",
                dims.iter().map(|&d| d as u128).product::<u128>(),
                values.len()
            )));
        }
        if spacing.iter().any(|s| !s.is_finite() || *s <= 0.0) {
            return Err(DataError::Invalid(format!(
                "volume spacing must be positive and finite, got {spacing:?}"
            )));
        }
        if origin.iter().any(|o| !o.is_finite()) {
            return Err(DataError::Invalid(format!(
                "volume origin must be finite, got {origin:?}"
            )));
        }
        // In parallel: this runs over every voxel each time a volume is loaded or derived.
        let (range, finite) = values.par_chunks(1 << 16).map(range_and_finite).reduce(
            || ([f32::INFINITY, f32::NEG_INFINITY], true),
            |(a, fa), (b, fb)| ([a[0].min(b[0]), a[1].max(b[1])], fa && fb),
        );
        if !finite && let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(DataError::Invalid(format!(
                "volume value {} at index {i} is not finite",
                values[i]
            )));
        }
        Ok(Self {
            dims,
            spacing,
            origin,
            values,
            value_range: range,
        })
    }

    pub fn voxel_count(&self) -> usize {
        self.values.len()
    }

    /// Linear index of voxel (x, y, z); the caller keeps the coordinates in range.
    #[inline]
    pub fn index(&self, x: u32, y: u32, z: u32) -> usize {
        x as usize + self.dims[0] as usize * (y as usize + self.dims[1] as usize * z as usize)
    }

    #[inline]
    pub fn value(&self, x: u32, y: u32, z: u32) -> f32 {
        self.values[self.index(x, y, z)]
    }

    /// Trilinear interpolation at a voxel-space position (voxel centres at integers), clamped to
    /// the grid so positions outside return the nearest boundary value.
    pub fn sample_trilinear(&self, voxel: Vec3) -> f32 {
        let (base, t) = self.cell_and_fraction(voxel);
        let [x, y, z] = base;
        let c = |dx: u32, dy: u32, dz: u32| self.value(x + dx, y + dy, z + dz);
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let c00 = lerp(c(0, 0, 0), c(1, 0, 0), t.x);
        let c10 = lerp(c(0, 1, 0), c(1, 1, 0), t.x);
        let c01 = lerp(c(0, 0, 1), c(1, 0, 1), t.x);
        let c11 = lerp(c(0, 1, 1), c(1, 1, 1), t.x);
        lerp(lerp(c00, c10, t.y), lerp(c01, c11, t.y), t.z)
    }

    /// World-space gradient at a voxel-space position: central differences one voxel either side
    /// of trilinear samples, divided by the world distance. At the grid boundary the difference
    /// becomes one-sided (the sample positions are clamped and the real distance is used).
    pub fn gradient(&self, voxel: Vec3) -> Vec3 {
        let max = self.max_voxel();
        let p = voxel.clamp(Vec3::ZERO, max);
        let mut g = [0.0f32; 3];
        for (axis, g) in g.iter_mut().enumerate() {
            let mut lo = p;
            let mut hi = p;
            lo[axis] = (p[axis] - 1.0).max(0.0);
            hi[axis] = (p[axis] + 1.0).min(max[axis]);
            // dims >= 2, so hi - lo >= 1 always.
            let dist = (hi[axis] - lo[axis]) * self.spacing[axis];
            *g = (self.sample_trilinear(hi) - self.sample_trilinear(lo)) / dist;
        }
        Vec3::from_array(g)
    }

    /// World position of the first voxel centre.
    pub fn world_min(&self) -> Vec3 {
        Vec3::from_array(self.origin)
    }

    /// World position of the last voxel centre.
    pub fn world_max(&self) -> Vec3 {
        self.voxel_to_world(self.max_voxel())
    }

    pub fn voxel_to_world(&self, v: Vec3) -> Vec3 {
        Vec3::from_array(self.origin) + v * Vec3::from_array(self.spacing)
    }

    fn max_voxel(&self) -> Vec3 {
        Vec3::new(
            (self.dims[0] - 1) as f32,
            (self.dims[1] - 1) as f32,
            (self.dims[2] - 1) as f32,
        )
    }

    /// The cell containing `voxel` (clamped to the grid) and the position inside it in [0, 1]^3.
    /// The last cell along each axis is used for positions on the far boundary.
    fn cell_and_fraction(&self, voxel: Vec3) -> ([u32; 3], Vec3) {
        // NaN fails every comparison; map it to 0 so a bad coordinate cannot index out of range.
        let p = Vec3::select(voxel.is_nan_mask(), Vec3::ZERO, voxel)
            .clamp(Vec3::ZERO, self.max_voxel());
        let mut base = [0u32; 3];
        let mut t = Vec3::ZERO;
        for axis in 0..3 {
            let cell = (p[axis].floor() as u32).min(self.dims[axis] - 2);
            base[axis] = cell;
            t[axis] = p[axis] - cell as f32;
        }
        (base, t)
    }
}

/// `[min, max]` of the finite values and whether all are finite. Eight independent lanes and
/// plain comparisons (no NaN-aware `min`) let the loop vectorise.
fn range_and_finite(values: &[f32]) -> ([f32; 2], bool) {
    const LANES: usize = 8;
    let mut lo = [f32::INFINITY; LANES];
    let mut hi = [f32::NEG_INFINITY; LANES];
    let mut finite = true;
    let mut chunks = values.chunks_exact(LANES);
    for chunk in &mut chunks {
        for k in 0..LANES {
            let v = chunk[k];
            finite &= v.is_finite();
            lo[k] = if v < lo[k] { v } else { lo[k] };
            hi[k] = if v > hi[k] { v } else { hi[k] };
        }
    }
    for &v in chunks.remainder() {
        finite &= v.is_finite();
        lo[0] = if v < lo[0] { v } else { lo[0] };
        hi[0] = if v > hi[0] { v } else { hi[0] };
    }
    let lo = lo.into_iter().fold(f32::INFINITY, f32::min);
    let hi = hi.into_iter().fold(f32::NEG_INFINITY, f32::max);
    ([lo, hi], finite)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A volume whose values are a linear function of the world position.
    fn linear() -> VolumeData {
        let dims = [4u32, 5, 6];
        let spacing = [0.5f32, 2.0, 1.5];
        let origin = [1.0f32, -2.0, 3.0];
        let mut values = Vec::new();
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    values.push(x as f32 + 10.0 * y as f32 + 100.0 * z as f32);
                }
            }
        }
        VolumeData::new(dims, spacing, origin, values).unwrap()
    }

    #[test]
    fn new_checks_invariants() {
        assert!(VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], vec![0.0; 7]).is_err());
        assert!(VolumeData::new([1, 2, 2], [1.0; 3], [0.0; 3], vec![0.0; 4]).is_err());
        assert!(VolumeData::new([2, 2, 2], [0.0, 1.0, 1.0], [0.0; 3], vec![0.0; 8]).is_err());
        assert!(VolumeData::new([2, 2, 2], [f32::NAN, 1.0, 1.0], [0.0; 3], vec![0.0; 8]).is_err());
        let mut v = vec![0.0; 8];
        v[3] = f32::NAN;
        assert!(VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], v).is_err());
        let v = VolumeData::new(
            [2, 2, 2],
            [1.0; 3],
            [0.0; 3],
            vec![-1.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0, 2.0],
        )
        .unwrap();
        assert_eq!(v.value_range, [-1.0, 5.0]);
        assert_eq!(v.voxel_count(), 8);
        // Spread over many chunks and lanes, with the extremes in the remainders.
        let n = 40 * 50 * 70;
        let mut values: Vec<f32> = (0..n).map(|i| (i % 97) as f32).collect();
        values[n - 1] = -3.0;
        values[70_001] = 200.0;
        let big = VolumeData::new([40, 50, 70], [1.0; 3], [0.0; 3], values.clone()).unwrap();
        assert_eq!(big.value_range, [-3.0, 200.0]);
        values[100_000] = f32::NAN;
        values[130_000] = f32::INFINITY;
        let e = VolumeData::new([40, 50, 70], [1.0; 3], [0.0; 3], values).unwrap_err();
        assert!(e.to_string().contains("at index 100000"), "{e}");
    }

    #[test]
    fn indexing_and_sampling() {
        let v = linear();
        assert_eq!(v.value(3, 2, 1), 3.0 + 20.0 + 100.0);
        assert_eq!(v.values[v.index(3, 2, 1)], 123.0);
        // Trilinear interpolation reproduces a linear function exactly.
        let s = v.sample_trilinear(Vec3::new(1.25, 2.5, 3.75));
        assert!((s - (1.25 + 25.0 + 375.0)).abs() < 1e-3, "{s}");
        // Clamped outside and exact on the far boundary.
        assert_eq!(v.sample_trilinear(Vec3::new(-5.0, 0.0, 0.0)), 0.0);
        assert_eq!(v.sample_trilinear(Vec3::new(3.0, 4.0, 5.0)), 543.0);
        assert_eq!(v.sample_trilinear(Vec3::new(30.0, 40.0, 50.0)), 543.0);
        assert_eq!(v.sample_trilinear(Vec3::NAN), 0.0);
    }

    #[test]
    fn gradient_is_world_space() {
        let v = linear();
        // d/dx = 1 per voxel / 0.5 world units, d/dy = 10 / 2, d/dz = 100 / 1.5.
        let want = Vec3::new(2.0, 5.0, 100.0 / 1.5);
        for p in [
            Vec3::new(1.5, 2.0, 2.5),
            Vec3::ZERO,
            Vec3::new(3.0, 4.0, 5.0),
        ] {
            let g = v.gradient(p);
            assert!((g - want).abs().max_element() < 1e-3, "at {p}: {g}");
        }
    }

    #[test]
    fn world_bounds() {
        let v = linear();
        assert_eq!(v.world_min(), Vec3::new(1.0, -2.0, 3.0));
        assert_eq!(v.world_max(), Vec3::new(1.0 + 1.5, -2.0 + 8.0, 3.0 + 7.5));
        assert_eq!(
            v.voxel_to_world(Vec3::new(2.0, 1.0, 0.0)),
            Vec3::new(2.0, 0.0, 3.0)
        );
    }
}
