// Procedural halftoning (Fischer et al. 2005, §3.3.2, after Strothotte & Schlechtweg): the pixel
// (x, y) is rotated by theta (eq. 7), mapped to dither coordinates (s, t) in a cell of n pixels,
// and the intensity compared with the threshold tau(s, t) (eq. 8–9).

struct Halftone {
    // x = theta in radians, y = cell size n in pixels, z = c_cross.
    params: vec4<f32>,
};

@group(0) @binding(0) var intensity: texture_2d<f32>;
@group(0) @binding(1) var<uniform> halftone: Halftone;

fn wrap(v: f32, n: f32) -> f32 {
    return (v - n * floor(v / n)) / n;
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let theta = halftone.params.x;
    let n = halftone.params.y;
    let c_cross = halftone.params.z;
    let x = f32(p.x);
    let y = f32(p.y);
    let xr = cos(theta) * x - sin(theta) * y;
    let yr = sin(theta) * x + cos(theta) * y;
    let s = wrap(xr, n);
    let t = wrap(yr, n);
    var tau = (1.0 - c_cross) * s + c_cross;
    if s <= c_cross {
        tau = c_cross * t;
    }
    let i = textureLoad(intensity, p, 0).r;
    return vec4<f32>(select(0.0, 1.0, i >= tau), 0.0, 0.0, 1.0);
}
