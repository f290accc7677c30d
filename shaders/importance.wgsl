// ImportanceCompositing (Viola et al., importance-driven feature enhancement; the tutorial's
// §"Importance Compositing"): per pixel of the frame, what the final synthesis in
// TwoLevelRaycast needs to render the focus object densely and the context sparsely.
//
// Kernels, in order (one dispatch each, 8×8 pixels per workgroup unless noted):
//   footprint   march the ray through the labels: the focus object's first and last hit (view
//               depth), a bit per object (table row) the ray meets, and for MImP the highest
//               importance of the other objects met and the depth of its last sample.
//   dilate      OR of the object bits over ±radius pixels along one axis (twice: x, then y):
//               the dilated footprints of image-space AImC.
//   weigh       Σ of the importance of the objects whose (dilated) footprint covers the pixel.
//   box         mean of that sum over ±radius pixels along one axis (twice): the averaged
//               footprints, so a footprint-weighted importance sum (eq. 2's denominator).
//   jfa_init,   jump flooding (Rong & Tan 2006), 1+JFA: the nearest focus-footprint pixel of
//   jfa_step    every pixel, so d_i, the image-space distance to the footprint (eq. 1).
//   reduce      one workgroup: e_max, the largest last-hit depth of the footprint, and its size.
//   finish      the importance buffer: countersink depth E (eq. 1: e_max − d_i·s_c outside the
//               footprint, the focus's first hit inside), the importance sum — for MImP
//               instead the highest importance among the objects the ray meets behind E (its
//               per-ray rule) — the footprint flag; and the countersink's view-space normal
//               (its two in-plane components from the distance field's gradient, the third
//               from the slope s_c).
//   alpha_mean  one workgroup: the mean opacity of a picture over its non-empty pixels (VPImC's
//               α_avg, eq. 3), for TwoLevelRaycast.
// Prepended: ray_common, ray_skip, ray_objects.

struct ImportanceParams {
    // Frame size in pixels.
    frame_size: vec2<u32>,
    // Countersink slope s_c (≤ 0: cylindrical, no countersink).
    slope: f32,
    // 1 for an orthographic camera.
    orthographic: u32,
    // World size of a pixel (orthographic) or of a pixel at unit view depth (perspective).
    pixel_world: f32,
    // The focus object's id.
    focus: u32,
    // The bits of every drawn object's table row (slots 0..32).
    all_rows: u32,
    // What the buffer's second channel holds: 0 the importance sum (AImC, VPImC), 1 the highest
    // importance behind the countersink (MImP's per-ray rule), 2 zero (a cutaway: no object
    // dropped for its importance).
    second_channel: u32,
    // Importance of table row i (the drawn objects, in table order) at weights[i / 4][i % 4].
    weights: array<vec4<f32>, 8>,
};
@group(1) @binding(4) var<uniform> imp: ImportanceParams;

// One pass of a separable or iterated kernel: the axis (0 = x, 1 = y) or the JFA step in
// pixels, and the radius in pixels.
struct PassParams {
    step: u32,
    radius: u32,
    pad0: u32,
    pad1: u32,
};
@group(1) @binding(5) var<uniform> pass_params: PassParams;

@group(1) @binding(6) var footprint_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(7) var bits_out: texture_storage_2d<r32uint, write>;
@group(1) @binding(8) var bits_in: texture_2d<u32>;
@group(1) @binding(9) var sum_out: texture_storage_2d<r32float, write>;
@group(1) @binding(10) var sum_in: texture_2d<f32>;
@group(1) @binding(11) var footprint_in: texture_2d<f32>;
@group(1) @binding(12) var seed_out: texture_storage_2d<rg32float, write>;
@group(1) @binding(13) var seed_in: texture_2d<f32>;
@group(1) @binding(14) var stats_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(15) var stats_in: texture_2d<f32>;
@group(1) @binding(16) var buffer_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(17) var cut_out: texture_storage_2d<rgba32float, write>;
@group(1) @binding(18) var picture_in: texture_2d<f32>;

// A pixel without a seed (no footprint pixel found yet).
const NO_SEED: f32 = -1.0e9;

fn frame_size() -> vec2<i32> {
    return vec2<i32>(imp.frame_size);
}

fn in_frame(id: vec2<u32>) -> bool {
    let size = frame_size();
    return i32(id.x) < size.x && i32(id.y) < size.y;
}

// Distance from the eye plane along the view direction (world units); positive in front.
fn view_depth(p: vec3<f32>) -> f32 {
    return -(ray.view * vec4<f32>(p, 1.0)).z;
}

// The drawn object a footprint sample at voxel-space q sees (0 for none), and how far the
// answer holds along the ray: `until` is the ray parameter past which the next sample must
// look again — the exit of q's brick (in the direction of `dq`, less a margin) when the brick
// holds no drawn object, only one, or (`known`: rows already met) no drawn object outside
// `known` (`object` is then 0) — else t itself.
struct Seen {
    object: u32,
    until: f32,
};

fn seen_at(q: vec3<f32>, dq: vec3<f32>, t: f32, known: u32) -> Seen {
    var s: Seen;
    s.object = 0u;
    s.until = t;
    let h = ray.step_world;
    let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims - 1.0) / f32(ray.brick_size)));
    let info = textureLoad(bricks, brick, 0);
    let rows = select(u32(info.w), 0xffffffffu, info.w < 0.0);
    if (ray.skip_empty != 0u && info.x > info.y) || (info.z < 0.0 && (rows & ~known) == 0u) {
        s.until = brick_exit(q, dq, t) - 1e-4 * h;
        return s;
    }
    if info.z >= 0.0 {
        // A brick of one object: every sample in it sees that object.
        s.object = u32(info.z);
        s.until = brick_exit(q, dq, t) - 1e-4 * h;
    } else if !(boundary_filtered() && drawn_union(q) < 0.45) {
        s.object = object_at(q);
    }
    if s.object >= two_level.columns || object_info(s.object, 0u).x < 0.5 {
        s.object = 0u;
    }
    return s;
}

// The table-row bit of a drawn object (0 past slot 31).
fn row_bit(object: u32) -> u32 {
    let slot = u32(object_info(object, 0u).x + 0.5) - 1u;
    return select(0u, 1u << slot, slot < 32u);
}

@compute @workgroup_size(8, 8, 1)
fn footprint(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let r = primary_ray(vec2<f32>(id.xy) + 0.5);
    var first = -1.0;
    var last = -1.0;
    var bits = 0u;
    // MImP: the highest importance of the other objects the ray meets and the depth of its last
    // sample (exact for rays that miss the focus: those march every sample, see below).
    var strongest = 0.0;
    var strongest_last = -1.0e30;
    let focus = imp.focus;
    if r.hits {
        let h = ray.step_world;
        let count = min(u32(max(floor((r.t_out - r.t_in) / h), -1.0) + 1.0), 65536u);
        // Forward from the front: the bits of the objects met, and the focus's first hit and
        // its hits up to there. Bricks of no drawn object or of one are taken at once; after
        // the first hit, so are bricks of objects already met (the focus included: its last
        // hit is searched from the back). The march ends early once every bit is set.
        var k = 0u;
        var k_hit = count;
        for (; k < count; k++) {
            let t = r.t_in + f32(k) * h;
            // Before the first hit the focus is never "known": its samples are all looked at.
            var known = 0u;
            if first >= 0.0 {
                known = bits;
            }
            let seen = seen_at(r.q0 + r.dq * t, r.dq, t, known);
            let next = min(max(ceil((seen.until - r.t_in) / h), f32(k + 1u)), f32(count));
            if seen.object != 0u {
                bits = bits | row_bit(seen.object);
                if seen.object != focus && imp.second_channel == 1u {
                    let weight = max(object_info(seen.object, 1u).z, 0.0);
                    if weight >= strongest {
                        strongest = weight;
                        strongest_last = view_depth(r.p0 + r.dir * (r.t_in + (next - 1.0) * h));
                    }
                }
                if seen.object == focus && first < 0.0 {
                    first = view_depth(r.p0 + r.dir * t);
                    last = view_depth(r.p0 + r.dir * (r.t_in + (next - 1.0) * h));
                    k_hit = u32(next) - 1u;
                }
            }
            k = u32(next) - 1u;
            if first >= 0.0 && (bits & imp.all_rows) == imp.all_rows {
                break;
            }
        }
        // Backward from the back to the focus's last hit, down to where its first hit ended.
        if first >= 0.0 && count > k_hit + 1u {
            var j = count - 1u;
            loop {
                let t = r.t_in + f32(j) * h;
                let seen = seen_at(r.q0 + r.dq * t, -r.dq, -t, 0u);
                if seen.object == focus {
                    last = view_depth(r.p0 + r.dir * t);
                    break;
                }
                // (seen.until is −(the brick's front, less a margin) for a brick taken at once.)
                let previous = min(floor((-seen.until - r.t_in) / h), f32(j) - 1.0);
                if previous <= f32(k_hit) {
                    break;
                }
                j = u32(previous);
            }
        }
    }
    textureStore(footprint_out, vec2<i32>(id.xy), vec4<f32>(first, last, strongest, strongest_last));
    textureStore(bits_out, vec2<i32>(id.xy), vec4<u32>(bits, 0u, 0u, 0u));
}

fn axis_offset(o: i32) -> vec2<i32> {
    if pass_params.step == 0u {
        return vec2<i32>(o, 0);
    }
    return vec2<i32>(0, o);
}

@compute @workgroup_size(8, 8, 1)
fn dilate(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let radius = i32(pass_params.radius);
    let top = frame_size() - 1;
    var bits = 0u;
    for (var o = -radius; o <= radius; o++) {
        let p = clamp(vec2<i32>(id.xy) + axis_offset(o), vec2<i32>(0), top);
        bits = bits | textureLoad(bits_in, p, 0).r;
    }
    textureStore(bits_out, vec2<i32>(id.xy), vec4<u32>(bits, 0u, 0u, 0u));
}

@compute @workgroup_size(8, 8, 1)
fn weigh(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let bits = textureLoad(bits_in, vec2<i32>(id.xy), 0).r;
    var sum = 0.0;
    for (var slot = 0u; slot < 32u; slot++) {
        if (bits & (1u << slot)) != 0u {
            sum += imp.weights[slot / 4u][slot % 4u];
        }
    }
    textureStore(sum_out, vec2<i32>(id.xy), vec4<f32>(sum, 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn box(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let radius = i32(pass_params.radius);
    let size = frame_size();
    var sum = 0.0;
    var n = 0.0;
    for (var o = -radius; o <= radius; o++) {
        let p = vec2<i32>(id.xy) + axis_offset(o);
        if all(p >= vec2<i32>(0)) && all(p < size) {
            sum += textureLoad(sum_in, p, 0).r;
            n += 1.0;
        }
    }
    textureStore(sum_out, vec2<i32>(id.xy), vec4<f32>(sum / max(n, 1.0), 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn jfa_init(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    var seed = vec2<f32>(NO_SEED);
    if textureLoad(footprint_in, vec2<i32>(id.xy), 0).y >= 0.0 {
        seed = vec2<f32>(id.xy);
    }
    textureStore(seed_out, vec2<i32>(id.xy), vec4<f32>(seed, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn jfa_step(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let k = i32(pass_params.step);
    let size = frame_size();
    let here = vec2<f32>(id.xy);
    var best = textureLoad(seed_in, vec2<i32>(id.xy), 0).xy;
    var best_d = 1e30;
    if best.x > NO_SEED * 0.5 {
        best_d = distance(best, here);
    }
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let p = vec2<i32>(id.xy) + vec2<i32>(dx, dy) * k;
            if any(p < vec2<i32>(0)) || any(p >= size) {
                continue;
            }
            let s = textureLoad(seed_in, p, 0).xy;
            if s.x > NO_SEED * 0.5 {
                let d = distance(s, here);
                if d < best_d {
                    best_d = d;
                    best = s;
                }
            }
        }
    }
    textureStore(seed_out, vec2<i32>(id.xy), vec4<f32>(best, 0.0, 0.0));
}

var<workgroup> partial_max: array<f32, 256>;
var<workgroup> partial_sum: array<f32, 256>;

@compute @workgroup_size(256, 1, 1)
fn reduce(@builtin(local_invocation_index) lane: u32) {
    let size = frame_size();
    let n = u32(size.x * size.y);
    var m = -1.0;
    var count = 0.0;
    for (var i = lane; i < n; i += 256u) {
        let last = textureLoad(footprint_in, vec2<i32>(i32(i % u32(size.x)), i32(i / u32(size.x))), 0).y;
        if last >= 0.0 {
            m = max(m, last);
            count += 1.0;
        }
    }
    partial_max[lane] = m;
    partial_sum[lane] = count;
    workgroupBarrier();
    for (var half = 128u; half > 0u; half /= 2u) {
        if lane < half {
            partial_max[lane] = max(partial_max[lane], partial_max[lane + half]);
            partial_sum[lane] += partial_sum[lane + half];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        textureStore(stats_out, vec2<i32>(0), vec4<f32>(partial_max[0], partial_sum[0], 0.0, 0.0));
    }
}

// MImP (§IV.A): "for each ray the object with highest importance along the ray is determined";
// the others are not drawn. The highest importance among the drawn objects the ray meets at view
// depths ≥ e (behind the countersink, whose front part is cut away), for a ray outside the focus
// footprint (inside it only the focus is drawn anyway), marched as the footprint is: bricks of
// no drawn object or only of objects already met are taken at once, and the march ends when
// the highest importance of any object but the focus (which the ray misses) is reached.
fn strongest_behind(pixel: vec2<u32>, e: f32) -> f32 {
    let r = primary_ray(vec2<f32>(pixel) + 0.5);
    if !r.hits {
        return 0.0;
    }
    let others = imp.all_rows & ~row_bit(imp.focus);
    var top = 0.0;
    for (var slot = 0u; slot < 32u; slot++) {
        if (others & (1u << slot)) != 0u {
            top = max(top, imp.weights[slot / 4u][slot % 4u]);
        }
    }
    let h = ray.step_world;
    let count = min(u32(max(floor((r.t_out - r.t_in) / h), -1.0) + 1.0), 65536u);
    let z0 = view_depth(r.p0);
    let dz = view_depth(r.p0 + r.dir) - z0;
    var k = 0u;
    if e > -1.0e29 && dz > 1e-12 {
        // One sample before the cut; the depth test below decides exactly.
        k = u32(clamp(floor(((e - z0) / dz - r.t_in) / h) - 1.0, 0.0, f32(count)));
    }
    var bits = 0u;
    var strongest = 0.0;
    for (; k < count; k++) {
        let t = r.t_in + f32(k) * h;
        let seen = seen_at(r.q0 + r.dq * t, r.dq, t, bits);
        var next = min(max(ceil((seen.until - r.t_in) / h), f32(k + 1u)), f32(count));
        if seen.object != 0u {
            if z0 + dz * t >= e {
                bits = bits | row_bit(seen.object);
                strongest = max(strongest, max(object_info(seen.object, 1u).z, 0.0));
                if strongest >= top {
                    break;
                }
            } else {
                // In front of the cut: sample by sample until behind it (a brick of one
                // object may reach past it).
                next = f32(k + 1u);
            }
        }
        k = u32(next) - 1u;
    }
    return strongest;
}

@compute @workgroup_size(8, 8, 1)
fn finish(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let pixel = vec2<i32>(id.xy);
    let fp = textureLoad(footprint_in, pixel, 0);
    let stats = textureLoad(stats_in, vec2<i32>(0), 0);
    let sum = textureLoad(sum_in, pixel, 0).r;
    let slope = imp.slope;
    var e = -1.0e30;
    var inside = 0.0;
    var normal = vec3<f32>(0.0, 0.0, 1.0);
    var d = 0.0;
    if fp.y >= 0.0 {
        // In the footprint: the context in front of the focus's first hit.
        e = fp.x;
        inside = 1.0;
    } else {
        let seed = textureLoad(seed_in, pixel, 0).xy;
        if seed.x > NO_SEED * 0.5 && stats.y > 0.0 {
            let away = vec2<f32>(id.xy) - seed;
            d = length(away);
            if slope > 0.0 {
                let e_max = stats.x;
                var pixel_world = imp.pixel_world;
                if imp.orthographic == 0u {
                    pixel_world = imp.pixel_world * e_max;
                }
                // Eq. 1: e_i = e_max − d_i · s_c (d_i in world units at the footprint's depth).
                e = e_max - d * pixel_world * slope;
                // The countersink z_view = −e_max + s_c · d(x, y): its normal towards the viewer
                // is (−s_c ∇d, 1), ∇d the unit vector away from the footprint (y up in view).
                let u = away / max(d, 1e-6);
                normal = normalize(vec3<f32>(-slope * u.x, slope * u.y, 1.0));
            }
        }
    }
    var second = sum;
    if imp.second_channel == 1u && inside < 0.5 {
        // The footprint march's answer holds where the strongest object's last sample is not
        // cut away; else march again behind the cut (around the footprint only).
        second = fp.z;
        if fp.w > -1.0e29 && fp.w < e {
            second = strongest_behind(id.xy, e);
        }
    } else if imp.second_channel == 1u {
        second = 0.0;
    } else if imp.second_channel == 2u {
        second = 0.0;
    }
    textureStore(buffer_out, pixel, vec4<f32>(e, second, inside, fp.y));
    textureStore(cut_out, pixel, vec4<f32>(normal, d));
}

@compute @workgroup_size(256, 1, 1)
fn alpha_mean(@builtin(local_invocation_index) lane: u32) {
    let size = vec2<i32>(textureDimensions(picture_in));
    let n = u32(size.x * size.y);
    var sum = 0.0;
    var count = 0.0;
    for (var i = lane; i < n; i += 256u) {
        let a = textureLoad(picture_in, vec2<i32>(i32(i % u32(size.x)), i32(i / u32(size.x))), 0).a;
        if a > 0.0 {
            sum += a;
            count += 1.0;
        }
    }
    partial_max[lane] = sum;
    partial_sum[lane] = count;
    workgroupBarrier();
    for (var half = 128u; half > 0u; half /= 2u) {
        if lane < half {
            partial_max[lane] += partial_max[lane + half];
            partial_sum[lane] += partial_sum[lane + half];
        }
        workgroupBarrier();
    }
    if lane == 0u {
        let mean = partial_max[0] / max(partial_sum[0], 1.0);
        textureStore(stats_out, vec2<i32>(0), vec4<f32>(mean, partial_sum[0], 0.0, 0.0));
    }
}
