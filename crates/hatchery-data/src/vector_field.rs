//! Vector fields on a voxel grid (a flow's velocity, a field's curl) and the operators of
//! Svakhine, Jang, Ebert & Gaither 2005, Table 1, that turn one into a scalar field: |U|, ∇·U
//! and |∇×U|. Derivatives are central differences on the grid (one-sided at its border), taken
//! with respect to world coordinates through the voxel → world transform, so a rotated or
//! anisotropic grid gives the same numbers as an axis-aligned one of the same field.
//!
//! Also two procedural fields that are always available, on the [-1, 1]³ grid of
//! [`crate::procedural`]: the Arnold–Beltrami–Childress flow ([`abc_flow`], whose curl is π·U: a
//! known answer) and Rayleigh–Bénard convection rolls ([`convection_rolls`], the flow that
//! [`crate::procedural::convection`]'s temperature belongs to).

use crate::geometry::Geometry;
use crate::{DataError, VolumeData};
use glam::{DMat3, Mat3, Vec3};
use rayon::prelude::*;

/// A 3-component field on a grid: `vectors[i]` is (U_x, U_y, U_z) in world axes at voxel `i`
/// (x fastest). Non-finite components mean "no data" there.
#[derive(Clone, Debug)]
pub struct VectorFieldData {
    pub dims: [u32; 3],
    pub geometry: Geometry,
    pub vectors: Vec<[f32; 3]>,
}

/// A Table 1 operator that makes a scalar field of a vector field.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Operator {
    /// |U| = √(Σ U_i²) (U's units).
    Magnitude,
    /// ∇·U = ∂U_x/∂x + ∂U_y/∂y + ∂U_z/∂z (U's units per world unit).
    Divergence,
    /// |∇×U| (U's units per world unit).
    CurlMagnitude,
}

impl VectorFieldData {
    /// Checks the invariants a [`VolumeData`] has (every dim ≥ 2, one vector per voxel, a
    /// finite invertible transform).
    pub fn new(
        dims: [u32; 3],
        geometry: Geometry,
        vectors: Vec<[f32; 3]>,
    ) -> Result<Self, DataError> {
        let voxels = dims.iter().map(|&d| d as usize).product::<usize>();
        if dims.iter().any(|&d| d < 2) || voxels != vectors.len() {
            return Err(DataError::Invalid(format!(
                "a vector field on {dims:?} voxels needs at least 2 voxels per axis and one \
                 vector per voxel, got {} vectors",
                vectors.len()
            )));
        }
        geometry.check()?;
        Ok(Self {
            dims,
            geometry,
            vectors,
        })
    }

    /// The field whose world x, y and z components are three scalar volumes on one grid.
    ///
    /// Errors: a component lies on another grid (dims or placement) than `x`, naming it.
    pub fn from_components(
        x: &VolumeData,
        y: &VolumeData,
        z: &VolumeData,
    ) -> Result<Self, DataError> {
        for (name, other) in [("y", y), ("z", z)] {
            if other.dims != x.dims || !x.geometry.same_placement(&other.geometry) {
                return Err(DataError::Invalid(format!(
                    "component {name} lies on another grid ({:?} voxels, {}) than component x \
                     ({:?} voxels, {}): resample the components onto one grid",
                    other.dims,
                    other.geometry.describe(),
                    x.dims,
                    x.geometry.describe()
                )));
            }
        }
        let (cx, cy, cz) = (x.values_f32(), y.values_f32(), z.values_f32());
        let vectors = (0..cx.len())
            .into_par_iter()
            .map(|i| [cx[i], cy[i], cz[i]])
            .collect();
        Self::new(x.dims, x.geometry, vectors)
    }

    /// The largest |U| over the finite vectors (0 for none).
    pub fn max_magnitude(&self) -> f32 {
        self.vectors
            .par_iter()
            .map(|v| Vec3::from_array(*v).length())
            .filter(|m| m.is_finite())
            .reduce(|| 0.0, f32::max)
    }

    /// `op` at every voxel, as a scalar volume on the same grid (non-finite where a vector it
    /// needs is "no data").
    pub fn apply(&self, op: Operator) -> Result<VolumeData, DataError> {
        let [nx, ny, _] = self.dims.map(|d| d as usize);
        let to_world = world_derivatives(&self.geometry);
        let values: Vec<f32> = (0..self.vectors.len())
            .into_par_iter()
            .map(|i| {
                let v = Vec3::from_array(self.vectors[i]);
                match op {
                    Operator::Magnitude => v.length(),
                    Operator::Divergence | Operator::CurlMagnitude => {
                        let ijk = [i % nx, (i / nx) % ny, i / (nx * ny)];
                        let j = to_world * self.voxel_jacobian(ijk);
                        // `j` has columns ∇U_x, ∇U_y, ∇U_z: j.col(c)[r] = ∂U_c/∂x_r.
                        let d = |c: usize, r: usize| j.col(c)[r];
                        if op == Operator::Divergence {
                            d(0, 0) + d(1, 1) + d(2, 2)
                        } else {
                            Vec3::new(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1))
                                .length()
                        }
                    }
                }
            })
            .collect();
        VolumeData::with_geometry(self.dims, self.geometry, values)
    }

    /// The voxel-step gradients of the components at voxel `ijk`, by central differences
    /// (one-sided at the border): column c is ∇U_c, i.e. row r, column c is ∂U_c/∂index_r.
    fn voxel_jacobian(&self, ijk: [usize; 3]) -> Mat3 {
        let n = self.dims.map(|d| d as usize);
        let at = |p: [usize; 3]| Vec3::from_array(self.vectors[p[0] + n[0] * (p[1] + n[1] * p[2])]);
        let rows = [0, 1, 2].map(|axis| {
            let (mut lo, mut hi) = (ijk, ijk);
            lo[axis] = ijk[axis].saturating_sub(1);
            hi[axis] = (ijk[axis] + 1).min(n[axis] - 1);
            (at(hi) - at(lo)) / (hi[axis] - lo[axis]) as f32
        });
        Mat3::from_cols(rows[0], rows[1], rows[2]).transpose()
    }
}

/// M^{-T} for the linear part M of the voxel → world transform: it maps a voxel-step gradient
/// to a world one (as [`Geometry::gradient_to_world`]), here applied to all three components'
/// gradients at once.
fn world_derivatives(g: &Geometry) -> Mat3 {
    (g.direction * DMat3::from_diagonal(g.spacing))
        .inverse()
        .transpose()
        .as_mat3()
}

/// The ABC (Arnold–Beltrami–Childress) flow on a `resolution`³ grid over [-1, 1]³:
/// U = (A sin πz + C cos πy, B sin πx + A cos πz, C sin πy + B cos πx). A Beltrami field:
/// ∇×U = π·U and ∇·U = 0 everywhere, so the operators have closed forms.
pub fn abc_flow(resolution: u32, a: f32, b: f32, c: f32) -> Result<VectorFieldData, DataError> {
    use std::f32::consts::PI;
    grid_field(resolution, |p| {
        let (x, y, z) = (PI * p.x, PI * p.y, PI * p.z);
        [
            a * z.sin() + c * y.cos(),
            b * x.sin() + a * z.cos(),
            c * y.sin() + b * x.cos(),
        ]
    })
}

/// The wavenumber along x of [`convection_rolls`]: one period, two counter-rotating rolls, per
/// unit of x, so four rolls across [-1, 1].
pub const ROLL_WAVENUMBER: f32 = 2.0 * std::f32::consts::PI;

/// The amplitude modulation along z of [`convection_rolls`] and of
/// [`crate::procedural::convection`].
pub fn roll_amplitude(z: f32) -> f32 {
    1.0 + 0.3 * (std::f32::consts::PI * z).cos()
}

/// Rayleigh–Bénard convection rolls between a hot floor (y = −1) and a cold lid (y = 1), the
/// subject of Svakhine et al. 2005's Figure 4, on a `resolution`³ grid over [-1, 1]³: the
/// velocity of the stream function ψ = a(z)·sin(k(x + 1))·sin(π(y + 1)/2) in each x–y plane,
/// U = (∂ψ/∂y, −∂ψ/∂x, 0), with k = [`ROLL_WAVENUMBER`] and a(z) = [`roll_amplitude`].
/// Divergence-free; the fluid rises where cos(k(x + 1)) < 0.
pub fn convection_rolls(resolution: u32) -> Result<VectorFieldData, DataError> {
    use std::f32::consts::FRAC_PI_2;
    let k = ROLL_WAVENUMBER;
    grid_field(resolution, |p| {
        let a = roll_amplitude(p.z);
        let (sx, cx) = (k * (p.x + 1.0)).sin_cos();
        let (sy, cy) = (FRAC_PI_2 * (p.y + 1.0)).sin_cos();
        [a * sx * FRAC_PI_2 * cy, -a * k * cx * sy, 0.0]
    })
}

/// `f` at the voxel centres of a `resolution`³ grid spanning [-1, 1]³ (as
/// [`crate::procedural`]'s scalar fields).
fn grid_field(
    resolution: u32,
    f: impl Fn(Vec3) -> [f32; 3] + Sync,
) -> Result<VectorFieldData, DataError> {
    if !(2..=1024).contains(&resolution) {
        return Err(DataError::Invalid(format!(
            "procedural vector field resolution must lie in 2..=1024, got {resolution}"
        )));
    }
    let n = resolution as usize;
    let spacing = 2.0 / (resolution - 1) as f64;
    let coord = |i: usize| (-1.0 + i as f64 * spacing) as f32;
    let vectors = (0..n * n * n)
        .into_par_iter()
        .map(|i| {
            f(Vec3::new(
                coord(i % n),
                coord((i / n) % n),
                coord(i / (n * n)),
            ))
        })
        .collect();
    VectorFieldData::new(
        [resolution; 3],
        Geometry::axis_aligned([spacing; 3], [-1.0; 3]),
        vectors,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A linear field U = A·x + b has ∇·U = trace A and ∇×U from A's antisymmetric part
    /// exactly, on any grid: checked on a rotated, anisotropic one.
    #[test]
    fn operators_of_a_linear_field_are_exact_on_a_rotated_anisotropic_grid() {
        let a = Mat3::from_cols(
            Vec3::new(0.5, -1.0, 2.0),
            Vec3::new(3.0, 0.25, -0.5),
            Vec3::new(-2.0, 1.5, 1.0),
        );
        let b = Vec3::new(0.1, -0.2, 0.3);
        let direction = DMat3::from_rotation_z(0.4) * DMat3::from_rotation_x(-0.7);
        let geometry = Geometry {
            spacing: DVec3::new(0.5, 2.0, 1.25),
            direction,
            origin: DVec3::new(3.0, -1.0, 2.0),
        };
        let dims = [5u32, 4, 6];
        let mut vectors = Vec::new();
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    let p = geometry.voxel_to_world(Vec3::new(i as f32, j as f32, k as f32));
                    vectors.push((a * p + b).to_array());
                }
            }
        }
        let field = VectorFieldData::new(dims, geometry, vectors).unwrap();
        // a.col(c)[r] = ∂U_r/∂x_c.
        let d = |r: usize, c: usize| a.col(c)[r];
        let divergence = d(0, 0) + d(1, 1) + d(2, 2);
        let curl = Vec3::new(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1)).length();
        let div = field.apply(Operator::Divergence).unwrap();
        let rot = field.apply(Operator::CurlMagnitude).unwrap();
        for (got, want) in [(div, divergence), (rot, curl)] {
            for v in got.values_f32().iter() {
                assert!((v - want).abs() < 1e-3, "{v} vs {want}");
            }
        }
    }

    /// The ABC flow: |∇×U| = π·|U| up to the central differences' O(h²) error, ∇·U = 0.
    #[test]
    fn abc_flow_is_a_beltrami_field() {
        let field = abc_flow(48, 1.0, 0.8, 0.6).unwrap();
        let m = field.apply(Operator::Magnitude).unwrap();
        let c = field.apply(Operator::CurlMagnitude).unwrap();
        let d = field.apply(Operator::Divergence).unwrap();
        let (m, c, d) = (m.values_f32(), c.values_f32(), d.values_f32());
        let n = 48usize;
        let mut worst = 0.0f32;
        for z in 1..n - 1 {
            for y in 1..n - 1 {
                for x in 1..n - 1 {
                    let i = x + n * (y + n * z);
                    worst = worst.max((c[i] - std::f32::consts::PI * m[i]).abs());
                    assert!(d[i].abs() < 1e-4, "divergence {} at {i}", d[i]);
                }
            }
        }
        // h = 2/47: the relative error of a central difference of sin is h²π²/6 ≈ 0.3 %.
        assert!(worst < 0.01 * std::f32::consts::PI * 2.4, "worst {worst}");
    }

    #[test]
    fn convection_rolls_are_divergence_free_and_components_must_share_a_grid() {
        let field = convection_rolls(40).unwrap();
        let d = field.apply(Operator::Divergence).unwrap();
        let peak = field.max_magnitude();
        let n = 40usize;
        for z in 1..n - 1 {
            for y in 1..n - 1 {
                for x in 1..n - 1 {
                    let v = d.values_f32()[x + n * (y + n * z)];
                    assert!(v.abs() < 0.05 * peak, "divergence {v} (peak |U| {peak})");
                }
            }
        }
        let one = VolumeData::new([3, 3, 3], [1.0; 3], [0.0; 3], vec![0.0; 27]).unwrap();
        let other = VolumeData::new([3, 3, 3], [2.0, 1.0, 1.0], [0.0; 3], vec![0.0; 27]).unwrap();
        let e = VectorFieldData::from_components(&one, &one, &other).unwrap_err();
        assert!(e.to_string().contains("component z"), "{e}");
        let f = VectorFieldData::from_components(&one, &one, &one).unwrap();
        assert_eq!(f.vectors.len(), 27);
    }
}
