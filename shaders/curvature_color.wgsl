// CurvatureColor: a curvature measure of each pixel (from Curvature's (κ1, κ2, θ1, θ2)) mapped
// through a 1-D transfer function (Hadwiger's curvature colour mapping, the tutorial's §1,
// Fig. 10): κ1, κ2, mean (κ1 + κ2)/2, Gaussian κ1·κ2, or curvedness √(κ1² + κ2²). Output
// premultiplied; nothing where there is no surface.

@group(0) @binding(0) var curvature: texture_2d<f32>;
// 256×1: colour and opacity of the transfer function (the LUT of TransferFunction1D).
@group(0) @binding(1) var lut: texture_2d<f32>;

struct CurvatureColor {
    // x = measure (0 κ1, 1 κ2, 2 mean, 3 Gaussian, 4 curvedness); y, z = TF domain lo, hi.
    options: vec4<f32>,
};
@group(0) @binding(2) var<uniform> params: CurvatureColor;

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
