// Depth darkening: unsharp masking of the depth buffer (Luft, Colditz & Deussen 2006). The
// difference between the blurred and the true eye distance, ΔD = G∗D − D, is negative where a
// pixel lies behind its surroundings; there the picture is darkened by black of opacity
// min(−λ·ΔD, strongest), which sets nested structures apart and puts a soft shadow behind
// every silhouette. Set near and far to the camera's clipping planes.

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var gbuffer: texture_depth_2d;

struct Params {
    lambda: f32, // default = 0.08, range = 0..1, darkening per unit of depth difference, λ
    sigma: f32, // default = 6, range = 1..24, Gaussian σ of the blur, in pixels
    strongest: f32, // default = 0.7, range = 0..1, the darkest shadow's opacity
    near: f32, // default = 0.1, range = 0.001..1000, the camera's near plane (world units)
    far: f32, // default = 100, range = 1..100000, the camera's far plane (world units)
}
@group(0) @binding(2) var<uniform> params: Params;

// Window depth (0 at near, 1 at far) → distance along the view axis.
fn eye_distance(d: f32) -> f32 {
    return params.near * params.far / (params.far - d * (params.far - params.near));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(floor(position.xy));
    let size = vec2<i32>(textureDimensions(gbuffer));
    let depth = eye_distance(textureLoad(gbuffer, p, 0));
    // G∗D on a 9×9 grid of taps spanning ±2σ (a sparse Gaussian: cheap at any σ).
    var sum = 0.0;
    var weight = 0.0;
    let spacing = params.sigma * 0.5;
    for (var j = -4; j <= 4; j++) {
        for (var i = -4; i <= 4; i++) {
            let offset = vec2<f32>(f32(i), f32(j)) * spacing;
            let q = clamp(p + vec2<i32>(round(offset)), vec2<i32>(0), size - 1);
            let w = exp(-dot(offset, offset) / (2.0 * params.sigma * params.sigma));
            sum += w * eye_distance(textureLoad(gbuffer, q, 0));
            weight += w;
        }
    }
    let delta = sum / weight - depth;
    let shadow = clamp(-params.lambda * delta, 0.0, params.strongest);
    // Black of opacity `shadow` over the (premultiplied) picture.
    let colour = textureLoad(image, p, 0);
    return vec4<f32>(colour.rgb * (1.0 - shadow), shadow + (1.0 - shadow) * colour.a);
}
