//! Scalar volumes on a regular grid placed in the world by a voxel → world transform.

use glam::Vec3;
use rayon::prelude::*;

use crate::DataError;
use crate::geometry::Geometry;
use crate::voxels::{Voxel, Voxels};

/// A scalar field sampled on a regular grid, i (x) fastest, placed in the world (RAS+ mm, see
/// [`crate::geometry`]) by `geometry`. Voxels keep the type the file stores them in (one byte
/// per voxel for uint8 data). Non-finite values (NaN, ±inf) mean "no data".
#[derive(Debug, Clone, PartialEq)]
pub struct VolumeData {
    /// Voxel counts along i, j, k.
    pub dims: [u32; 3],
    /// Voxel → world transform (origin, spacing, direction).
    pub geometry: Geometry,
    /// `dims[0] * dims[1] * dims[2]` values, index = `i + dims[0] * (j + dims[1] * k)`.
    pub voxels: Voxels,
    /// `[min, max]` of the finite values (`[0, 0]` when there are none).
    pub value_range: [f32; 2],
    /// Name of the voxel type in the file (`uint8`, `float32`, ...), for `hatchery info`; may be
    /// wider than `voxels` (an int32 file is kept as f32).
    pub stored_type: &'static str,
    /// How the file's header placed the voxels (e.g. "sform (sform_code 2)"), for
    /// `hatchery info`; empty for volumes made in memory.
    pub placement: String,
    /// What the loader worked around, one line each (a resampled slice gap, skipped files):
    /// nodes show them as their warning.
    pub warnings: Vec<String>,
}

impl VolumeData {
    /// An axis-aligned f32 volume (identity direction); see [`Self::from_voxels`].
    pub fn new(
        dims: [u32; 3],
        spacing: [f32; 3],
        origin: [f32; 3],
        values: Vec<f32>,
    ) -> Result<Self, DataError> {
        if spacing.iter().any(|s| !s.is_finite() || *s <= 0.0) {
            return Err(DataError::Invalid(format!(
                "volume spacing must be positive and finite, got {spacing:?}"
            )));
        }
        let geometry = Geometry::axis_aligned(spacing.map(f64::from), origin.map(f64::from));
        Self::with_geometry(dims, geometry, values)
    }

    /// An f32 volume; see [`Self::from_voxels`].
    pub fn with_geometry(
        dims: [u32; 3],
        geometry: Geometry,
        values: Vec<f32>,
    ) -> Result<Self, DataError> {
        Self::from_voxels(dims, geometry, Voxels::F32(values))
    }

    /// Checks the invariants (length, every dim >= 2, a finite invertible transform) and
    /// computes the value range over the finite values. The voxels are kept as they are.
    pub fn from_voxels(
        dims: [u32; 3],
        geometry: Geometry,
        voxels: Voxels,
    ) -> Result<Self, DataError> {
        if dims.iter().any(|&d| d < 2) {
            return Err(DataError::Invalid(format!(
                "volume dims must be at least 2 along every axis, got {dims:?}"
            )));
        }
        let expected = dims
            .iter()
            .try_fold(1usize, |acc, &d| acc.checked_mul(d as usize));
        if expected != Some(voxels.len()) {
            return Err(DataError::Invalid(format!(
                "volume dims {dims:?} need {} values, got {}",
                dims.iter().map(|&d| d as u128).product::<u128>(),
                voxels.len()
            )));
        }
        geometry.check()?;
        // In parallel: this runs over every voxel each time a volume is loaded or derived.
        let range = crate::with_voxels!(&voxels, v => finite_range(v));
        let value_range = if range[0] <= range[1] {
            range
        } else {
            [0.0, 0.0]
        };
        Ok(Self {
            dims,
            geometry,
            stored_type: voxels.type_name(),
            voxels,
            value_range,
            placement: String::new(),
            warnings: Vec::new(),
        })
    }

    /// The same grid and transform with other values (a mask, a filtered copy).
    pub fn with_values(&self, values: Vec<f32>) -> Result<Self, DataError> {
        let mut v = Self::with_geometry(self.dims, self.geometry, values)?;
        v.placement.clone_from(&self.placement);
        Ok(v)
    }

    /// Spacing along i, j, k in world units.
    pub fn spacing(&self) -> [f32; 3] {
        self.geometry.spacing.as_vec3().to_array()
    }

    /// World position of voxel (0, 0, 0).
    pub fn origin(&self) -> [f32; 3] {
        self.geometry.origin.as_vec3().to_array()
    }

    /// Whether some voxels are "no data" (non-finite; only float voxels can be).
    pub fn has_no_data(&self) -> bool {
        self.voxels
            .as_f32()
            .is_some_and(|v| !v.par_iter().all(|x| x.is_finite()))
    }

    /// Whether any voxel holds a finite value (integer voxels always do); `value_range` is
    /// `[0, 0]` when none does.
    pub fn has_finite_values(&self) -> bool {
        self.voxels
            .as_f32()
            .is_none_or(|v| v.par_iter().any(|x| x.is_finite()))
    }

    /// The values as f32: borrowed when stored as f32, else converted (a copy: avoid on big
    /// volumes).
    pub fn values_f32(&self) -> std::borrow::Cow<'_, [f32]> {
        match self.voxels.as_f32() {
            Some(v) => std::borrow::Cow::Borrowed(v),
            None => std::borrow::Cow::Owned(self.voxels.to_f32()),
        }
    }

    pub fn voxel_count(&self) -> usize {
        self.voxels.len()
    }

    /// Linear index of voxel (x, y, z); the caller keeps the coordinates in range.
    #[inline]
    pub fn index(&self, x: u32, y: u32, z: u32) -> usize {
        x as usize + self.dims[0] as usize * (y as usize + self.dims[1] as usize * z as usize)
    }

    #[inline]
    pub fn value(&self, x: u32, y: u32, z: u32) -> f32 {
        self.voxels.get(self.index(x, y, z))
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
    /// of trilinear samples (a gradient per voxel step), mapped to world units through the
    /// transform. At the grid boundary, and next to "no data", the difference becomes one-sided.
    pub fn gradient(&self, voxel: Vec3) -> Vec3 {
        let max = self.max_voxel();
        let p = voxel.clamp(Vec3::ZERO, max);
        let mut g = [0.0f32; 3];
        for (axis, g) in g.iter_mut().enumerate() {
            let mut lo = p;
            let mut hi = p;
            lo[axis] = (p[axis] - 1.0).max(0.0);
            hi[axis] = (p[axis] + 1.0).min(max[axis]);
            let (a, b) = (self.sample_trilinear(lo), self.sample_trilinear(hi));
            // Next to "no data" the difference becomes one-sided; 0 with no data either side.
            *g = match (a.is_finite(), b.is_finite()) {
                // dims >= 2, so hi - lo >= 1 always.
                (true, true) => (b - a) / (hi[axis] - lo[axis]),
                (true, false) if p[axis] > lo[axis] => {
                    (self.sample_trilinear(p) - a) / (p[axis] - lo[axis])
                }
                (false, true) if hi[axis] > p[axis] => {
                    (b - self.sample_trilinear(p)) / (hi[axis] - p[axis])
                }
                _ => 0.0,
            };
            if !g.is_finite() {
                *g = 0.0;
            }
        }
        self.geometry.gradient_to_world(Vec3::from_array(g))
    }

    /// Lower corner of the world bounding box of the voxel centres.
    pub fn world_min(&self) -> Vec3 {
        self.geometry.world_bounds(self.dims)[0]
    }

    /// Upper corner of the world bounding box of the voxel centres.
    pub fn world_max(&self) -> Vec3 {
        self.geometry.world_bounds(self.dims)[1]
    }

    /// World position of a voxel-space point.
    pub fn voxel_to_world(&self, v: Vec3) -> Vec3 {
        self.geometry.voxel_to_world(v)
    }

    /// Voxel-space position of a world point.
    pub fn world_to_voxel(&self, p: Vec3) -> Vec3 {
        self.geometry.world_to_voxel(p)
    }

    pub(crate) fn max_voxel(&self) -> Vec3 {
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

/// `[min, max]` of the finite values, in parallel (`[inf, -inf]` when there are none).
fn finite_range<T: Voxel>(values: &[T]) -> [f32; 2] {
    values
        .par_chunks(1 << 16)
        .map(range_and_finite)
        .map(|(r, _)| r)
        .reduce(
            || [f32::INFINITY, f32::NEG_INFINITY],
            |a, b| [a[0].min(b[0]), a[1].max(b[1])],
        )
}

/// `[min, max]` of the finite values and whether all are finite. Eight independent lanes and
/// plain comparisons (no NaN-aware `min`) let the loop vectorise.
fn range_and_finite<T: Voxel>(values: &[T]) -> ([f32; 2], bool) {
    const LANES: usize = 8;
    let mut lo = [f32::INFINITY; LANES];
    let mut hi = [f32::NEG_INFINITY; LANES];
    let mut finite = true;
    let mut chunks = values.chunks_exact(LANES);
    for chunk in &mut chunks {
        for k in 0..LANES {
            let v = chunk[k].to_f32();
            let f = v.is_finite();
            finite &= f;
            lo[k] = if f && v < lo[k] { v } else { lo[k] };
            hi[k] = if f && v > hi[k] { v } else { hi[k] };
        }
    }
    for &v in chunks.remainder() {
        let v = v.to_f32();
        let f = v.is_finite();
        finite &= f;
        lo[0] = if f && v < lo[0] { v } else { lo[0] };
        hi[0] = if f && v > hi[0] { v } else { hi[0] };
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
        // Non-finite values are "no data": allowed, and left out of the value range.
        let mut v = vec![0.0; 8];
        v[3] = f32::NAN;
        v[4] = 2.0;
        v[5] = f32::NEG_INFINITY;
        let nd = VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], v).unwrap();
        assert_eq!(nd.value_range, [0.0, 2.0]);
        assert!(nd.has_no_data());
        let all_nan = VolumeData::new([2, 2, 2], [1.0; 3], [0.0; 3], vec![f32::NAN; 8]).unwrap();
        assert_eq!(all_nan.value_range, [0.0, 0.0]);
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
        let nd = VolumeData::new([40, 50, 70], [1.0; 3], [0.0; 3], values).unwrap();
        assert_eq!(nd.value_range, [-3.0, 200.0]);
    }

    #[test]
    fn indexing_and_sampling() {
        let v = linear();
        assert_eq!(v.value(3, 2, 1), 3.0 + 20.0 + 100.0);
        assert_eq!(v.values_f32()[v.index(3, 2, 1)], 123.0);
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
