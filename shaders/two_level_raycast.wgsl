// TwoLevelRaycast: two-level volume rendering of a segmented volume (Hadwiger §2.2–2.4, Fig. 26).
// Each sample's object is decided by boundary filtering (§2.3): the binary mask of each object
// among the eight neighbouring voxels is filtered trilinearly and thresholded at 0.5 (ids are
// never interpolated as numbers); point sampling takes the nearest voxel's id. A ray is split
// into segments, maximal runs of samples of one object; each segment is composited with its
// object's local mode (over, mip, iso, sum) and rendering mode, and the segments are combined
// front to back with the global mode (over, mip, sum). Prepended: ray_common, ray_classify,
// ray_shade, ray_skip, ray_objects. The CPU reference is tests/common/two_level_reference.rs.
//
// Importance-driven rendering (Viola et al.; the buffers come from ImportanceCompositing, see
// shaders/importance.wgsl): a sample's object may be dropped (MImP: in the focus footprint
// everything but the focus, around it the context in front of the countersink, and behind it
// every object less important than the ray's most important one), get a level of
// sparseness S_o = I_o / Σ I (AImC, eq. 2) applied as opacity, colour saturation, screen door,
// a sparse rendering style or volume thinning (§V.C), or belong to the occluding part, whose segment's accumulated
// opacity is scaled by S_o / α_avg (VPImC, eq. 3). A segment is a run of samples of one object
// *and* one level (dense or sparse/occluding), so a context object splits at the countersink.

// (E, Σ I, 1 in the focus footprint, focus last hit) per pixel; E = countersink view depth. For
// MImP the second channel is the highest importance behind E (0 for a cutaway).
@group(1) @binding(4) var importance_buffer: texture_2d<f32>;
// (countersink view-space normal, distance to the footprint in pixels) per pixel.
@group(1) @binding(5) var importance_cut: texture_2d<f32>;
// 1×1: x = α_avg of the occluding context (VPImC's first pass), else 1.
@group(1) @binding(6) var occluder_stats: texture_2d<f32>;
// Volume thinning's ranks (hatchery_data::thinning): row = object id, column = key bin (of
// THIN_BINS over [0, 1]); the fraction of that object's voxels whose key is in a lower bin.
@group(1) @binding(7) var thin_ranks: texture_2d<f32>;
// The volume's world gradients at the voxel centres (value/gradient_texture.rs) where
// TL_THIN_GRADIENTS is 1 (CPU adapters): the key's gradients by one filtered fetch each, the
// same as central_gradient's six inside the grid; a 1³ blank otherwise.
@group(1) @binding(8) var thin_gradients: texture_3d<f32>;
override TL_THIN_GRADIENTS: i32 = 0;

// world_gradient(p) for the thinning key: from thin_gradients where bound.
fn thinning_gradient(p: vec3<f32>) -> vec3<f32> {
    if TL_THIN_GRADIENTS != 0 {
        let q = (ray.to_voxel * vec4<f32>(p, 1.0)).xyz;
        return textureSampleLevel(thin_gradients, linear_clamp, grid_uv(q), 0.0).xyz;
    }
    return world_gradient(p);
}

// world_hessian(p, h) for the thinning key, its six gradients by thinning_gradient.
fn thinning_hessian(p: vec3<f32>, h: f32) -> mat3x3<f32> {
    if TL_THIN_GRADIENTS == 0 {
        return world_hessian(p, h);
    }
    var columns: array<vec3<f32>, 3>;
    for (var axis = 0; axis < 3; axis++) {
        var e = vec3<f32>(0.0);
        e[axis] = h;
        columns[axis] = (thinning_gradient(p + e) - thinning_gradient(p - e)) / (2.0 * h);
    }
    let hessian = mat3x3<f32>(columns[0], columns[1], columns[2]);
    return 0.5 * (hessian + transpose(hessian));
}
const THIN_BINS: f32 = 256.0;

// The rank within object `id` of thinning key `key`: the fraction of its voxels sorted before.
fn thinning_rank(id: u32, key: f32) -> f32 {
    let bin = min(u32(key * THIN_BINS), u32(THIN_BINS) - 1u);
    return textureLoad(thin_ranks, vec2<i32>(i32(bin), i32(id)), 0).r;
}

const IMP_NONE: u32 = 0u;
const IMP_MIMP: u32 = 1u;
const IMP_AIMC_IMAGE: u32 = 2u;
const IMP_AIMC_OBJECT: u32 = 3u;
const IMP_VPIMC: u32 = 4u;
const SPARSE_OPACITY: u32 = 0u;
const SPARSE_SATURATION: u32 = 1u;
const SPARSE_SCREEN_DOOR: u32 = 2u;
const SPARSE_STYLE: u32 = 3u;
const SPARSE_THINNING: u32 = 4u;

// Volume thinning (Viola et al. §V.C: "Voxels of an object are sorted according to two sorting
// keys. The first sorting key is gradient magnitude, the second sorting key is curvature
// magnitude of the iso-surface through the voxel."): the key of the sample at voxel-space q,
// world p, in [0, 1] — (L + κ̂) / B with L = min(⌊B · |∇f| / |∇f|max⌋, B − 1) the sample's level of
// gradient magnitude (B levels, |∇f|max the volume's largest) and κ̂ = min(√(κ1² + κ2²) · w, 1)
// its curvature magnitude in units of w, the smallest spacing (curvature_shape: the Hessian by
// central differences of the gradient at ±w, or the B-spline's own). Sorting samples by this key
// sorts them by level, then by curvature; a sample of level of sparseness S is kept where the
// fraction of its object's voxels sorted before it (`thinning_rank`) is at least 1 − S, so the
// last S of the object's voxels in this order remain (0 where the gradient vanishes: dropped
// first).
fn thinning_key(q: vec3<f32>, p: vec3<f32>) -> f32 {
    var g = vec3<f32>(0.0);
    if TL_THIN_GRADIENTS != 0 {
        g = textureSampleLevel(thin_gradients, linear_clamp, grid_uv(q), 0.0).xyz;
    } else {
        g = gradient_at(q);
    }
    let g_length = length(g);
    if g_length < 1e-12 {
        return 0.0;
    }
    let bands = max(two_level.thin_bands, 1.0);
    let l = min(floor(bands * min(g_length * two_level.thin_gradient, 1.0)), bands - 1.0);
    let w = two_level.thin_step;
    let shape = shape_operator(g, g_length, thinning_hessian(p, w));
    let kappa = min(curvature_magnitude(shape) * w, 1.0);
    return (l + kappa) / bands;
}

// Screen-door threshold of voxel-space point q: a low-discrepancy value over the voxel lattice
// (the R3 sequence), so a level of sparseness S keeps an even fraction S of the voxels.
fn screen_door(q: vec3<f32>) -> f32 {
    let v = floor(q + 0.5);
    return fract(0.5 + dot(v, vec3<f32>(0.8191725134, 0.6710436067, 0.5497004779)));
}

// A level of sparseness s applied to a sample's colour and opacity (opacity and saturation
// levels); the screen door and sparse styles are applied by the caller.
fn sparse_sample(c: vec3<f32>, a: f32, s: f32, level: u32) -> vec4<f32> {
    if level == SPARSE_SATURATION {
        let grey = vec3<f32>(dot(c, vec3<f32>(0.299, 0.587, 0.114)));
        return vec4<f32>(mix(grey, c, s), a * s);
    }
    return vec4<f32>(c, a * s);
}

// A closed segment with VPImC's correction: its accumulated opacity (and premultiplied colour)
// scaled by `scale` = S_o / α_avg, never beyond opaque.
fn corrected(seg: vec4<f32>, scale: f32) -> vec4<f32> {
    if scale == 1.0 || seg.a <= 0.0 {
        return seg;
    }
    return seg * min(scale, 1.0 / seg.a);
}

const MODE_DVR: u32 = 0u;
const MODE_SHADED: u32 = 1u;
const MODE_TONE: u32 = 2u;
const MODE_CONTOURS: u32 = 3u;
const MODE_MIP: u32 = 4u;
const MODE_ISO: u32 = 5u;
const GLOBAL_OVER: u32 = 0u;
const GLOBAL_MIP: u32 = 1u;
const GLOBAL_SUM: u32 = 2u;
const LOCAL_OVER: u32 = 0u;
const LOCAL_MIP: u32 = 1u;
const LOCAL_ISO: u32 = 2u;
const LOCAL_SUM: u32 = 3u;

// Pipeline constants (TwoLevelRaycast specialises its pipeline on what the table and the node
// use; −1, the default, reads the uniforms and keeps every branch): the global mode, the
// importance method, and bit masks of the rendering modes (1 << MODE_*)
// and local compositing modes (1 << LOCAL_*) that any drawn object (or the sparse style) has.
// On lavapipe every branch compiled into the march costs per sample even when no lane takes it.
override TL_GLOBAL: i32 = -1;
override TL_METHOD: i32 = -1;
override TL_MODES: i32 = -1;
override TL_LOCALS: i32 = -1;
// 1 where the level of sparseness is volume thinning (its key is compiled into the march only
// then), 0 where it is not; −1 reads the uniform.
override TL_THINNING: i32 = -1;

fn global_mode_of() -> u32 {
    return select(two_level.global_mode, u32(TL_GLOBAL), TL_GLOBAL >= 0);
}

fn method_of() -> u32 {
    return select(two_level.method, u32(TL_METHOD), TL_METHOD >= 0);
}

// Whether an object may have rendering mode `m` / local compositing `c`.
fn may_mode(m: u32) -> bool {
    return (TL_MODES & (1 << m)) != 0;
}

fn may_local(c: u32) -> bool {
    return (TL_LOCALS & (1 << c)) != 0;
}

// Whether the level of sparseness is volume thinning.
fn thinning(level: u32) -> bool {
    return select(level == SPARSE_THINNING, TL_THINNING > 0, TL_THINNING >= 0);
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
fn combine(total: vec4<f32>, seg: vec4<f32>, global_mode: u32) -> vec4<f32> {
    let s = vec4<f32>(seg.rgb, min(seg.a, 1.0));
    if global_mode == GLOBAL_OVER {
        return total + (1.0 - total.a) * s;
    }
    if global_mode == GLOBAL_MIP {
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
    let h = ray.step_world;
    let step_voxels = ray.step_voxels;
    var start = r.t_in;
    if ray.jitter != 0u {
        start += h * hash(position);
    }
    let l = ray.light;
    let global_mode = global_mode_of();
    let columns = two_level.columns;
    var count = min(u32(max(floor((r.t_out - start) / h), -1.0) + 1.0), 65536u);

    // Importance-driven rendering: this pixel's buffers and the ray's view depth z(t).
    let method = method_of();
    let level = two_level.level;
    let focus = two_level.focus;
    let first_pass = two_level.first_pass != 0u;
    var imp = vec4<f32>(-1.0e30, 1.0, 0.0, -1.0);
    var cut = vec4<f32>(0.0, 0.0, 1.0, 0.0);
    var alpha_avg = 1.0;
    if method != IMP_NONE {
        imp = textureLoad(importance_buffer, vec2<i32>(position), 0);
        cut = textureLoad(importance_cut, vec2<i32>(position), 0);
        alpha_avg = max(textureLoad(occluder_stats, vec2<i32>(0), 0).x, 1e-6);
    }
    let z0 = -(ray.view * vec4<f32>(r.p0, 1.0)).z;
    let dz = -(ray.view * vec4<f32>(r.dir, 0.0)).z;
    // MImP: where the countersink cuts this ray (t), for the cut's shading normal.
    var t_cut = -1.0e30;
    if method == IMP_MIMP && imp.z < 0.5 && imp.x > -1.0e29 && abs(dz) > 1e-12 {
        t_cut = (imp.x - z0) / dz;
    }
    // Samples every sample of which importance drops are not marched (one sample of margin
    // each way, taken by the rule below): MImP drops the context in front of the countersink
    // around the footprint, so the ray starts at the cut; VPImC's first pass draws only the
    // context in front of the focus in its footprint, so it returns at once elsewhere and
    // stops at the focus's first hit there.
    var k_first = 0u;
    if method == IMP_MIMP && t_cut > start && dz > 1e-12 {
        k_first = u32(min(max(floor((t_cut - start) / h) - 1.0, 0.0), f32(count)));
    }
    if method == IMP_VPIMC && first_pass {
        if imp.z < 0.5 {
            return out;
        }
        if dz > 1e-12 {
            let t_focus = (imp.x - z0) / dz;
            count = min(count, u32(max(ceil((t_focus - start) / h) + 1.0, 0.0)));
        }
    }

    var total = vec4<f32>(0.0);
    var hit_t = -1.0;
    // The open segment: its key (object id · 2 + 1 when sparse/occluding; 0 = none), object,
    // table row, modes, VPImC scale, and running state.
    var current_key = 0u;
    var current = 0u;
    var scale = 1.0;
    var row = 0;
    var mode = MODE_DVR;
    var local = LOCAL_OVER;
    var iso = 0.0;
    var domain = vec2<f32>(0.0, 1.0);
    var seg = vec4<f32>(0.0);
    var best = -1e30;
    var seg_first_t = -1.0;
    var seg_normal = vec3<f32>(0.0);
    var seg_done = false;
    var previous_value = NO_DATA;
    var previous_t = 0.0;

    var info_brick = vec3<i32>(-1);
    var info = vec4<f32>(0.0);
    for (var k = k_first; k <= count; k++) {
        // One step past the last sample closes the last segment.
        var id = 0u;
        var t = start + f32(k) * h;
        let q = r.q0 + r.dq * t;
        // Empty-space skipping: a brick no drawn object reaches holds only "no object"
        // samples, which close the open segment exactly as stepping through them would.
        var jump = false;
        if k < count {
            // Consecutive samples mostly share a brick: fetch its entry when the brick changes.
            let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims - 1.0) / f32(ray.brick_size)));
            if any(brick != info_brick) {
                info = textureLoad(bricks, brick, 0);
                info_brick = brick;
            }
            jump = ray.skip_empty != 0u && info.x > info.y;
            // Inside a brick of one object no sample needs its 8 voxels; where the drawn
            // objects' union mask is below 0.5 (0.45: a margin for the filter's fixed-point
            // weights) none of them can exceed 0.5, so neither.
            if jump {
                id = 0u;
            } else if info.z >= 0.0 {
                id = u32(info.z);
            } else if boundary_filtered() && drawn_union(q) < 0.45 {
                id = 0u;
            } else {
                id = object_at(q);
            }
        }
        if k < count && !jump {
            if id >= columns {
                id = 0u;
            } else if id != 0u && id != current && object_info(id, 0u).x < 0.5 {
                // (The open segment's object is drawn: it passed this test when it opened.)
                id = 0u;
            }
        }
        // Importance: drop the sample, or give it a level of sparseness s (flag: sparse or
        // occluding, a segment of its own).
        var flag = 0u;
        var s = 1.0;
        if method != IMP_NONE && id != 0u {
            let z = z0 + dz * t;
            let in_front = z < imp.x;
            let s_o = clamp(object_info(id, 1u).z / max(imp.y, 1e-6), 0.0, 1.0);
            if method == IMP_MIMP {
                // In the footprint only the focus; elsewhere nothing in front of the
                // countersink, and behind it only the ray's most important object (imp.y, the
                // per-ray rule; 0 for a cutaway, which keeps every object). The open segment's
                // object passed this test when it opened.
                let weaker = id != current && max(object_info(id, 1u).z, 0.0) < imp.y;
                if (imp.z > 0.5 && id != focus) || (imp.z < 0.5 && (in_front || weaker)) {
                    id = 0u;
                }
            } else if method == IMP_VPIMC {
                // The occluding part: context in front of the focus, in its footprint only.
                if id != focus && in_front && imp.z > 0.5 {
                    flag = 1u;
                    s = s_o;
                } else if first_pass {
                    id = 0u;
                }
            } else if method == IMP_AIMC_IMAGE || (id != focus && in_front) {
                s = s_o;
                // In the countersink around the footprint the ray misses the focus, so the sum
                // lacks it: count it, as the context there is in front of its surroundings.
                if method == IMP_AIMC_OBJECT && imp.z < 0.5 {
                    let with_focus = imp.y + object_info(focus, 1u).z;
                    s = clamp(object_info(id, 1u).z / max(with_focus, 1e-6), 0.0, 1.0);
                }
                // The focus keeps its own style; only the context turns sparse.
                if level == SPARSE_STYLE && s < 0.999 && id != focus {
                    flag = 1u;
                }
            }
        }
        let key = id * 2u + flag;
        if key != current_key {
            // Close the open segment into the total with the global mode.
            if current != 0u && seg.a > 0.0 {
                seg = corrected(seg, scale);
                total = combine(total, seg, global_mode);
                if hit_t < 0.0 {
                    hit_t = seg_first_t;
                    out.normal = vec4<f32>(seg_normal, 1.0);
                }
            }
            if global_mode == GLOBAL_OVER && total.a >= ray.early_termination {
                break;
            }
            current = id;
            current_key = key;
            scale = 1.0;
            seg = vec4<f32>(0.0);
            best = -1e30;
            seg_first_t = -1.0;
            seg_done = false;
            previous_value = NO_DATA;
            if id != 0u {
                let info = object_info(id, 0u);
                row = i32(info.x + 0.5) - 1;
                mode = u32(info.y + 0.5);
                local = u32(info.z + 0.5);
                iso = info.w;
                domain = object_info(id, 1u).xy;
                if flag == 1u && method == IMP_VPIMC && !first_pass {
                    scale = s / alpha_avg;
                } else if flag == 1u && method != IMP_VPIMC {
                    mode = two_level.sparse_mode;
                    local = two_level.sparse_local;
                }
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
        // VPImC and sparse styles change the segment, not each sample; the screen door keeps
        // a fraction s of the voxels as they are.
        if flag == 1u {
            s = 1.0;
        }
        if s < 1.0 && level == SPARSE_SCREEN_DOOR {
            if screen_door(q) >= s {
                continue;
            }
            s = 1.0;
        }
        // Volume thinning keeps a context sample, unchanged, where its rank within its object
        // is at least 1 − s; the focus is never thinned (in image-space AImC it keeps opacity
        // × s, as with a sparse style). Its key needs a Hessian (36 fetches), so a DVR sample
        // is decided once its transfer function gives it opacity: samples that add nothing
        // anyway skip it. An iso object's samples are decided before the crossing test (a
        // thinned sample is not the one the crossing interpolates from); a "no data" sample
        // now restarts the crossing before it is decided.
        let thinned = s < 1.0 && thinning(level) && current != focus;
        // Just behind a countersink cut the cut surface shades the context (MImP).
        let on_cut = method == IMP_MIMP && t >= t_cut && t - t_cut <= two_level.cut_band;
        let v = value_at(q);
        if no_data(v) {
            previous_value = NO_DATA;
            continue;
        }
        if may_local(LOCAL_ISO) && local == LOCAL_ISO {
            if thinned {
                if thinning_rank(current, thinning_key(q, r.p0 + r.dir * t)) < 1.0 - s {
                    continue;
                }
                s = 1.0;
            }
            if v >= iso {
                var t_hit = t;
                if !no_data(previous_value) && v != previous_value {
                    t_hit = previous_t + h * (iso - previous_value) / (v - previous_value);
                }
                let p = r.p0 + r.dir * t_hit;
                var n = view_normal(surface_gradient(r.q0 + r.dq * t_hit, current));
                if on_cut {
                    n = cut.xyz;
                }
                let hv = normalize(l + view_direction(p));
                let base = table_lookup_row(iso, row, domain).rgb;
                var c = base;
                if (may_mode(MODE_SHADED) && mode == MODE_SHADED) || (may_mode(MODE_ISO) && mode == MODE_ISO) {
                    c = shade_surface(base, n, l, hv, 1);
                } else if may_mode(MODE_TONE) && mode == MODE_TONE {
                    c = tone(base, n, l);
                }
                let sparse = sparse_sample(c, 1.0, s, level);
                seg = vec4<f32>(sparse.rgb * sparse.a, sparse.a);
                seg_first_t = t_hit;
                seg_normal = n;
                seg_done = true;
                if global_mode == GLOBAL_OVER {
                    total = combine(total, corrected(seg, scale), global_mode);
                    if hit_t < 0.0 {
                        hit_t = seg_first_t;
                        out.normal = vec4<f32>(seg_normal, 1.0);
                    }
                    seg = vec4<f32>(0.0);
                    if total.a >= ray.early_termination {
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
        if thinned {
            if thinning_rank(current, thinning_key(q, r.p0 + r.dir * t)) < 1.0 - s {
                continue;
            }
            s = 1.0;
        }
        var c = entry.rgb;
        var a = entry.a;
        var n = vec3<f32>(0.0);
        let shaded = may_mode(MODE_SHADED) && mode == MODE_SHADED;
        let toned = may_mode(MODE_TONE) && mode == MODE_TONE;
        let contoured = may_mode(MODE_CONTOURS) && mode == MODE_CONTOURS;
        if shaded || toned || contoured {
            let p = r.p0 + r.dir * t;
            let g = shading_gradient(q, current);
            n = view_normal(g);
            if on_cut {
                n = cut.xyz;
            }
            let v_dir = view_direction(p);
            if shaded {
                c = clamp(c * phong_term(n, l, normalize(l + v_dir)), vec3<f32>(0.0), vec3<f32>(1.0));
            } else if toned {
                c = tone(c, n, l);
            } else {
                let g_norm = clamp(length(g) / max(ray.max_gradient, 1e-20), 0.0, 1.0);
                a = a * g_norm * pow(1.0 - abs(dot(n, v_dir)), 8.0);
            }
        }
        if s < 1.0 {
            let sparse = sparse_sample(c, a, s, level);
            c = sparse.rgb;
            a = sparse.a;
        }
        if may_local(LOCAL_MIP) && local == LOCAL_MIP {
            // Contours maximise their intensity, the other modes the data value.
            var key = v;
            if contoured {
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
        if !may_local(LOCAL_SUM) || local == LOCAL_OVER {
            seg += (1.0 - seg.a) * vec4<f32>(c * a, a);
            // Early termination inside the segment: what follows adds less than 1 − alpha.
            seg_done = seg.a >= ray.early_termination;
        } else {
            seg += vec4<f32>(c * a, a);
        }
        if seg_done && global_mode == GLOBAL_OVER {
            // Nothing more joins this segment: with global over, combine it now, and stop
            // the ray if it is opaque (the segment stays open, empty, until its object ends).
            total = combine(total, corrected(seg, scale), global_mode);
            if hit_t < 0.0 {
                hit_t = seg_first_t;
                out.normal = vec4<f32>(seg_normal, 1.0);
            }
            seg = vec4<f32>(0.0);
            if total.a >= ray.early_termination {
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
