// Stippling of surfaces (Preim & Tietjen, "Illustrative Visualization for Surgical Planning",
// §2.1, §6 and "Efficient Texture-based Stippling" in Viola et al.'s 2005 tutorial): dots of ink whose
// density gives the tone. The dots are a solid (3-D) texture: one jittered point per cell of a
// world-space lattice, each with a random threshold, so they stick to the surface when the
// camera moves. A point is drawn where its threshold is below the density the shading asks for,
// lies within half a cell of the surface's tangent plane (one point per cell² of surface on
// average, whatever the surface's orientation), and is drawn as a round dot of `radius` screen
// pixels. Levels of detail: the cell is a power of two near `spacing` pixels, and the two nearest
// levels are cross-faded so the dots per pixel stay right when zooming.
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

struct Stipple {
    // Clip space → world, and view → world (the camera's axes and eye in world space).
    inverse_view_proj: mat4x4<f32>,
    view_to_world: mat4x4<f32>,
    // Frame size in pixels.
    frame: vec2<f32>,
    // Distance between neighbouring dots at full density and the dot radius, pixels.
    spacing: f32,
    radius: f32,
    // a = π·radius²/spacing²: the ink a full-density lattice would lay down without overlaps.
    coverage: f32,
    seed: u32,
    // 1 for an orthographic camera; 1 to thin dots by n·v (foreshortening); lattice cells
    // searched on each side of the pixel's cell.
    orthographic: u32,
    foreshortening: u32,
    reach: i32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
};

// PCG4D (Jarzynski & Olano 2020): four well-mixed 32-bit words from four.
fn stipple_hash(v_in: vec4<u32>) -> vec4<u32> {
    var v = v_in * 1664525u + 1013904223u;
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    v ^= v >> vec4<u32>(16u);
    v.x += v.y * v.w;
    v.y += v.z * v.x;
    v.z += v.x * v.y;
    v.w += v.y * v.z;
    return v;
}

fn stipple_unit(v: vec4<u32>) -> vec4<f32> {
    return vec4<f32>(v >> vec4<u32>(8u)) * (1.0 / 16777216.0);
}

// Ink in [0, 1] at the surface point `pos` (normal `n`, world units per pixel `pixel_world`,
// the screen's right and up axes in world space) from the dots of lattice level `level`, each
// kept where its threshold is below `keep`.
fn stipple_level(u: Stipple, pos: vec3<f32>, n: vec3<f32>, right: vec3<f32>, up: vec3<f32>,
                 pixel_world: f32, level: i32, keep: f32) -> f32 {
    if keep <= 0.0 {
        return 0.0;
    }
    let cell = exp2(f32(level));
    let base = vec3<i32>(floor(pos / cell));
    let r = u.reach;
    var ink = 0.0;
    for (var dz = -r; dz <= r; dz++) {
        for (var dy = -r; dy <= r; dy++) {
            for (var dx = -r; dx <= r; dx++) {
                let g = base + vec3<i32>(dx, dy, dz);
                let h = stipple_unit(stipple_hash(vec4<u32>(bitcast<vec3<u32>>(g), bitcast<u32>(level) ^ u.seed)));
                if h.w >= keep {
                    continue;
                }
                // The cell's point, its height over the tangent plane and its foot on it.
                let d = (vec3<f32>(g) + h.xyz) * cell - pos;
                let height = dot(d, n);
                if abs(height) >= 0.5 * cell {
                    continue;
                }
                let t = d - n * height;
                let s = vec2<f32>(dot(t, right), dot(t, up)) / pixel_world;
                // A round dot of `radius` pixels with a one-pixel anti-aliased edge.
                ink = max(ink, clamp(u.radius + 0.5 - length(s), 0.0, 1.0));
            }
        }
    }
    return ink;
}

// 1 (paper) to 0 (ink) at pixel p from the shading's intensity and the layer's window depth and
// view-space normal (w = coverage) there.
fn stipple(p: vec2<i32>, u: Stipple, intensity: vec4<f32>, depth: f32, normal: vec4<f32>) -> vec4<f32> {
    if normal.w < 0.5 {
        return vec4<f32>(1.0, 0.0, 0.0, 1.0);
    }
    // The tone rule: ink coverage 1 − exp(−a·ρ) (dots of area a per cell at density ρ, overlapping
    // at random) equals the darkness 1 − intensity; ρ saturates at 1 (coverage 1 − exp(−a)).
    let darkness = clamp(1.0 - intensity.r, 0.0, 1.0);
    var density = min(-log(max(1.0 - darkness, 1e-6)) / u.coverage, 1.0);
    // The surface point in world space, and the world length of one pixel there.
    let centre = vec2<f32>(p) + 0.5;
    let ndc = vec2<f32>(centre.x / u.frame.x * 2.0 - 1.0, 1.0 - centre.y / u.frame.y * 2.0);
    let w0 = u.inverse_view_proj * vec4<f32>(ndc, depth, 1.0);
    let pos = w0.xyz / w0.w;
    let w1 = u.inverse_view_proj * vec4<f32>(ndc.x + 2.0 / u.frame.x, ndc.y, depth, 1.0);
    let pixel_world = max(length(w1.xyz / w1.w - pos), 1e-20);
    let n = normalize((u.view_to_world * vec4<f32>(normalize(normal.xyz), 0.0)).xyz);
    let right = normalize(u.view_to_world[0].xyz);
    let up = normalize(u.view_to_world[1].xyz);
    if u.foreshortening != 0u {
        // A surface seen at an angle shows 1/cos θ times its dots per pixel: thin them by cos θ.
        var to_viewer = normalize(u.view_to_world[2].xyz);
        if u.orthographic == 0u {
            to_viewer = normalize(u.view_to_world[3].xyz - pos);
        }
        density *= abs(dot(n, to_viewer));
    }
    // Levels of detail: the target cell is `spacing` pixels in world units; level l0 (cell 2^l0,
    // finer than the target) and l0 + 1 (coarser) share the density so that the dots per area
    // sum to density/target² whatever the fraction f.
    let level = log2(u.spacing * pixel_world);
    let l0 = floor(level);
    let f = level - l0;
    let keep0 = density * (1.0 - f) * exp2(-2.0 * f);
    let keep1 = min(density * f * exp2(2.0 - 2.0 * f), 1.0);
    let fine = stipple_level(u, pos, n, right, up, pixel_world, i32(l0), keep0);
    let coarse = stipple_level(u, pos, n, right, up, pixel_world, i32(l0) + 1, keep1);
    return vec4<f32>(1.0 - max(fine, coarse), 0.0, 0.0, 1.0);
}
