//! CPU reference of the tricubic B-spline reconstruction (Hadwiger et al., tutorial §1.3 "Filter
//! kernel considerations"): values, gradients and Hessians by direct convolution of the 4×4×4
//! voxels around a point with the cubic B-spline and its first and second derivatives — the
//! definition, where shaders/ray_bspline.wgsl takes 8 trilinear fetches per value (Sigg &
//! Hadwiger). The data is extended by clamping at the grid's faces and the point is clamped to
//! the box of voxel centres first, as the shader does.

#![allow(dead_code)]

use glam::{Mat3, Vec3};
use hatchery_data::VolumeData;

/// The cubic B-spline's weights of voxels `i−1, i, i+1, i+2` at fraction `a ∈ [0, 1]`.
pub fn weights(a: f32) -> [f32; 4] {
    let b = 1.0 - a;
    [
        b * b * b / 6.0,
        (3.0 * a * a * a - 6.0 * a * a + 4.0) / 6.0,
        (-3.0 * a * a * a + 3.0 * a * a + 3.0 * a + 1.0) / 6.0,
        a * a * a / 6.0,
    ]
}

/// Their first derivatives with respect to `a`.
pub fn first_weights(a: f32) -> [f32; 4] {
    let b = 1.0 - a;
    [
        -0.5 * b * b,
        1.5 * a * a - 2.0 * a,
        -1.5 * a * a + a + 0.5,
        0.5 * a * a,
    ]
}

/// Their second derivatives.
pub fn second_weights(a: f32) -> [f32; 4] {
    [1.0 - a, 3.0 * a - 2.0, 1.0 - 3.0 * a, a]
}

/// Value, gradient and Hessian of the B-spline at voxel-space `q`, in data units and voxel
/// coordinates (no spacing or orientation applied). `None` where one of the 64 voxels is not
/// finite ("no data": the GPU falls back to the trilinear filter there).
#[derive(Clone, Copy, Debug)]
pub struct Derivatives {
    pub value: f32,
    pub gradient: Vec3,
    pub hessian: Mat3,
}

pub fn derivatives(volume: &VolumeData, q: Vec3) -> Option<Derivatives> {
    let top = Vec3::new(
        (volume.dims[0] - 1) as f32,
        (volume.dims[1] - 1) as f32,
        (volume.dims[2] - 1) as f32,
    );
    let p = q.clamp(Vec3::ZERO, top);
    let i = p.floor();
    let a = p - i;
    let (w, d, s) = (
        [weights(a.x), weights(a.y), weights(a.z)],
        [first_weights(a.x), first_weights(a.y), first_weights(a.z)],
        [
            second_weights(a.x),
            second_weights(a.y),
            second_weights(a.z),
        ],
    );
    let index = |axis: usize, k: usize| -> u32 {
        (i[axis] as i64 - 1 + k as i64).clamp(0, volume.dims[axis] as i64 - 1) as u32
    };
    let (mut value, mut gradient) = (0.0f64, [0.0f64; 3]);
    let mut h = [[0.0f64; 3]; 3];
    for z in 0..4 {
        for y in 0..4 {
            for x in 0..4 {
                let v = volume.value(index(0, x), index(1, y), index(2, z));
                if !v.is_finite() {
                    return None;
                }
                let v = f64::from(v);
                let k = [x, y, z];
                // The weight of this voxel with the derivative orders `order` per axis.
                let weight = |order: [u8; 3]| -> f64 {
                    (0..3)
                        .map(|axis| {
                            let table = match order[axis] {
                                0 => &w[axis],
                                1 => &d[axis],
                                _ => &s[axis],
                            };
                            f64::from(table[k[axis]])
                        })
                        .product()
                };
                value += weight([0, 0, 0]) * v;
                for axis in 0..3 {
                    let mut order = [0u8; 3];
                    order[axis] = 1;
                    gradient[axis] += weight(order) * v;
                    for other in 0..3 {
                        let mut order = [0u8; 3];
                        order[axis] += 1;
                        order[other] += 1;
                        h[axis][other] += weight(order) * v;
                    }
                }
            }
        }
    }
    let column = |c: usize| Vec3::new(h[0][c] as f32, h[1][c] as f32, h[2][c] as f32);
    Some(Derivatives {
        value: value as f32,
        gradient: Vec3::new(gradient[0] as f32, gradient[1] as f32, gradient[2] as f32),
        hessian: Mat3::from_cols(column(0), column(1), column(2)),
    })
}

/// The B-spline's value at voxel-space `q`, or the trilinear one next to "no data".
pub fn value(volume: &VolumeData, q: Vec3) -> f32 {
    derivatives(volume, q).map_or_else(|| volume.sample_trilinear(q), |d| d.value)
}

/// The B-spline's world-space gradient at voxel-space `q` (per world unit), or central
/// differences next to "no data".
pub fn gradient(volume: &VolumeData, q: Vec3) -> Vec3 {
    match derivatives(volume, q) {
        Some(d) => volume.geometry.gradient_to_world(d.gradient),
        None => volume.gradient(q),
    }
}
