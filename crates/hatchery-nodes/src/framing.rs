//! Framing the data (issue 25): where an orbit camera must stand so that given world points
//! (the corners of a volume's grid, of a label map's objects, of a mesh's bounds) fill a chosen
//! fraction of the frame from its azimuth and elevation, so a preset frames any data the way it
//! frames its own.

use glam::Vec3;

/// The orbit of [`crate::camera::Camera::orbit`] for `azimuth`/`elevation` (degrees): the unit
/// vector from the target to the eye, and the world up vector of the view. With `up_z`,
/// elevation is measured from the xy plane and azimuth 0 looks along -y (medical RAS data);
/// otherwise azimuth 0, elevation 0 looks along -z with +y up. Looking straight along the up
/// axis, another up is picked so the view stays defined.
pub fn orbit_basis(azimuth_deg: f32, elevation_deg: f32, up_z: bool) -> (Vec3, Vec3) {
    let (az, el) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    let (offset, up) = if up_z {
        (
            Vec3::new(az.sin() * el.cos(), -az.cos() * el.cos(), el.sin()),
            Vec3::Z,
        )
    } else {
        (
            Vec3::new(az.sin() * el.cos(), el.sin(), az.cos() * el.cos()),
            Vec3::Y,
        )
    };
    let up = if offset.cross(up).length_squared() < 1e-8 {
        if up_z { Vec3::Y } else { -Vec3::Z }
    } else {
        up
    };
    (offset, up)
}

/// How a camera frames a set of points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Framing {
    /// The point looked at: the points' bounding-box centre, shifted by the pan.
    pub target: Vec3,
    /// Eye distance from the target (world units).
    pub distance: f32,
    /// Orthographic views: the distance whose 2·d·tan(fov/2) spans the frame's shorter side
    /// (the extent); perspective views: equal to `distance`.
    pub extent_distance: f32,
    pub near: f32,
    pub far: f32,
}

/// The view from `azimuth`/`elevation` in which `points` fill `fill` (0–1] of the frame: the
/// projection of every point lies within `fill` of the half-width and half-height, and one
/// touches that bound. `fov_deg` spans the frame's shorter side (as the Camera node's `fov`),
/// `aspect` is width / height. `pan` shifts the target by fractions of the frame's shorter
/// side (x right, y up), so the data moves the other way on screen. `clip` is the camera's
/// own (near, far, distance): near and far scale with the framed distance (so window depths,
/// which Silhouette's thresholds read, spread as they did for the camera's own data, at any
/// scale), widened where needed to enclose the points' bounding sphere. `None` without points
/// or with non-finite ones.
#[allow(clippy::too_many_arguments)]
pub fn frame_points(
    points: &[Vec3],
    azimuth_deg: f32,
    elevation_deg: f32,
    up_z: bool,
    fov_deg: f32,
    aspect: f32,
    orthographic: bool,
    fill: f32,
    pan: [f32; 2],
    clip: (f32, f32, f32),
) -> Option<Framing> {
    if points.is_empty() || points.iter().any(|p| !p.is_finite()) {
        return None;
    }
    let (lo, hi) = points
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let centre = (lo + hi) * 0.5;
    let (toward_eye, world_up) = orbit_basis(azimuth_deg, elevation_deg, up_z);
    // The screen's right and up directions in the world.
    let right = (-toward_eye).cross(world_up).normalize();
    let up = right.cross(-toward_eye);
    let half_short = (fov_deg.to_radians() / 2.0).tan();
    let (tx, ty) = if aspect >= 1.0 {
        (half_short * aspect, half_short)
    } else {
        (half_short, half_short / aspect)
    };
    let fill = fill.clamp(1e-3, 20.0);
    let radius = points
        .iter()
        .map(|p| (*p - centre).length())
        .fold(0.0f32, f32::max)
        .max(1e-6);
    // Perspective: a point at depth z (towards the eye) and offsets x, y projects inside the
    // filled part when d − z ≥ |x| / (fill·tx) and ≥ |y| / (fill·ty).
    // Orthographic: the half-height must cover |y| / fill and |x| / (fill·aspect).
    let mut need = 0.0f32;
    for p in points {
        let q = *p - centre;
        let (x, y, z) = (q.dot(right).abs(), q.dot(up).abs(), q.dot(toward_eye));
        let lateral = (x / (fill * tx)).max(y / (fill * ty));
        need = need.max(if orthographic { lateral } else { z + lateral });
    }
    let need = need.max(radius * 1e-3);
    let (distance, extent_distance) = if orthographic {
        // The eye stands outside the bounding sphere; the extent comes from `need`.
        (need.max(2.0 * radius), need)
    } else {
        (need, need)
    };
    let across = 2.0 * extent_distance * half_short;
    let target = centre + right * (pan[0] * across) + up * (pan[1] * across);
    let margin = radius * 1.05;
    let (near0, far0, distance0) = clip;
    let scale = distance / distance0.max(1e-12);
    let near = (near0 * scale).min(distance - margin).max(distance * 1e-4);
    let far = (far0 * scale).max(distance + margin + (target - centre).length());
    Some(Framing {
        target,
        distance,
        extent_distance,
        near,
        far,
    })
}

/// Edge of the voxel blocks whose occupancy approximates a volume's shape for framing.
const BLOCK: u32 = 4;

/// Points outlining where a grid holds something, in world space: the centres of the 4³-voxel
/// blocks that hold at least one voxel for which `occupied(index)` holds (index =
/// x + nx·(y + ny·z)) and touch an empty block or the grid's edge. The data's outline within
/// two voxels, few enough points to project from every view. Empty when nothing is occupied.
pub fn occupied_block_outline(
    dims: [u32; 3],
    geometry: &hatchery_data::geometry::Geometry,
    occupied: impl Fn(usize) -> bool + Sync,
) -> Vec<Vec3> {
    use rayon::prelude::*;
    let [nx, ny, nz] = dims;
    let b = dims.map(|d| d.div_ceil(BLOCK));
    // One row of blocks per (block y, block z), filled in parallel.
    let blocks: Vec<bool> = (0..b[1] * b[2])
        .into_par_iter()
        .flat_map_iter(|row| {
            let (by, bz) = (row % b[1], row / b[1]);
            let mut hit = vec![false; b[0] as usize];
            for z in bz * BLOCK..((bz + 1) * BLOCK).min(nz) {
                for y in by * BLOCK..((by + 1) * BLOCK).min(ny) {
                    let base = (nx as usize) * (y as usize + ny as usize * z as usize);
                    for x in 0..nx {
                        let h = &mut hit[(x / BLOCK) as usize];
                        if !*h && occupied(base + x as usize) {
                            *h = true;
                        }
                    }
                }
            }
            hit
        })
        .collect();
    let at = |x: i64, y: i64, z: i64| {
        let inside = (0..b[0] as i64).contains(&x)
            && (0..b[1] as i64).contains(&y)
            && (0..b[2] as i64).contains(&z);
        inside && blocks[(x + b[0] as i64 * (y + b[1] as i64 * z)) as usize]
    };
    let last = Vec3::new((nx - 1) as f32, (ny - 1) as f32, (nz - 1) as f32);
    let mut points = Vec::new();
    for (i, _) in blocks.iter().enumerate().filter(|(_, h)| **h) {
        let i = i as i64;
        let (x, y, z) = (
            i % b[0] as i64,
            (i / b[0] as i64) % b[1] as i64,
            i / (b[0] * b[1]) as i64,
        );
        let inner = [
            (1, 0, 0),
            (-1, 0, 0),
            (0, 1, 0),
            (0, -1, 0),
            (0, 0, 1),
            (0, 0, -1),
        ]
        .iter()
        .all(|(dx, dy, dz)| at(x + dx, y + dy, z + dz));
        if !inner {
            let lo = Vec3::new(x as f32, y as f32, z as f32) * BLOCK as f32;
            let centre = ((lo + (lo + Vec3::splat(BLOCK as f32 - 1.0)).min(last)) * 0.5).min(last);
            points.push(geometry.voxel_to_world(centre));
        }
    }
    points
}

/// At most `limit` of `points`, evenly strided (a mesh's vertices for framing).
pub fn strided(points: &[[f32; 3]], limit: usize) -> Vec<Vec3> {
    let step = points.len().div_ceil(limit.max(1)).max(1);
    points
        .iter()
        .step_by(step)
        .map(|p| Vec3::from(*p))
        .collect()
}

/// The 8 corners of the box `[lo, hi]`.
pub fn box_corners(lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    std::array::from_fn(|c| {
        Vec3::new(
            if c & 1 == 0 { lo.x } else { hi.x },
            if c & 2 == 0 { lo.y } else { hi.y },
            if c & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera;

    /// Projects `p` with `camera` to NDC x, y.
    fn ndc(camera: &Camera, p: Vec3) -> (f32, f32) {
        let c = camera.view_proj() * p.extend(1.0);
        (c.x / c.w, c.y / c.w)
    }

    fn camera_for(points: &[Vec3], ortho: bool, aspect: f32, az: f32, el: f32) -> Camera {
        let f = frame_points(
            points,
            az,
            el,
            true,
            40.0,
            aspect,
            ortho,
            0.8,
            [0.0, 0.0],
            (10.0, 2000.0, 330.0),
        )
        .unwrap();
        let (w, h) = ((100.0 * aspect) as u32, 100);
        let mut cam = Camera::orbit(
            f.target, az, el, f.distance, 40.0, ortho, f.near, f.far, true, w, h,
        );
        if ortho {
            cam = cam.with_orthographic_extent(f.extent_distance, 40.0);
        }
        cam
    }

    #[test]
    fn framed_points_fill_the_chosen_fraction_and_stay_inside() {
        // An off-centre, anisotropic box (a head of 140 × 180 × 160 mm somewhere in scanner space).
        let corners = box_corners(
            Vec3::new(-300.0, 40.0, 10.0),
            Vec3::new(-160.0, 220.0, 170.0),
        );
        for ortho in [false, true] {
            for (aspect, az, el) in [(1.333, -60.0, 20.0), (0.6, 30.0, -10.0), (2.0, 180.0, 60.0)] {
                let cam = camera_for(&corners, ortho, aspect, az, el);
                let extent = corners.iter().map(|p| {
                    let (x, y) = ndc(&cam, *p);
                    x.abs().max(y.abs())
                });
                let max = extent.fold(0.0f32, f32::max);
                assert!(
                    (max - 0.8).abs() < 1e-3,
                    "ortho {ortho}, aspect {aspect}, az {az}: reaches {max} of the frame, want 0.8"
                );
                // Every corner lies between near and far.
                for p in &corners {
                    let depth = (cam.view * p.extend(1.0)).z;
                    assert!(
                        -depth > cam.near && -depth < cam.far,
                        "{p} outside near/far"
                    );
                }
            }
        }
    }

    const CLIP: (f32, f32, f32) = (0.05, 100.0, 3.5);

    /// A perspective view (40°, up y) of a square frame, the data filling 0.8 of it.
    fn square_view(
        points: &[Vec3],
        az: f32,
        el: f32,
        pan: [f32; 2],
        clip: (f32, f32, f32),
    ) -> Option<Framing> {
        frame_points(points, az, el, false, 40.0, 1.0, false, 0.8, pan, clip)
    }

    #[test]
    fn near_and_far_scale_with_the_framed_distance_and_enclose_the_data() {
        let corners = box_corners(Vec3::splat(-10.0), Vec3::splat(10.0));
        let f = square_view(&corners, 30.0, 20.0, [0.0; 2], (5.0, 400.0, 100.0)).unwrap();
        let s = f.distance / 100.0;
        assert!(
            (f.near - 5.0 * s).abs() < 1e-3 && (f.far - 400.0 * s).abs() < 1e-2,
            "{f:?}"
        );
        // A camera whose near plane would cut into the data is widened to enclose it.
        let g = square_view(&corners, 30.0, 20.0, [0.0; 2], (90.0, 110.0, 100.0)).unwrap();
        let r = 10.0 * 3f32.sqrt();
        assert!(g.near < g.distance - r && g.far > g.distance + r, "{g:?}");
    }

    #[test]
    fn panning_moves_the_target_by_fractions_of_the_frame() {
        let corners = box_corners(Vec3::splat(-1.0), Vec3::splat(1.0));
        let f0 = square_view(&corners, 0.0, 0.0, [0.0, 0.0], CLIP).unwrap();
        let f1 = square_view(&corners, 0.0, 0.0, [0.25, 0.0], CLIP).unwrap();
        let across = 2.0 * f0.distance * (20.0f32).to_radians().tan();
        // Azimuth 0, elevation 0, up y: screen right is world +x.
        assert!((f1.target - Vec3::new(0.25 * across, 0.0, 0.0)).length() < 1e-4);
        assert!(square_view(&[], 0.0, 0.0, [0.0; 2], CLIP).is_none());
    }
}
