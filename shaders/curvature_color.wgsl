// CurvatureColor: a curvature measure of each pixel (from Curvature's (κ1, κ2, θ1, θ2)) mapped
// through a 1-D transfer function (Hadwiger's curvature colour mapping, the tutorial's §1,
// Fig. 10): κ1, κ2, mean (κ1 + κ2)/2, Gaussian κ1·κ2, or curvedness √(κ1² + κ2²); or both
// principal curvatures through a 2-D transfer function (the tutorial's (κ1, κ2) map): texel
// (i, j) of the W×H map holds the colour of κ1 = −r + 2r·i/(W−1) (left to right) and
// κ2 = r − 2r·j/(H−1) (top to bottom), r = `range`, bilinear between texels, clamped at the
// edges. Output premultiplied; nothing where there is no surface.

@group(0) @binding(0) var curvature: texture_2d<f32>;
// 256×1: colour and opacity of the transfer function (the LUT of TransferFunction1D).
@group(0) @binding(1) var lut: texture_2d<f32>;
// The 2-D (κ1, κ2) map, straight RGBA (measure 5 only).
@group(0) @binding(2) var map2d: texture_2d<f32>;

struct CurvatureColor {
    // x = measure (0 κ1, 1 κ2, 2 mean, 3 Gaussian, 4 curvedness, 5 the 2-D map); y, z = TF
    // domain lo, hi; w = the 2-D map's range r (world units⁻¹).
    options: vec4<f32>,
};
@group(0) @binding(3) var<uniform> params: CurvatureColor;

// The 2-D map's colour of (κ1, κ2).
fn map_colour(k: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(map2d));
    let r = max(params.options.w, 1e-12);
    let uv = clamp(
        vec2<f32>((k.x + r) / (2.0 * r), (r - k.y) / (2.0 * r)),
        vec2<f32>(0.0),
        vec2<f32>(1.0),
    ) * (size - 1.0);
    let base = min(floor(uv), max(size - 2.0, vec2<f32>(0.0)));
    let f = uv - base;
    let b = vec2<i32>(base);
    let last = vec2<i32>(size) - 1;
    let t00 = textureLoad(map2d, min(b, last), 0);
    let t10 = textureLoad(map2d, min(b + vec2<i32>(1, 0), last), 0);
    let t01 = textureLoad(map2d, min(b + vec2<i32>(0, 1), last), 0);
    let t11 = textureLoad(map2d, min(b + vec2<i32>(1, 1), last), 0);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

fn measure(k: vec2<f32>) -> f32 {
    let m = i32(params.options.x + 0.5);
    if m == 0 {
        return k.x;
    }
    if m == 1 {
        return k.y;
    }
    if m == 2 {
        return 0.5 * (k.x + k.y);
    }
    if m == 3 {
        return k.x * k.y;
    }
    return length(k);
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let c = textureLoad(curvature, pixel_of(in.position), 0);
    if c.z < -5.0 {
        return vec4<f32>(0.0);
    }
    if i32(params.options.x + 0.5) == 5 {
        let entry = map_colour(c.xy);
        return vec4<f32>(entry.rgb * entry.a, entry.a);
    }
    let span = params.options.z - params.options.y;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((measure(c.xy) - params.options.y) / span, 0.0, 1.0);
    }
    // The LUT rule of TransferFunction1D::lookup.
    let x = u * 255.0;
    let k = min(floor(x), 254.0);
    let entry = mix(textureLoad(lut, vec2<i32>(i32(k), 0), 0), textureLoad(lut, vec2<i32>(i32(k) + 1, 0), 0), x - k);
    return vec4<f32>(entry.rgb * entry.a, entry.a);
}
