// TwoLevelRaycast: two-level volume rendering of a segmented volume (Hadwiger §2.2–2.4, Fig. 26).
// Each sample's object is decided by boundary filtering (§2.3): the binary mask of each object
// among the eight neighbouring voxels is filtered trilinearly and thresholded at 0.5 (ids are
// never interpolated as numbers); point sampling takes the nearest voxel's id. A ray is split
// into segments, maximal runs of samples of one object; each segment is composited with its
// object's local mode (over, mip, iso, sum) and rendering mode, and the segments are combined
// front to back with the global mode (over, mip, sum). Prepended: ray_common, ray_classify,
// ray_shade, ray_skip. The CPU reference is tests/common/two_level_reference.rs.

// Binding 9 (`bricks`, see ray_common) holds (0, 1, id, 0) for bricks a drawn object reaches
// and (1, 0, id, 0) for the others, so an empty brick reads as one to skip; id is the one object
// every sample of the brick sees, −1 where several meet.
// Object ids (R16Uint), on the volume's grid.
@group(0) @binding(11) var object_ids: texture_3d<u32>;
// Per id, at column id % 256 of rows 2 · (id / 256) and the one after: (table row + 1, or 0
// when not drawn; rendering mode; local compositing; iso value) and (TF domain lo, hi, 0, 0).
@group(0) @binding(12) var objects: texture_2d<f32>;

// 1 where a voxel belongs to a drawn object (R8Unorm, filtered): the union of the drawn
// objects' masks, an upper bound of each one's filtered mask.
@group(0) @binding(14) var drawn_mask: texture_3d<f32>;

struct TwoLevel {
    // x = global compositing (0 over, 1 mip, 2 sum); y = 1 for boundary filtering, 0 for point
    // sampling; z = number of columns of `objects` (largest id + 1); w = 1 to take normals from
    // each object's own filtered mask instead of the data (label maps without intensities).
    options: vec4<f32>,
};
@group(0) @binding(13) var<uniform> two_level: TwoLevel;

const MODE_DVR: i32 = 0;
const MODE_SHADED: i32 = 1;
const MODE_TONE: i32 = 2;
const MODE_CONTOURS: i32 = 3;
const MODE_MIP: i32 = 4;
const MODE_ISO: i32 = 5;
const LOCAL_OVER: i32 = 0;
const LOCAL_MIP: i32 = 1;
const LOCAL_ISO: i32 = 2;
const LOCAL_SUM: i32 = 3;

fn object_info(id: u32, which: u32) -> vec4<f32> {
    return textureLoad(objects, vec2<i32>(i32(id % 256u), i32((id / 256u) * 2u + which)), 0);
}

fn id_at(v: vec3<i32>) -> u32 {
    let top = vec3<i32>(ray.dims.xyz) - 1;
    return textureLoad(object_ids, clamp(v, vec3<i32>(0), top), 0).r;
}

// The object at voxel-space q: boundary filtering (§2.3) or the nearest voxel; 0 for none
// (background, or no object's filtered mask above 0.5, as at a junction of three objects).
fn object_at(q: vec3<f32>) -> u32 {
    let p = clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0);
    if two_level.options.y < 0.5 {
        return id_at(vec3<i32>(round(p)));
    }
    let base = vec3<i32>(floor(p));
    let f = p - floor(p);
    var ids: array<u32, 8>;
    var weights: array<f32, 8>;
    for (var c = 0; c < 8; c++) {
        let o = vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1);
        ids[c] = id_at(base + o);
        let w3 = select(1.0 - f, f, vec3<bool>(o == vec3<i32>(1)));
        weights[c] = w3.x * w3.y * w3.z;
    }
    // The filtered binary mask of the object at corner c: the weights of the corners holding it.
    for (var c = 0; c < 8; c++) {
        var mask = 0.0;
        for (var d = 0; d < 8; d++) {
            if ids[d] == ids[c] {
                mask += weights[d];
            }
        }
        if mask > 0.5 {
            return ids[c];
        }
    }
    return 0u;
}

// The trilinearly filtered binary mask of object `id` at voxel-space q (§2.3).
fn object_mask(q: vec3<f32>, id: u32) -> f32 {
    let p = clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0);
    let base = vec3<i32>(floor(p));
    let f = p - floor(p);
    var mask = 0.0;
    for (var c = 0; c < 8; c++) {
        let o = vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1);
        if id_at(base + o) == id {
            let w3 = select(1.0 - f, f, vec3<bool>(o == vec3<i32>(1)));
            mask += w3.x * w3.y * w3.z;
        }
    }
    return mask;
}

// World-space gradient of object `id`'s filtered mask (central differences in voxel space):
// the shading normal of an object boundary when the data holds no intensities.
fn object_gradient(q: vec3<f32>, id: u32) -> vec3<f32> {
    var g = vec3<f32>(0.0);
    for (var axis = 0; axis < 3; axis++) {
        var lo = q;
        var hi = q;
        lo[axis] -= 1.0;
        hi[axis] += 1.0;
        g[axis] = (object_mask(hi, id) - object_mask(lo, id)) * 0.5;
    }
    return (ray.grad_to_world * vec4<f32>(g, 0.0)).xyz;
}

// The gradient that shades a sample of object `id`: the data's, or the object mask's.
fn shading_gradient(q: vec3<f32>, id: u32) -> vec3<f32> {
    if two_level.options.w > 0.5 {
        return object_gradient(q, id);
    }
    return gradient_at(q);
}

// The drawn objects' union mask at voxel-space q, filtered trilinearly by the sampler.
fn drawn_union(q: vec3<f32>) -> f32 {
    let uv = (clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0) + 0.5) / ray.dims.xyz;
    return textureSampleLevel(drawn_mask, linear_clamp, uv, 0.0).r;
}

// Cool-to-warm tone shading (Gooch et al. 1998; the tutorial's "tone shading").
fn tone(c: vec3<f32>, n: vec3<f32>, l: vec3<f32>) -> vec3<f32> {
    let t = (1.0 + dot(n, l)) * 0.5;
    let cool = vec3<f32>(0.0, 0.0, 0.55) + 0.25 * c;
    let warm = vec3<f32>(0.3, 0.3, 0.0) + 0.5 * c;
    return clamp(mix(cool, warm, t), vec3<f32>(0.0), vec3<f32>(1.0));
}

// A finished segment (premultiplied, alpha clamped to 1) combined into the total by the global
// mode: over, mip (per-channel maximum), sum.
fn combine(total: vec4<f32>, seg: vec4<f32>, global_mode: i32) -> vec4<f32> {
    let s = vec4<f32>(seg.rgb, min(seg.a, 1.0));
    if global_mode == 0 {
        return total + (1.0 - total.a) * s;
    }
    if global_mode == 1 {
        return max(total, s);
    }
    return total + s;
}

// What a finished segment leaves: premultiplied colour and where it was first visible.
struct Segment {
    color: vec4<f32>,
    first_t: f32,
    first_normal: vec3<f32>,
};

fn cast_two_level(position: vec2<f32>) -> RayResult {
    var out: RayResult;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;
    let r = primary_ray(position);
    if !r.hits {
        return out;
    }
    let h = ray.box_min.w;
    let step_voxels = ray.box_max.w;
    var start = r.t_in;
    if ray.frame.z > 0.5 {
        start += h * hash(position);
    }
    let l = ray.light.xyz;
    let global_mode = i32(two_level.options.x + 0.5);
    let columns = i32(two_level.options.z + 0.5);
    let count = min(u32(max(floor((r.t_out - start) / h), -1.0) + 1.0), 65536u);

    var total = vec4<f32>(0.0);
    var hit_t = -1.0;
    // The open segment: its object (0 = none), table row, modes, and running state.
    var current = 0u;
    var row = 0;
    var mode = 0;
    var local = 0;
    var iso = 0.0;
    var domain = vec2<f32>(0.0, 1.0);
    var seg = vec4<f32>(0.0);
    var best = -1e30;
    var seg_first_t = -1.0;
    var seg_normal = vec3<f32>(0.0);
    var seg_done = false;
    var previous_value = NO_DATA;
    var previous_t = 0.0;

    for (var k = 0u; k <= count; k++) {
        // One step past the last sample closes the last segment.
        var id = 0u;
        var t = start + f32(k) * h;
        let q = r.q0 + r.dq * t;
        // Empty-space skipping: a brick no drawn object reaches holds only "no object"
        // samples, which close the open segment exactly as stepping through them would.
        var jump = false;
        if k < count {
            let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0) / ray.skip.y));
            let info = textureLoad(bricks, brick, 0);
            jump = ray.skip.x > 0.5 && info.x > info.y;
            // Inside a brick of one object no sample needs its 8 voxels; where the drawn
            // objects' union mask is below 0.5 (0.45: a margin for the filter's fixed-point
            // weights) none of them can exceed 0.5, so neither.
            if jump {
                id = 0u;
            } else if info.z >= 0.0 {
                id = u32(info.z);
            } else if two_level.options.y > 0.5 && drawn_union(q) < 0.45 {
                id = 0u;
            } else {
                id = object_at(q);
            }
        }
        if k < count && !jump {
            if i32(id) >= columns {
                id = 0u;
            } else if id != 0u && object_info(id, 0u).x < 0.5 {
                id = 0u;
            }
        }
        if id != current {
            // Close the open segment into the total with the global mode.
            if current != 0u && seg.a > 0.0 {
                total = combine(total, seg, global_mode);
                if hit_t < 0.0 {
                    hit_t = seg_first_t;
                    out.normal = vec4<f32>(seg_normal, 1.0);
                }
            }
            if global_mode == 0 && total.a >= ray.frame.w {
                break;
            }
            current = id;
            seg = vec4<f32>(0.0);
            best = -1e30;
            seg_first_t = -1.0;
            seg_done = false;
            previous_value = NO_DATA;
            if id != 0u {
                let info = object_info(id, 0u);
                row = i32(info.x + 0.5) - 1;
                mode = i32(info.y + 0.5);
                local = i32(info.z + 0.5);
                iso = info.w;
                domain = object_info(id, 1u).xy;
            }
        }
        if jump {
            let exit = brick_exit(q, r.dq, t) - 1e-4 * h;
            let next = min(max(ceil((exit - start) / h), f32(k + 1u)), f32(count));
            k = u32(next) - 1u;
            continue;
        }
        if current == 0u || seg_done {
            continue;
        }
        let v = value_at(q);
        if no_data(v) {
            previous_value = NO_DATA;
            continue;
        }
        if local == LOCAL_ISO {
            if v >= iso {
                var t_hit = t;
                if !no_data(previous_value) && v != previous_value {
                    t_hit = previous_t + h * (iso - previous_value) / (v - previous_value);
                }
                let p = r.p0 + r.dir * t_hit;
                let n = view_normal(shading_gradient(r.q0 + r.dq * t_hit, current));
                let hv = normalize(l + view_direction(p));
                let base = table_lookup_row(iso, row, domain).rgb;
                var c = base;
                if mode == MODE_SHADED || mode == MODE_ISO {
                    c = shade_surface(base, n, l, hv, 1);
                } else if mode == MODE_TONE {
                    c = tone(base, n, l);
                }
                seg = vec4<f32>(c, 1.0);
                seg_first_t = t_hit;
                seg_normal = n;
                seg_done = true;
                if global_mode == 0 {
                    total = combine(total, seg, global_mode);
                    if hit_t < 0.0 {
                        hit_t = seg_first_t;
                        out.normal = vec4<f32>(seg_normal, 1.0);
                    }
                    seg = vec4<f32>(0.0);
                    if total.a >= ray.frame.w {
                        break;
                    }
                }
            }
            previous_value = v;
            previous_t = t;
            continue;
        }
        let entry = table_lookup_row(v, row, domain);
        if entry.a <= 0.0 {
            continue;
        }
        var c = entry.rgb;
        var a = entry.a;
        var n = vec3<f32>(0.0);
        if mode == MODE_SHADED || mode == MODE_TONE || mode == MODE_CONTOURS {
            let p = r.p0 + r.dir * t;
            let g = shading_gradient(q, current);
            n = view_normal(g);
            let v_dir = view_direction(p);
            if mode == MODE_SHADED {
                c = clamp(c * phong_term(n, l, normalize(l + v_dir)), vec3<f32>(0.0), vec3<f32>(1.0));
            } else if mode == MODE_TONE {
                c = tone(c, n, l);
            } else {
                let g_norm = clamp(length(g) / max(ray.dims.w, 1e-20), 0.0, 1.0);
                a = a * g_norm * pow(1.0 - abs(dot(n, v_dir)), 8.0);
            }
        }
        if local == LOCAL_MIP {
            // Contours maximise their intensity, the other modes the data value.
            var key = v;
            if mode == MODE_CONTOURS {
                key = a;
            }
            if key > best && a > 0.0 {
                best = key;
                seg = vec4<f32>(c * a, a);
                seg_first_t = t;
                seg_normal = n;
            }
            continue;
        }
        // Over and sum: opacity corrected for the step (TF opacities are per voxel).
        a = 1.0 - pow(1.0 - clamp(a, 0.0, 1.0), step_voxels);
        if a <= 0.0 {
            continue;
        }
        if seg_first_t < 0.0 {
            seg_first_t = t;
            seg_normal = n;
        }
        if local == LOCAL_OVER {
            seg += (1.0 - seg.a) * vec4<f32>(c * a, a);
            // Early termination inside the segment: what follows adds less than 1 − alpha.
            seg_done = seg.a >= ray.frame.w;
        } else {
            seg += vec4<f32>(c * a, a);
        }
        if seg_done && global_mode == 0 {
            // Nothing more joins this segment: with global over, combine it now, and stop
            // the ray if it is opaque (the segment stays open, empty, until its object ends).
            total = combine(total, seg, global_mode);
            if hit_t < 0.0 {
                hit_t = seg_first_t;
                out.normal = vec4<f32>(seg_normal, 1.0);
            }
            seg = vec4<f32>(0.0);
            if total.a >= ray.frame.w {
                break;
            }
        }
    }
    out.color = min(total, vec4<f32>(1.0));
    if hit_t >= 0.0 {
        out.depth = to_window_depth(r.p0 + r.dir * hit_t);
    }
    return out;
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    return fragment_out(cast_two_level(in.position.xy));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !outside_frame(id.xy) {
        store_result(id.xy, cast_two_level(vec2<f32>(id.xy) + 0.5));
    }
}
