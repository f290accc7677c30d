// CurvatureFlow: noise advected along the principal curvature directions in image space (the
// tutorial's §1, Hadwiger's Fig. 11/14 "flow along curvature directions"), as a line integral
// convolution: each surface pixel averages a 3-D value noise, evaluated at the world positions
// of the points along its streamline through Curvature's direction field (RK2 steps of `step`
// pixels, `length`/2 each way, ending at depth jumps), so the streaks follow the chosen principal direction and stay
// attached to the surface as the view moves (the noise lives in world space, not on the screen).
// Output: a mask in [0, 1] (`mean` on average, contrast restored by √n), 0 off the surface.

@group(0) @binding(0) var curvature: texture_2d<f32>;
@group(0) @binding(1) var depth: texture_depth_2d;

struct Flow {
    inv_view_proj: mat4x4<f32>,
    // Frame width and height (px); steps per half streamline; step (px).
    frame: vec2<f32>,
    steps: u32,
    step: f32,
    // Noise grain (world units); 1 for the smaller-|κ| direction; contrast; mean output value.
    grain: f32,
    smaller_curvature: u32,
    contrast: f32,
    mean: f32,
};
@group(0) @binding(2) var<uniform> flow: Flow;

fn hash3(c: vec3<i32>) -> f32 {
    var h = (u32(c.x) * 73856093u) ^ (u32(c.y) * 19349663u) ^ (u32(c.z) * 83492791u);
    h = (h ^ (h >> 16u)) * 0x45d9f3bu;
    h = (h ^ (h >> 16u)) * 0x45d9f3bu;
    h = h ^ (h >> 16u);
    return f32(h & 0xffffffu) / 16777216.0;
}

// Trilinear value noise in [0, 1] with cells of `grain` world units.
fn noise(x: vec3<f32>) -> f32 {
    let g = x / max(flow.grain, 1e-9);
    let i = vec3<i32>(floor(g));
    let f = g - floor(g);
    var v = 0.0;
    for (var k = 0; k < 8; k++) {
        let o = vec3<i32>(k & 1, (k >> 1u) & 1, (k >> 2u) & 1);
        let w = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1)
            * select(1.0 - f.z, f.z, o.z == 1);
        v += w * hash3(i + o);
    }
    return v;
}

// The surface point under pixel position p (world), w = 0 where there is none.
fn surface_at(p: vec2<f32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(depth));
    let t = clamp(vec2<i32>(floor(p)), vec2<i32>(0), size - 1);
    let d = textureLoad(depth, t, 0);
    if d >= 1.0 {
        return vec4<f32>(0.0);
    }
    let ndc = vec2<f32>(p.x / flow.frame.x * 2.0 - 1.0, 1.0 - p.y / flow.frame.y * 2.0);
    let w = flow.inv_view_proj * vec4<f32>(ndc, d, 1.0);
    return vec4<f32>(w.xyz / w.w, 1.0);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let p = position.xy;
    let here = surface_at(p);
    let smaller = flow.smaller_curvature != 0u;
    if here.w == 0.0 || textureLoad(curvature, pixel_of(position), 0).z < -5.0 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    // The largest world distance one step may cover on a continuous surface: eight times a
    // pixel's footprint at this depth (grazing surfaces stretch a pixel by 1/|n·v|).
    let ndc = vec2<f32>(p.x / flow.frame.x * 2.0 - 1.0, 1.0 - p.y / flow.frame.y * 2.0);
    let z = textureLoad(depth, pixel_of(position), 0);
    let side4 = flow.inv_view_proj * vec4<f32>(ndc + vec2<f32>(2.0 / flow.frame.x, 0.0), z, 1.0);
    let jump = 8.0 * flow.step * distance(side4.xyz / side4.w, here.xyz);
    var sum = noise(here.xyz);
    var n = 1.0;
    let start = direction_field(curvature, p, smaller);
    if dot(start, start) > 0.0 {
        for (var sense = -1.0; sense <= 1.0; sense += 2.0) {
            var q = p;
            var d = sense * start;
            var previous = here.xyz;
            for (var i = 0u; i < flow.steps; i++) {
                let k1 = align(direction_field(curvature, q, smaller), d);
                let k2 = align(direction_field(curvature, q + 0.5 * flow.step * k1, smaller), k1);
                if dot(k2, k2) == 0.0 {
                    break;
                }
                let next = q + flow.step * k2;
                let s = surface_at(next);
                if s.w == 0.0 || any(next < vec2<f32>(0.0)) || any(next >= flow.frame.xy) {
                    break;
                }
                // A jump in depth (a silhouette or fold): the streamline ends there rather than
                // carrying noise across onto the surface behind.
                if distance(s.xyz, previous) > jump {
                    break;
                }
                previous = s.xyz;
                sum += noise(s.xyz);
                n += 1.0;
                q = next;
                d = k2;
            }
        }
    }
    let value = clamp(flow.mean + (sum / n - 0.5) * sqrt(n) * flow.contrast, 0.0, 1.0);
    return vec4<f32>(value, 0.0, 0.0, 1.0);
}
