// Empty-space skipping (hatchery_data::bricks): each 8³-voxel brick's value range, and which
// values the transfer function shows. A skipped brick is left at the first sample past it on
// the ray's own lattice of t, so the samples taken are exactly those taken without skipping.

// [min, max] of the values trilinear samples can take in the brick holding voxel-space q.
fn brick_range(q: vec3<f32>) -> vec2<f32> {
    let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims - 1.0) / f32(ray.brick_size)));
    return textureLoad(bricks, brick, 0).xy;
}

// Whether no value in `range` is visible under any row of the transfer function. A brick of
// only the lowest value (range.y = lo, see hatchery_data::bricks) asks the table's last entry:
// whether that value itself is visible, which its bin can overstate.
fn range_is_invisible(range: vec2<f32>) -> bool {
    let lo = ray.value_range.x;
    if range.y <= lo {
        return textureLoad(visibility, vec2<i32>(i32(ray.visibility_bins), 0), 0).r == 0.0;
    }
    let span = max(ray.value_range.y - lo, 1e-30);
    let last = i32(ray.visibility_bins) - 1;
    let a = clamp(i32(floor((range.x - lo) / span * f32(ray.visibility_bins))), 0, last);
    let b = clamp(i32(floor((range.y - lo) / span * f32(ray.visibility_bins))), 0, last);
    var before = 0.0;
    if a > 0 {
        before = textureLoad(visibility, vec2<i32>(a - 1, 0), 0).r;
    }
    return textureLoad(visibility, vec2<i32>(b, 0), 0).r - before == 0.0;
}

// The ray parameter where the ray leaves the brick holding q (q = q0 + dq·t).
fn brick_exit(q: vec3<f32>, dq: vec3<f32>, t: f32) -> f32 {
    let brick = floor(clamp(q, vec3<f32>(0.0), ray.dims - 1.0) / f32(ray.brick_size));
    var exit = 1e30;
    for (var axis = 0; axis < 3; axis++) {
        if dq[axis] > 1e-12 {
            exit = min(exit, t + ((brick[axis] + 1.0) * f32(ray.brick_size) - q[axis]) / dq[axis]);
        } else if dq[axis] < -1e-12 {
            exit = min(exit, t + (brick[axis] * f32(ray.brick_size) - q[axis]) / dq[axis]);
        }
    }
    return exit;
}

