// Image-space silhouettes (Fischer et al. 2005, §3.3.1): a Sobel depth-gradient magnitude against
// depth_threshold (eq. 3), the sum of the dot products with the four neighbour normals against
// normal_threshold (eq. 4–5), OR of the two. Optionally with procedurally perturbed sampling
// positions (PIP, Yuan & Chen 2005, eq. 2): every tap at offset (s, t) is read at
// (x + s·P(x, y), y + t·P(x, y)).

// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/): the pass calls
// `silhouette` with this node's textures and its PIP mode and switches as constants, which the
// compiler folds (as uniforms, every mode's code stayed in the pass: about twice the time on
// lavapipe).

// Mirrored field by field by `SilhouetteUniforms` (crates/hatchery-nodes/src/silhouette.rs);
// the PIP mode and the switches are constants of the pass, not members.
struct Silhouette {
    depth_threshold: f32,
    normal_threshold: f32,
    // PIP: P's scale in pixels, the pattern size in pixels, the noise seed.
    pip_amount: f32,
    pip_scale: f32,
    pip_seed: f32,
    // Distance of the unperturbed taps, whole pixels (1: the paper's neighbours; a render at
    // k times the designed size reads them k pixels away, so its lines are k times as wide).
    tap_distance: f32,
    // Padding to 16 bytes.
    pad1: f32,
    pad2: f32,
};

// Bilinear read at a fractional pixel position (taps at integer positions are exact).
fn silhouette_depth_at(layer_depth: texture_depth_2d, q: vec2<f32>) -> f32 {
    let base = floor(q);
    let f = q - base;
    let p = vec2<i32>(base);
    let top = mix(load_depth_clamped(layer_depth, p), load_depth_clamped(layer_depth, p + vec2<i32>(1, 0)), f.x);
    let bottom = mix(load_depth_clamped(layer_depth, p + vec2<i32>(0, 1)), load_depth_clamped(layer_depth, p + vec2<i32>(1, 1)), f.x);
    return mix(top, bottom, f.y);
}

fn silhouette_normal_at(layer_normal: texture_2d<f32>, q: vec2<f32>) -> vec3<f32> {
    let base = floor(q);
    let f = q - base;
    let p = vec2<i32>(base);
    let top = mix(load_clamped(layer_normal, p).xyz, load_clamped(layer_normal, p + vec2<i32>(1, 0)).xyz, f.x);
    let bottom = mix(load_clamped(layer_normal, p + vec2<i32>(0, 1)).xyz, load_clamped(layer_normal, p + vec2<i32>(1, 1)).xyz, f.x);
    return mix(top, bottom, f.y);
}

// A lattice point's value in [0, 1): PCG (O'Neill 2014) of its integer coordinates and the seed's
// bits, the same on every device (fract(sin(x)·43758) rests on each driver's sin precision).
fn silhouette_hash2(p: vec2<f32>, seed: f32) -> f32 {
    let q = bitcast<vec2<u32>>(vec2<i32>(p));
    let s = silhouette_pcg(bitcast<u32>(seed));
    return f32(silhouette_pcg(q.x ^ silhouette_pcg(q.y ^ s)) >> 8u) / 16777216.0;
}

fn silhouette_pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Smooth value noise in [0, 1] with cells of `scale` pixels.
fn silhouette_value_noise(x: vec2<f32>, scale: f32, seed: f32) -> f32 {
    let q = x / scale;
    let i = floor(q);
    let f = q - i;
    let u = f * f * (3.0 - 2.0 * f);
    let a = silhouette_hash2(i, seed);
    let b = silhouette_hash2(i + vec2<f32>(1.0, 0.0), seed);
    let c = silhouette_hash2(i + vec2<f32>(0.0, 1.0), seed);
    let d = silhouette_hash2(i + vec2<f32>(1.0, 1.0), seed);
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// The perturbation P(x, y) in pixels. `mode`: 0 none, 1 constant, 2 texture, 3 noise, 4 dots.
fn silhouette_perturbation(u: Silhouette, pattern: texture_2d<f32>, mode: i32, p: vec2<i32>) -> f32 {
    let amount = u.pip_amount;
    let scale = max(u.pip_scale, 1.0);
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
            return amount * silhouette_value_noise(x, scale, u.pip_seed);
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

// Eq. 3: the Sobel magnitude of the depth around a pixel (taps named by their offsets:
// m = −1, 0, p = +1 in x then y) reaches the threshold.
fn silhouette_depth_edge(
    d_mm: f32, d_0m: f32, d_pm: f32, d_m0: f32, d_p0: f32, d_mp: f32, d_0p: f32, d_pp: f32,
    threshold: f32,
) -> bool {
    let gx = (d_pm + 2.0 * d_p0 + d_pp) - (d_mm + 2.0 * d_m0 + d_mp);
    let gy = (d_mp + 2.0 * d_0p + d_pp) - (d_mm + 2.0 * d_0m + d_pm);
    return sqrt(gx * gx + gy * gy) >= threshold;
}

// Eq. 4–5: the summed similarity of the centre normal with its four neighbours' falls below the
// threshold.
fn silhouette_crease(n: vec3<f32>, a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, d: vec3<f32>, threshold: f32) -> bool {
    return dot(n, a) + dot(n, b) + dot(n, c) + dot(n, d) < threshold;
}

// The mask at pixel p: 1 on a silhouette, 0 elsewhere.
fn silhouette(
    p: vec2<i32>,
    u: Silhouette,
    layer_depth: texture_depth_2d,
    layer_normal: texture_2d<f32>,
    pattern: texture_2d<f32>,
    mode: i32,
    use_depth: bool,
    use_normals: bool,
) -> vec4<f32> {
    if mode == 0 {
        return silhouette_unperturbed(p, u, layer_depth, layer_normal, use_depth, use_normals);
    }
    let c = vec2<f32>(p);
    let s = silhouette_perturbation(u, pattern, mode, p);
    var response = 0.0;
    if use_depth && silhouette_depth_edge(
        silhouette_depth_at(layer_depth, c + vec2<f32>(-s, -s)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(0.0, -s)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(s, -s)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(-s, 0.0)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(s, 0.0)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(-s, s)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(0.0, s)),
        silhouette_depth_at(layer_depth, c + vec2<f32>(s, s)),
        u.depth_threshold,
    ) {
        response = 1.0;
    }
    // Normals only where there is a surface.
    let centre = load_clamped(layer_normal, p);
    if use_normals && centre.w > 0.5 && silhouette_crease(
        centre.xyz,
        silhouette_normal_at(layer_normal, c + vec2<f32>(s, 0.0)),
        silhouette_normal_at(layer_normal, c + vec2<f32>(-s, 0.0)),
        silhouette_normal_at(layer_normal, c + vec2<f32>(0.0, s)),
        silhouette_normal_at(layer_normal, c + vec2<f32>(0.0, -s)),
        u.normal_threshold,
    ) {
        response = 1.0;
    }
    return vec4<f32>(response, 0.0, 0.0, 1.0);
}

// Without perturbation every tap is `tap_distance` whole pixels away: texels, not bilinear
// quads, at coordinates clamped once per pixel (at distance 1 the same values as the general
// path).
fn silhouette_unperturbed(
    p: vec2<i32>,
    u: Silhouette,
    layer_depth: texture_depth_2d,
    layer_normal: texture_2d<f32>,
    use_depth: bool,
    use_normals: bool,
) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(layer_depth));
    let k = vec2<i32>(i32(u.tap_distance));
    let lo = max(p - k, vec2<i32>(0));
    let hi = min(p + k, size - vec2<i32>(1));
    var response = 0.0;
    if use_depth && silhouette_depth_edge(
        textureLoad(layer_depth, lo, 0),
        textureLoad(layer_depth, vec2<i32>(p.x, lo.y), 0),
        textureLoad(layer_depth, vec2<i32>(hi.x, lo.y), 0),
        textureLoad(layer_depth, vec2<i32>(lo.x, p.y), 0),
        textureLoad(layer_depth, vec2<i32>(hi.x, p.y), 0),
        textureLoad(layer_depth, vec2<i32>(lo.x, hi.y), 0),
        textureLoad(layer_depth, vec2<i32>(p.x, hi.y), 0),
        textureLoad(layer_depth, hi, 0),
        u.depth_threshold,
    ) {
        response = 1.0;
    }
    let centre = textureLoad(layer_normal, p, 0);
    if use_normals && centre.w > 0.5 && silhouette_crease(
        centre.xyz,
        textureLoad(layer_normal, vec2<i32>(hi.x, p.y), 0).xyz,
        textureLoad(layer_normal, vec2<i32>(lo.x, p.y), 0).xyz,
        textureLoad(layer_normal, vec2<i32>(p.x, hi.y), 0).xyz,
        textureLoad(layer_normal, vec2<i32>(p.x, lo.y), 0).xyz,
        u.normal_threshold,
    ) {
        response = 1.0;
    }
    return vec4<f32>(response, 0.0, 0.0, 1.0);
}
