//! Where a voxel grid lies in the world: the voxel → world transform of ITK and VTK (origin,
//! spacing, direction cosines), in hatchery's one world convention.
//!
//! **World convention: RAS+ millimetres**, NIfTI's: +x = Right, +y = Anterior, +z = Superior. DICOM, NRRD (`space: left-posterior-superior`) and
//! MetaImage state positions in LPS+ (+x = Left, +y = Posterior); [`Geometry::from_lps`] turns
//! them into RAS+ by negating x and y, so one object written in every format lands in one place.
//! Formats without an anatomical frame (VTK ImageData, TIFF stacks, meshes) are taken as given.

use glam::{DMat3, DMat4, DVec3, Mat4, Vec3};

use crate::DataError;

/// The voxel → world transform of a grid: `world = origin + direction · (spacing ⊙ ijk)` for the
/// voxel index `ijk` (voxel centres at integers). Units: millimetres (or the file's unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Distance between voxel centres along i, j, k (positive).
    pub spacing: DVec3,
    /// Columns: the world direction of the i, j and k axes (unit vectors; may contain flips
    /// and rotations; not necessarily orthogonal for sheared files).
    pub direction: DMat3,
    /// World position of the centre of voxel (0, 0, 0).
    pub origin: DVec3,
}

impl Default for Geometry {
    fn default() -> Self {
        Geometry::axis_aligned([1.0; 3], [0.0; 3])
    }
}

impl Geometry {
    /// An axis-aligned grid (identity direction).
    pub fn axis_aligned(spacing: [f64; 3], origin: [f64; 3]) -> Self {
        Geometry {
            spacing: DVec3::from_array(spacing),
            direction: DMat3::IDENTITY,
            origin: DVec3::from_array(origin),
        }
    }

    /// A geometry stated in LPS+ (DICOM, NRRD `left-posterior-superior`, MetaImage), converted
    /// to hatchery's RAS+ world by negating the x and y rows.
    pub fn from_lps(spacing: [f64; 3], direction: DMat3, origin: [f64; 3]) -> Self {
        let flip = DMat3::from_diagonal(DVec3::new(-1.0, -1.0, 1.0));
        Geometry {
            spacing: DVec3::from_array(spacing),
            direction: flip * direction,
            origin: flip * DVec3::from_array(origin),
        }
    }

    /// The geometry of a 3×4 affine `world = A · (i, j, k, 1)` (NIfTI's sform, in RAS+):
    /// spacing = column lengths, direction = normalised columns, origin = last column.
    ///
    /// Errors: a zero or non-finite column, or a singular matrix.
    pub fn from_affine(rows: [[f64; 4]; 3]) -> Result<Self, DataError> {
        let col = |c: usize| DVec3::new(rows[0][c], rows[1][c], rows[2][c]);
        let mut spacing = [0.0; 3];
        let mut dirs = [DVec3::ZERO; 3];
        for c in 0..3 {
            let v = col(c);
            let len = v.length();
            if !len.is_finite() || len == 0.0 {
                return Err(DataError::Invalid(format!(
                    "voxel → world affine has a zero or non-finite column {c}: {rows:?}"
                )));
            }
            spacing[c] = len;
            dirs[c] = v / len;
        }
        let g = Geometry {
            spacing: DVec3::from_array(spacing),
            direction: DMat3::from_cols(dirs[0], dirs[1], dirs[2]),
            origin: col(3),
        };
        g.check()?;
        Ok(g)
    }

    /// Checks that the transform is finite and invertible.
    pub fn check(&self) -> Result<(), DataError> {
        let finite = self.spacing.is_finite()
            && self.origin.is_finite()
            && self.direction.to_cols_array().iter().all(|v| v.is_finite());
        if !finite {
            return Err(DataError::Invalid(format!(
                "voxel → world transform is not finite: {self:?}"
            )));
        }
        if self.spacing.min_element() <= 0.0 {
            return Err(DataError::Invalid(format!(
                "voxel spacing must be positive, got {:?}",
                self.spacing.to_array()
            )));
        }
        if self.direction.determinant().abs() < 1e-6 {
            return Err(DataError::Invalid(format!(
                "voxel axes are degenerate (direction matrix {:?} is singular)",
                self.direction.to_cols_array_2d()
            )));
        }
        Ok(())
    }

    /// The 4×4 voxel → world matrix (double precision).
    pub fn to_world(&self) -> DMat4 {
        let m = self.direction * DMat3::from_diagonal(self.spacing);
        DMat4::from_cols(
            m.x_axis.extend(0.0),
            m.y_axis.extend(0.0),
            m.z_axis.extend(0.0),
            self.origin.extend(1.0),
        )
    }

    /// The 4×4 world → voxel matrix (double precision).
    pub fn to_voxel(&self) -> DMat4 {
        self.to_world().inverse()
    }

    /// [`Self::to_world`] in single precision (for shaders).
    pub fn to_world_f32(&self) -> Mat4 {
        self.to_world().as_mat4()
    }

    /// World position of a voxel-space point.
    pub fn voxel_to_world(&self, ijk: Vec3) -> Vec3 {
        self.to_world().transform_point3(ijk.as_dvec3()).as_vec3()
    }

    /// Voxel-space position of a world point.
    pub fn world_to_voxel(&self, p: Vec3) -> Vec3 {
        self.to_voxel().transform_point3(p.as_dvec3()).as_vec3()
    }

    /// Whether `other` places voxels where this geometry does: the voxel → world transforms
    /// agree within 1/1000 of the smallest spacing (what lets two volumes be read at the same
    /// voxel coordinates: labels, a second field, vector components).
    pub fn same_placement(&self, other: &Geometry) -> bool {
        let tolerance = 1e-3 * self.spacing.min_element();
        self.to_world().abs_diff_eq(other.to_world(), tolerance)
    }

    /// Whether the direction matrix is the identity (the grid is axis-aligned, no flips).
    pub fn is_axis_aligned(&self) -> bool {
        self.direction.abs_diff_eq(DMat3::IDENTITY, 1e-9)
    }

    /// Maps a voxel-space gradient (value per voxel step) to the world-space gradient (value
    /// per world unit): `M^{-T} g` for the linear part `M` of the voxel → world transform.
    pub fn gradient_to_world(&self, g_voxel: Vec3) -> Vec3 {
        let m = self.direction * DMat3::from_diagonal(self.spacing);
        (m.inverse().transpose() * g_voxel.as_dvec3()).as_vec3()
    }

    /// World bounding box `[min, max]` of the voxel centres of a grid with `dims` voxels.
    pub fn world_bounds(&self, dims: [u32; 3]) -> [Vec3; 2] {
        let last = DVec3::new(
            dims[0].saturating_sub(1) as f64,
            dims[1].saturating_sub(1) as f64,
            dims[2].saturating_sub(1) as f64,
        );
        let m = self.to_world();
        let mut lo = DVec3::INFINITY;
        let mut hi = DVec3::NEG_INFINITY;
        for c in 0..8 {
            let corner = DVec3::new(
                if c & 1 == 0 { 0.0 } else { last.x },
                if c & 2 == 0 { 0.0 } else { last.y },
                if c & 4 == 0 { 0.0 } else { last.z },
            );
            let p = m.transform_point3(corner);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        [lo.as_vec3(), hi.as_vec3()]
    }

    /// One line for `hatchery info`: the 3×4 affine rows.
    pub fn describe(&self) -> String {
        let m = self.to_world();
        let row = |r: usize| {
            let v = m.row(r);
            // + 0.0 shows −0 as 0.
            format!(
                "[{:.4}, {:.4}, {:.4}, {:.4}]",
                v.x + 0.0,
                v.y + 0.0,
                v.z + 0.0,
                v.w + 0.0
            )
        };
        format!("[{}, {}, {}]", row(0), row(1), row(2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn affine_round_trip_and_lps() {
        // NIfTI LAS example of ../shared/cases/las_blob.nii.
        let g = Geometry::from_affine([
            [-2.0, 0.0, 0.0, 23.0],
            [0.0, 2.0, 0.0, -15.0],
            [0.0, 0.0, 2.0, -15.0],
        ])
        .unwrap();
        assert_eq!(g.spacing, DVec3::splat(2.0));
        assert_eq!(
            g.voxel_to_world(Vec3::new(2.0, 4.0, 4.0)),
            Vec3::new(19.0, -7.0, -7.0)
        );
        let back = g.world_to_voxel(Vec3::new(19.0, -7.0, -7.0));
        assert!((back - Vec3::new(2.0, 4.0, 4.0)).abs().max_element() < 1e-5);
        // Negated zeros (from LPS) read as 0 in `hatchery info`.
        let negated = Geometry::from_affine([
            [0.7, -0.0, 0.0, 8.0],
            [-0.0, -1.3, -0.0, -4.0],
            [0.0, 0.0, -1.0, 15.0],
        ])
        .unwrap();
        assert!(
            !negated.describe().contains("-0.0000"),
            "{}",
            negated.describe()
        );
        // The same grid in LPS: x and y negated.
        let lps = Geometry::from_lps(
            [2.0; 3],
            DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0)),
            [-23.0, 15.0, -15.0],
        );
        assert!(lps.to_world().abs_diff_eq(g.to_world(), 1e-12));
        // Gradients: value = world x on this grid grows by -2 per voxel along i.
        let gw = g.gradient_to_world(Vec3::new(-2.0, 0.0, 0.0));
        assert!((gw - Vec3::X).length() < 1e-6, "{gw}");
        let [lo, hi] = g.world_bounds([24, 16, 16]);
        assert_eq!(lo, Vec3::new(-23.0, -15.0, -15.0));
        assert_eq!(hi, Vec3::new(23.0, 15.0, 15.0));
    }

    #[test]
    fn degenerate_affines_are_refused() {
        assert!(
            Geometry::from_affine([[0.0; 4], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]]).is_err()
        );
        assert!(
            Geometry::from_affine([
                [1.0, 1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0]
            ])
            .is_err()
        );
    }
}
