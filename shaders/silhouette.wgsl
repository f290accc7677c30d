// Image-space silhouettes (Fischer et al. 2005, §3.3.1): a Sobel depth-gradient magnitude against
// depth_threshold (eq. 3), the sum of the dot products with the four neighbour normals against
// normal_threshold (eq. 4–5), OR of the two. Optionally with procedurally perturbed sampling
// positions (PIP, Yuan & Chen 2005, eq. 2): every tap at offset (s, t) is read at
// (x + s·P(x, y), y + t·P(x, y)).

struct Silhouette {
    // x = depth threshold, y = normal threshold, z = use depth, w = use normals (z, w: unless
    // the pipeline constants below say).
    thresholds: vec4<f32>,
    // x = mode (unless PIP_MODE says), y = amount, z = pattern scale in pixels, w = seed.
    pip: vec4<f32>,
};

// The mode and the switches as pipeline constants, one pipeline per combination: folded by
// the compiler, they cost nothing per pixel (as uniforms, every mode's code stayed in the pass:
// about twice the time on lavapipe). PIP_MODE: 0 none, 1 constant, 2 texture, 3 noise, 4 dots;
// switches 0 or 1. The default −1 reads the uniform's value instead (an unspecialised pipeline).
override PIP_MODE: f32 = -1.0;
override USE_DEPTH: f32 = -1.0;
override USE_NORMALS: f32 = -1.0;

// A pipeline constant, or the uniform's value where it is left at −1.
fn constant_or(value: f32, uniform: f32) -> f32 {
    return select(uniform, value, value >= 0.0);
}

@group(0) @binding(0) var layer_depth: texture_depth_2d;
@group(0) @binding(1) var layer_normal: texture_2d<f32>;
@group(0) @binding(2) var pattern: texture_2d<f32>;
@group(0) @binding(3) var<uniform> silhouette: Silhouette;

// Bilinear read at a fractional pixel position (taps at integer positions are exact).
fn depth_at(q: vec2<f32>) -> f32 {
    let base = floor(q);
    let f = q - base;
    let p = vec2<i32>(base);
    let top = mix(load_depth_clamped(layer_depth, p), load_depth_clamped(layer_depth, p + vec2<i32>(1, 0)), f.x);
    let bottom = mix(load_depth_clamped(layer_depth, p + vec2<i32>(0, 1)), load_depth_clamped(layer_depth, p + vec2<i32>(1, 1)), f.x);
    return mix(top, bottom, f.y);
}

fn normal_at(q: vec2<f32>) -> vec3<f32> {
    let base = floor(q);
    let f = q - base;
    let p = vec2<i32>(base);
    let top = mix(load_clamped(layer_normal, p).xyz, load_clamped(layer_normal, p + vec2<i32>(1, 0)).xyz, f.x);
    let bottom = mix(load_clamped(layer_normal, p + vec2<i32>(0, 1)).xyz, load_clamped(layer_normal, p + vec2<i32>(1, 1)).xyz, f.x);
    return mix(top, bottom, f.y);
}

fn hash2(p: vec2<f32>, seed: f32) -> f32 {
    return fract(sin(dot(p, vec2<f32>(127.1, 311.7)) + seed * 74.7) * 43758.5453);
}

// Smooth value noise in [0, 1] with cells of `scale` pixels.
fn value_noise(x: vec2<f32>, scale: f32, seed: f32) -> f32 {
    let q = x / scale;
    let i = floor(q);
    let f = q - i;
    let u = f * f * (3.0 - 2.0 * f);
    let a = hash2(i, seed);
    let b = hash2(i + vec2<f32>(1.0, 0.0), seed);
    let c = hash2(i + vec2<f32>(0.0, 1.0), seed);
    let d = hash2(i + vec2<f32>(1.0, 1.0), seed);
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// The perturbation P(x, y) in pixels.
fn perturbation(p: vec2<i32>) -> f32 {
    let mode = i32(constant_or(PIP_MODE, silhouette.pip.x) + 0.5);
    let amount = silhouette.pip.y;
    let scale = max(silhouette.pip.z, 1.0);
    let x = vec2<f32>(p) + 0.5;
    switch mode {
        case 1: {
            return amount;
        }
        case 2: {
            // A tiled grey-scale texture, one texel per pixel.
            let size = vec2<i32>(textureDimensions(pattern));
            let t = textureLoad(pattern, ((p % size) + size) % size, 0);
            return amount * dot(t.rgb, vec3<f32>(0.299, 0.587, 0.114));
        }
        case 3: {
            return amount * value_noise(x, scale, silhouette.pip.w);
        }
        case 4: {
            // A regular matrix of round dots, `scale` pixels apart, radius 0.3·scale.
            let cell = x / scale - floor(x / scale) - 0.5;
            let r = length(cell) * scale;
            return amount * (1.0 - smoothstep(0.25 * scale, 0.35 * scale, r));
        }
        default: {
            return 1.0;
        }
    }
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let c = vec2<f32>(p);
    let s = perturbation(p);
    var response = 0.0;

    if constant_or(USE_DEPTH, silhouette.thresholds.z) > 0.5 {
        // Sobel on the depth image (eq. 3).
        let d_mm = depth_at(c + vec2<f32>(-s, -s));
        let d_0m = depth_at(c + vec2<f32>(0.0, -s));
        let d_pm = depth_at(c + vec2<f32>(s, -s));
        let d_m0 = depth_at(c + vec2<f32>(-s, 0.0));
        let d_p0 = depth_at(c + vec2<f32>(s, 0.0));
        let d_mp = depth_at(c + vec2<f32>(-s, s));
        let d_0p = depth_at(c + vec2<f32>(0.0, s));
        let d_pp = depth_at(c + vec2<f32>(s, s));
        let gx = (d_pm + 2.0 * d_p0 + d_pp) - (d_mm + 2.0 * d_m0 + d_mp);
        let gy = (d_mp + 2.0 * d_0p + d_pp) - (d_mm + 2.0 * d_0m + d_pm);
        if sqrt(gx * gx + gy * gy) >= silhouette.thresholds.x {
            response = 1.0;
        }
    }

    let centre = load_clamped(layer_normal, p);
    if constant_or(USE_NORMALS, silhouette.thresholds.w) > 0.5 && centre.w > 0.5 {
        // Normal similarity with the four neighbours (eq. 4–5); only where there is a surface.
        let n = centre.xyz;
        let similarity = dot(n, normal_at(c + vec2<f32>(s, 0.0))) + dot(n, normal_at(c + vec2<f32>(-s, 0.0)))
            + dot(n, normal_at(c + vec2<f32>(0.0, s))) + dot(n, normal_at(c + vec2<f32>(0.0, -s)));
        if similarity < silhouette.thresholds.y {
            response = 1.0;
        }
    }
    return vec4<f32>(response, 0.0, 0.0, 1.0);
}
