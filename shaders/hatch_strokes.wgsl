// HatchStrokes: hatching strokes along principal curvature directions (Nagy et al. 2002;
// Yuan & Chen 2005 §4.4) on an iso-surface seen through a G-buffer.
//
// `trace` (compute, one thread per candidate seed — a vertex of a mesh of the same surface):
// project the seed; keep it if it is visible (its view depth within `tolerance` of the G-buffer's
// at its pixel) and passes Yuan–Chen's random-number test against its tone: u < density ·
// darkness, with u a hash of the seed's index (so the same surface points seed strokes in every
// frame, and a darker tone keeps a superset of the seeds of a lighter one). From the seed, a
// stroke is integrated both ways with RK4 in image space through the direction field of
// Curvature's image (the larger-|κ| principal direction, or the smaller), each half `steps`
// steps of `step` pixels, stopping where the surface ends, the depth jumps (a fold or a
// silhouette), the field turns by more than 45° in one step, or at the frame's edge; strokes
// shorter than two steps are dropped (they would taper to nothing). Where the
// darkness exceeds `cross`, a second stroke follows the other principal direction
// (cross-hatching). `finish` writes the indirect draw of the strokes' segments.
//
// `vs_stroke` / `fs_stroke`: each segment an anti-aliased quad, half width tapering to 0 over
// `taper` of the stroke's length at both ends, max-blended into a one-channel coverage target.

struct Hatch {
    view_proj: mat4x4<f32>,
    view: mat4x4<f32>,
    inv_proj: mat4x4<f32>,
    // Frame width and height (px); RK4 step (px); steps per half stroke.
    frame: vec2<f32>,
    step: f32,
    steps: u32,
    // Seeds per unit of screen area; cross-hatching darkness threshold (≥ 1: none); depth
    // tolerance (world units); most strokes.
    density: f32,
    cross_threshold: f32,
    depth_tolerance: f32,
    max_strokes: u32,
    // Stroke width (px); taper (fraction of the length); 1 to follow the smaller |κ|, 0 the
    // larger; 1 when a tone mask is bound (else headlight Lambert from the G-buffer normal).
    width: f32,
    taper: f32,
    smaller_curvature: u32,
    use_tone: u32,
    // Candidate seeds; seed salt.
    seeds: u32,
    salt: u32,
    pad0: u32,
    pad1: u32,
};

struct Stroke {
    // Index of the seed (mesh vertex) the stroke grew from.
    seed: u32,
    // Valid points are first..=last of the stroke's 2·steps + 1 slots (the seed at `steps`).
    first: u32,
    last: u32,
    // 0 = along the chosen direction, 1 = cross-hatching along the other.
    cross: u32,
};

@group(0) @binding(0) var<uniform> hatch: Hatch;
@group(0) @binding(1) var curvature: texture_2d<f32>;
@group(0) @binding(2) var depth: texture_depth_2d;
@group(0) @binding(3) var normals: texture_2d<f32>;
@group(0) @binding(4) var tone: texture_2d<f32>;
@group(0) @binding(5) var<storage, read> seeds: array<f32>;
@group(0) @binding(6) var<storage, read_write> strokes: array<Stroke>;
@group(0) @binding(7) var<storage, read_write> points: array<vec2<f32>>;
@group(0) @binding(8) var<storage, read_write> counter: atomic<u32>;
@group(0) @binding(9) var<storage, read_write> indirect: array<u32, 4>;
@group(0) @binding(10) var<storage, read> strokes_in: array<Stroke>;
@group(0) @binding(11) var<storage, read> points_in: array<vec2<f32>>;

fn steps() -> u32 {
    return hatch.steps;
}

fn slots() -> u32 {
    return 2u * steps() + 1u;
}

// PCG hash to [0, 1).
fn random(v: u32) -> f32 {
    var s = v * 747796405u + 2891336453u;
    let word = ((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u;
    return f32((word >> 22u) ^ word) / 4294967296.0;
}

fn inside(p: vec2<f32>) -> bool {
    return all(p >= vec2<f32>(0.0)) && all(p < hatch.frame.xy);
}

// View-space z of the G-buffer surface at texel t (−1e30 where there is none).
fn surface_z(t: vec2<i32>) -> f32 {
    let d = textureLoad(depth, t, 0);
    if d >= 1.0 {
        return -1e30;
    }
    let ndc = vec2<f32>(
        (f32(t.x) + 0.5) / hatch.frame.x * 2.0 - 1.0,
        1.0 - (f32(t.y) + 0.5) / hatch.frame.y * 2.0,
    );
    let v = hatch.inv_proj * vec4<f32>(ndc, d, 1.0);
    return v.z / v.w;
}

// The hatching direction field at pixel position p: the larger-|κ| principal direction (or the
// smaller with direction = min), the other one for cross-hatching.
fn field(p: vec2<f32>, other: bool) -> vec2<f32> {
    return direction_field(curvature, p, (hatch.smaller_curvature != 0u) != other);
}

// Integrates one half of a stroke from p along ±`heading`, writing points at slot
// base + steps ± i; returns how many steps it made.
fn trace_half(base: u32, start: vec2<f32>, heading: vec2<f32>, sense: i32, other: bool) -> u32 {
    let h = hatch.step;
    let tolerance = hatch.depth_tolerance;
    var p = start;
    var d = heading;
    var z = surface_z(vec2<i32>(floor(p)));
    for (var i = 1u; i <= steps(); i++) {
        let k1 = align(field(p, other), d);
        let k2 = align(field(p + 0.5 * h * k1, other), k1);
        let k3 = align(field(p + 0.5 * h * k2, other), k1);
        let k4 = align(field(p + h * k3, other), k1);
        if dot(k1, k1) == 0.0 || dot(k2, k2) == 0.0 || dot(k3, k3) == 0.0 || dot(k4, k4) == 0.0 {
            return i - 1u;
        }
        let step = (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
        let length = sqrt(dot(step, step));
        if length < 1e-6 {
            return i - 1u;
        }
        let next_d = step / length;
        // A turn of more than 45° in one step: an umbilic or a singularity of the field.
        if dot(next_d, d) < 0.7071 {
            return i - 1u;
        }
        let next = p + h * next_d;
        if !inside(next) {
            return i - 1u;
        }
        let next_z = surface_z(vec2<i32>(floor(next)));
        if abs(next_z - z) > tolerance {
            return i - 1u;
        }
        p = next;
        d = next_d;
        z = next_z;
        points[base + u32(i32(steps()) + sense * i32(i))] = p;
    }
    return steps();
}

fn trace_stroke(seed: u32, p: vec2<f32>, other: bool) {
    let slot = atomicAdd(&counter, 1u);
    if slot >= hatch.max_strokes {
        return;
    }
    let base = slot * slots();
    let heading = field(p, other);
    points[base + steps()] = p;
    var back = 0u;
    var ahead = 0u;
    if dot(heading, heading) > 0.0 {
        back = trace_half(base, p, -heading, -1, other);
        ahead = trace_half(base, p, heading, 1, other);
    }
    if back + ahead < 2u {
        // Shorter than two steps (a seed at a silhouette or fold): it would taper to nothing.
        back = 0u;
        ahead = 0u;
    }
    strokes[slot] = Stroke(seed, steps() - back, steps() + ahead, select(0u, 1u, other));
}

@compute @workgroup_size(64)
fn trace(@builtin(global_invocation_id) gid: vec3<u32>) {
    let id = gid.x + gid.y * 65535u * 64u;
    if id >= hatch.seeds {
        return;
    }
    let u = random(id ^ hatch.salt);
    let density = hatch.density;
    if u >= density {
        return;
    }
    let world = vec4<f32>(seeds[6u * id], seeds[6u * id + 1u], seeds[6u * id + 2u], 1.0);
    let clip = hatch.view_proj * world;
    if clip.w <= 0.0 {
        return;
    }
    let ndc = clip.xyz / clip.w;
    if any(abs(ndc.xy) > vec2<f32>(1.0)) || ndc.z < 0.0 || ndc.z > 1.0 {
        return;
    }
    let p = vec2<f32>((ndc.x + 1.0) * 0.5, (1.0 - ndc.y) * 0.5) * hatch.frame.xy;
    let t = vec2<i32>(floor(p));
    if !inside(p) {
        return;
    }
    // Visible: on the G-buffer's surface at its pixel or a neighbour (a grazing surface's depth
    // changes fast across one pixel), not behind it.
    let seed_z = (hatch.view * world).z;
    let size = vec2<i32>(textureDimensions(depth));
    var nearest = 1e30;
    for (var k = 0; k < 9; k++) {
        let n = clamp(t + vec2<i32>(k % 3 - 1, k / 3 - 1), vec2<i32>(0), size - 1);
        nearest = min(nearest, abs(seed_z - surface_z(n)));
    }
    if nearest > hatch.depth_tolerance {
        return;
    }
    if textureLoad(curvature, t, 0).z < -5.0 {
        return;
    }
    var brightness: f32;
    if hatch.use_tone == 1u {
        brightness = textureLoad(tone, t, 0).r;
    } else {
        brightness = max(textureLoad(normals, t, 0).z, 0.0);
    }
    let darkness = 1.0 - clamp(brightness, 0.0, 1.0);
    // Yuan–Chen: the seed draws when its random number is below its tone's darkness.
    if u >= density * darkness {
        return;
    }
    trace_stroke(id, p, false);
    if darkness > hatch.cross_threshold {
        trace_stroke(id, p, true);
    }
}

@compute @workgroup_size(1)
fn finish() {
    let n = min(atomicLoad(&counter), hatch.max_strokes);
    indirect[0] = 6u;
    indirect[1] = n * (slots() - 1u);
    indirect[2] = 0u;
    indirect[3] = 0u;
}

struct StrokeOut {
    @builtin(position) position: vec4<f32>,
    // p0, p1 (px).
    @location(0) @interpolate(flat) ends: vec4<f32>,
    // Half widths at p0 and p1 (px).
    @location(1) @interpolate(flat) widths: vec2<f32>,
};

// Half width at point index k of a stroke with valid points first..=last.
fn half_width(k: u32, first: u32, last: u32) -> f32 {
    let taper = hatch.taper;
    if taper <= 0.0 {
        return 0.5 * hatch.width;
    }
    let t = f32(k - first) / max(f32(last - first), 1.0);
    return 0.5 * hatch.width * clamp(min(t, 1.0 - t) / taper, 0.0, 1.0);
}

@vertex
fn vs_stroke(@builtin(vertex_index) index: u32, @builtin(instance_index) instance: u32) -> StrokeOut {
    var out: StrokeOut;
    let segments = slots() - 1u;
    let s = instance / segments;
    let k = instance % segments;
    let stroke = strokes_in[s];
    // Outside the stroke's valid points: a degenerate triangle (nothing drawn).
    out.position = vec4<f32>(2.0, 2.0, 0.0, 1.0);
    out.ends = vec4<f32>(0.0);
    out.widths = vec2<f32>(0.0);
    if k < stroke.first || k + 1u > stroke.last {
        return out;
    }
    let p0 = points_in[s * slots() + k];
    let p1 = points_in[s * slots() + k + 1u];
    let w0 = half_width(k, stroke.first, stroke.last);
    let w1 = half_width(k + 1u, stroke.first, stroke.last);
    var corner = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0),
        vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
    );
    let uv = corner[index];
    let grow = max(w0, w1) + 1.0;
    let length = distance(p0, p1);
    var along = vec2<f32>(1.0, 0.0);
    if length > 1e-6 {
        along = (p1 - p0) / length;
    }
    let across = vec2<f32>(-along.y, along.x);
    let pixel = p0 - grow * along + uv.x * (length + 2.0 * grow) * along
        + (uv.y * 2.0 - 1.0) * grow * across;
    out.position = vec4<f32>(
        pixel.x / hatch.frame.x * 2.0 - 1.0,
        1.0 - pixel.y / hatch.frame.y * 2.0,
        0.0,
        1.0,
    );
    out.ends = vec4<f32>(p0, p1);
    out.widths = vec2<f32>(w0, w1);
    return out;
}

@fragment
fn fs_stroke(in: StrokeOut) -> @location(0) vec4<f32> {
    let q = in.position.xy;
    let p0 = in.ends.xy;
    let p1 = in.ends.zw;
    let d = p1 - p0;
    let t = clamp(dot(q - p0, d) / max(dot(d, d), 1e-12), 0.0, 1.0);
    let distance_px = distance(q, p0 + t * d);
    let radius = mix(in.widths.x, in.widths.y, t);
    let coverage = clamp(radius + 0.5 - distance_px, 0.0, 1.0);
    return vec4<f32>(coverage, 0.0, 0.0, 1.0);
}
