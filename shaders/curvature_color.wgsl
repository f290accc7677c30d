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
    // The measure (a MEASURE_* constant).
    measure: u32,
    // The 2-D map's range r (world units⁻¹).
    map_range: f32,
    // The transfer function's domain (lo, hi).
    domain: vec2<f32>,
};

// CurvatureColor.measure (hatchery_nodes::curvature_color::Measure).
const MEASURE_CURVEDNESS: u32 = 0u;
const MEASURE_K1: u32 = 1u;
const MEASURE_K2: u32 = 2u;
const MEASURE_MEAN: u32 = 3u;
const MEASURE_GAUSSIAN: u32 = 4u;
const MEASURE_K1_K2: u32 = 5u;
@group(0) @binding(3) var<uniform> params: CurvatureColor;

// The 2-D map's colour of (κ1, κ2).
fn map_colour(k: vec2<f32>) -> vec4<f32> {
    let size = vec2<f32>(textureDimensions(map2d));
    let r = max(params.map_range, 1e-12);
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
    let m = params.measure;
    if m == MEASURE_K1 {
        return k.x;
    }
    if m == MEASURE_K2 {
        return k.y;
    }
    if m == MEASURE_MEAN {
        return 0.5 * (k.x + k.y);
    }
    if m == MEASURE_GAUSSIAN {
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
    if params.measure == MEASURE_K1_K2 {
        let entry = map_colour(c.xy);
        return vec4<f32>(entry.rgb * entry.a, entry.a);
    }
    let span = params.domain.y - params.domain.x;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((measure(c.xy) - params.domain.x) / span, 0.0, 1.0);
    }
    // The LUT rule of TransferFunction1D::lookup.
    let x = u * 255.0;
    let k = min(floor(x), 254.0);
    let entry = mix(textureLoad(lut, vec2<i32>(i32(k), 0), 0), textureLoad(lut, vec2<i32>(i32(k) + 1, 0), 0), x - k);
    return vec4<f32>(entry.rgb * entry.a, entry.a);
}
