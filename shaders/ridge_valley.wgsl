// RidgeValley: ridge and valley lines of an iso-surface from Curvature's (κ1, κ2, θ1, θ2) image
// (the tutorial's §1, Fig. 12; Hadwiger's curvature-based lines). A ridge is where the first
// principal curvature κ1 exceeds `threshold` and is a maximum along its own principal direction
// (θ1 on screen); a valley where κ2 is below −`threshold` and a minimum along the second
// direction (θ2). The extremality test fits a parabola through the curvature one pixel before,
// at and after the pixel along the direction on screen and needs a clear maximum (the parabola's
// curvature beyond 1 % of the value: constant curvature, as around a torus's tube, is no line);
// the line's coverage is `thickness`/2 + ½ − |offset of the extremum| (pixels), clamped to [0, 1]
// (lines up to 3 px wide: the extremum must lie within a pixel).
// Output: a mask (1 on the line).

@group(0) @binding(0) var curvature: texture_2d<f32>;

struct RidgeValley {
    // Smallest |κ| of a line (world units⁻¹).
    threshold: f32,
    // Line thickness (pixels).
    thickness: f32,
    // 0 for ridges, 1 for valleys.
    valleys: u32,
    pad0: f32,
};
@group(0) @binding(1) var<uniform> params: RidgeValley;

// The curvature that makes the line (κ1 for ridges, −κ2 for valleys: both maxima), bilinearly
// interpolated at pixel position p (pixel centres at .5); −1e30 off the surface.
fn key_at(p: vec2<f32>) -> f32 {
    let q = p - 0.5;
    let base = vec2<i32>(floor(q));
    let f = q - floor(q);
    var value = 0.0;
    for (var c = 0; c < 4; c++) {
        let o = vec2<i32>(c & 1, c >> 1u);
        let t = load_clamped(curvature, base + o);
        if t.z < -5.0 {
            return -1e30;
        }
        let w = select(1.0 - f, f, vec2<bool>(o == vec2<i32>(1)));
        var k = t.x;
        if params.valleys != 0u {
            k = -t.y;
        }
        value += w.x * w.y * k;
    }
    return value;
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let pixel = pixel_of(in.position);
    let here = textureLoad(curvature, pixel, 0);
    if here.z < -5.0 {
        return vec4<f32>(0.0);
    }
    var theta = here.z;
    if params.valleys != 0u {
        theta = here.w;
    }
    let d = vec2<f32>(cos(theta), sin(theta));
    let p = in.position.xy;
    let k0 = key_at(p);
    let km = key_at(p - d);
    let kp = key_at(p + d);
    if k0 < params.threshold || km <= -1e29 || kp <= -1e29 {
        return vec4<f32>(0.0);
    }
    // Parabola through (−1, km), (0, k0), (1, kp): a maximum needs negative curvature.
    let a = 0.5 * (km + kp) - k0;
    if a >= -0.01 * max(abs(k0), params.threshold) {
        return vec4<f32>(0.0);
    }
    let offset = 0.25 * (km - kp) / a;
    if abs(offset) > 1.0 {
        return vec4<f32>(0.0);
    }
    let coverage = clamp(0.5 * params.thickness + 0.5 - abs(offset), 0.0, 1.0);
    return vec4<f32>(coverage, 0.0, 0.0, 0.0);
}
