// Procedural halftoning (Fischer et al. 2005, §3.3.2, after Strothotte & Schlechtweg): the pixel
// (x, y) is rotated by theta (eq. 7), mapped to dither coordinates (s, t) in a cell of n pixels,
// and the intensity compared with the threshold tau(s, t) (eq. 8–9).
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

struct Halftone {
    // The screen angle θ in radians, the cell size n in pixels, c_cross (eq. 8).
    theta: f32,
    cell: f32,
    c_cross: f32,
    // cos θ and sin θ: computed once, not per pixel.
    cos_theta: f32,
    sin_theta: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
};

fn halftone_wrap(v: f32, n: f32) -> f32 {
    return (v - n * floor(v / n)) / n;
}

// 1 (paper) where the intensity at p reaches the screen's threshold, 0 (ink) elsewhere.
fn halftone(p: vec2<i32>, u: Halftone, intensity: vec4<f32>) -> vec4<f32> {
    let n = u.cell;
    let c_cross = u.c_cross;
    let x = f32(p.x);
    let y = f32(p.y);
    let c = u.cos_theta;
    let s_theta = u.sin_theta;
    let xr = c * x - s_theta * y;
    let yr = s_theta * x + c * y;
    let s = halftone_wrap(xr, n);
    let t = halftone_wrap(yr, n);
    var tau = (1.0 - c_cross) * s + c_cross;
    if s <= c_cross {
        tau = c_cross * t;
    }
    return vec4<f32>(select(0.0, 1.0, intensity.r >= tau), 0.0, 0.0, 1.0);
}
