// Raycast: one transfer function along the whole ray. Direct volume rendering (front-to-back,
// eq. 1 of the context-preserving paper), maximum intensity projection, and the first hit of an
// iso value. Prepended: ray_common (uniforms, sampling, the primary ray), ray_classify (tables),
// ray_shade (eq. 3, 5, 8, style TFs), ray_skip (empty-space skipping).

// Maximum intensity projection on its own loop: a sample and a maximum per step. The other
// modes' state is not live here, and there is no brick skipping: on lavapipe this plain loop is
// 15× faster than MIP inside the shared loop and 4× faster than with the brick test (probably
// its jumps make neighbouring pixels' loops diverge); docs/benchmarks.md.
fn cast_mip(r: PrimaryRay, start: f32, h: f32) -> RayResult {
    var out: RayResult;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;
    let count = min(u32(max(floor((r.t_out - start) / h), -1.0) + 1.0), 65536u);
    // The maximum of the texels themselves: texels map to data values increasingly
    // (ray.texel_values.x < ray.texel_values.y), so the largest texel is the largest value, mapped once at the
    // end. Same samples as value_at; the same winner, except where two texels map to one f32
    // value (a tie there keeps the earliest sample, here the larger texel: same colour). "No data"
    // (texels below −0.5) never wins: the start is the float just below −0.5.
    var best = bitcast<f32>(0xbf000001u);
    var best_t = -1.0;
    for (var k = 0u; k < count; k++) {
        let t = start + f32(k) * h;
        let texel = texel_at(r.q0 + r.dq * t);
        if texel > best {
            best = texel;
            best_t = t;
        }
    }
    if best_t < 0.0 {
        return out;
    }
    let entry = table_lookup(ray.texel_values.x + best * (ray.texel_values.y - ray.texel_values.x));
    out.color = vec4<f32>(entry.rgb * entry.a, entry.a);
    out.depth = to_window_depth(r.p0 + r.dir * best_t);
    out.normal = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    return out;
}

// Strokes embedded in the volume rendering (Yuan & Chen 2005 §5): a stroke mask and the depth
// of the surface it was drawn on. Where a stroke covers a pixel its colour, with opacity
// coverage × alpha, is composited as a layer at the stroke's depth: under what the ray gathered
// in front of it, over what lies behind (an opaque stroke ends the ray: no sample behind it
// contributes; a soft edge lets the volume behind show through). DVR only. ray.embed_strokes = 1 when strokes are bound; ray.rho =
// the global alpha ρ that scales every sample's opacity.
@group(1) @binding(0) var stroke_depth: texture_depth_2d;
@group(1) @binding(1) var stroke_mask: texture_2d<f32>;
struct Strokes {
    // Straight RGBA of the strokes.
    color: vec4<f32>,
};
@group(1) @binding(2) var<uniform> strokes: Strokes;

// The stroke at `position`: (coverage, t along the ray where it lies; 1e30 for none).
fn stroke_at(position: vec2<f32>, p0: vec3<f32>, dir: vec3<f32>) -> vec2<f32> {
    if ray.embed_strokes == 0u {
        return vec2<f32>(0.0, 1e30);
    }
    let pixel = vec2<i32>(floor(position));
    let m = clamp(textureLoad(stroke_mask, pixel, 0).r, 0.0, 1.0);
    let z = textureLoad(stroke_depth, pixel, 0);
    if m <= 0.0 || z >= 1.0 {
        return vec2<f32>(0.0, 1e30);
    }
    let ndc = vec2<f32>(position.x / ray.frame.x * 2.0 - 1.0, 1.0 - position.y / ray.frame.y * 2.0);
    let h4 = ray.inv_view_proj * vec4<f32>(ndc, z, 1.0);
    return vec2<f32>(m, dot(h4.xyz / h4.w - p0, dir));
}

// The mode (a RAY_MODE_* constant) and the shading (SHADING_*) as pipeline constants: Raycast makes one
// pipeline per combination, the compiler folds the constants and drops the other modes' code
// from the loop. −1 (the default, for other programs) reads them from the uniform instead.
override RAY_MODE: i32 = -1;
override RAY_SHADING: i32 = -1;

fn ray_mode() -> u32 {
    return select(ray.mode, u32(RAY_MODE), RAY_MODE >= 0);
}

// Svakhine, Jang, Ebert & Gaither 2005, Table 1 (docs/enhancement.md), DVR: the banding widget
// maps the transfer function's opacity o_o (where it is not 0) to ((1 + sin(o_o·π·m)) / 2)^n
// before shading; boundary enhancement multiplies the sample's opacity by |∇P|^n (|∇P| divided
// by the volume's largest gradient magnitude, Ray.max_gradient) and silhouette enhancement by
// (1 − |∇P̂·V|)^n, after shading and before ρ and the step correction. RAY_ENHANCE holds the
// ENHANCE_* bits of those that are on; the Raycast node specialises it per pipeline, so with 0
// (the default) none of this code is in the loop.
const ENHANCE_BOUNDARY: u32 = 1u;
const ENHANCE_SILHOUETTE: u32 = 2u;
const ENHANCE_BANDING: u32 = 4u;
override RAY_ENHANCE: u32 = 0u;

struct Enhancement {
    // The exponents n of boundary and silhouette enhancement, the banding period m and power n.
    boundary: f32,
    silhouette: f32,
    banding_period: f32,
    banding_power: f32,
    // A 2-D transfer function's second domain (RAY_TF2D != 0; docs/transfer_functions_2d.md).
    second_domain: vec2<f32>,
    // The second field's value range: second_field's w is (S − min) / (max − min).
    second_range: vec2<f32>,
};
@group(1) @binding(3) var<uniform> enhancement: Enhancement;

// Svakhine et al. 2005 §3.2–3.3: fields besides the rendered one, on its grid. second_field:
// xyz = ∇S / max |∇S| (world axes), w = S normalised over its range (−1: no data); vector_field: xyz =
// U / max |U|. RAY_ENHANCE_FIELD (an ENHANCE_FROM_* constant) says which one boundary and
// silhouette enhancement measure; 1³ blanks stand in for fields a pipeline does not read.
@group(1) @binding(4) var second_field: texture_3d<f32>;
@group(1) @binding(5) var vector_field: texture_3d<f32>;
const ENHANCE_FROM_RENDERED: u32 = 0u;
const ENHANCE_FROM_SECOND: u32 = 1u;
const ENHANCE_FROM_VECTOR: u32 = 2u;
override RAY_ENHANCE_FIELD: u32 = 0u;

// A field texture on the volume's grid at voxel-space q (trilinear, as the volume is sampled).
fn field_sample(field: texture_3d<f32>, q: vec3<f32>) -> vec4<f32> {
    let p = clamp(q, vec3<f32>(0.0), ray.dims - 1.0);
    return textureSampleLevel(field, linear_clamp, (p + 0.5) / ray.dims, 0.0);
}

// 2-D transfer functions (Kniss et al. 2002, Svakhine et al. 2005 §3.3): tf_table holds a
// LUT_SIZE × LUT_SIZE table over value × a second coordinate, RAY_TF2D says which (a TF2D_*
// constant; 0: a 1-D table, none of this code is in the loop). Specialised by the Raycast node.
const TF2D_GRADIENT: u32 = 1u;
const TF2D_LAPLACIAN: u32 = 2u;
const TF2D_SECOND: u32 = 3u;
override RAY_TF2D: u32 = 0u;

fn enhanced(bit: u32) -> bool {
    return (RAY_ENHANCE & bit) != 0u;
}

// x^n for x in [0, 1] and n > 0 (0 for x = 0, where pow is undefined).
fn power(x: f32, n: f32) -> f32 {
    if x <= 0.0 {
        return 0.0;
    }
    return pow(min(x, 1.0), n);
}

// The banding widget: ((1 + sin(o·π·m)) / 2)^n.
fn banding(o: f32) -> f32 {
    let pi = 3.14159265358979;
    return power(0.5 * (1.0 + sin(o * pi * enhancement.banding_period)), enhancement.banding_power);
}

// The factor of boundary and silhouette enhancement on a sample with normalised gradient magnitude
// g_norm ∈ [0, 1], view-space unit normal n (0 where the gradient vanishes) and direction to the
// viewer v.
fn enhancement_factor(g_norm: f32, n: vec3<f32>, v: vec3<f32>) -> f32 {
    var f = 1.0;
    if enhanced(ENHANCE_BOUNDARY) {
        f *= power(g_norm, enhancement.boundary);
    }
    if enhanced(ENHANCE_SILHOUETTE) {
        f *= power(1.0 - abs(dot(n, v)), enhancement.silhouette);
    }
    return f;
}

// Pre-integrated transfer function (Engel et al. 2001; hatchery_data::preintegration): 1 when
// tf_table holds the segment table in rows 1 … LUT_SIZE (row 1 + front position, column back
// position). Specialised by the Raycast node.
override RAY_PREINTEGRATED: i32 = 0;

fn preintegrated() -> bool {
    return RAY_PREINTEGRATED == 1;
}

// Position of data value v in the transfer function's table, [0, LUT_SIZE − 1].
fn table_position(v: f32) -> f32 {
    let span = ray.tf_domain.y - ray.tf_domain.x;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((v - ray.tf_domain.x) / span, 0.0, 1.0);
    }
    return u * (LUT_SIZE - 1.0);
}

// The segment whose value runs from `front` to `back`: premultiplied colour and opacity, for
// the step, bilinear between the table's entries.
fn preintegrated_lookup(front: f32, back: f32) -> vec4<f32> {
    let x = table_position(back);
    let y = table_position(front);
    let k = min(floor(vec2<f32>(x, y)), vec2<f32>(LUT_SIZE - 2.0));
    let f = vec2<f32>(x, y) - k;
    let c = vec2<i32>(i32(k.x), 1 + i32(k.y));
    let a = textureLoad(tf_table, c, 0);
    let b = textureLoad(tf_table, c + vec2<i32>(1, 0), 0);
    let d = textureLoad(tf_table, c + vec2<i32>(0, 1), 0);
    let e = textureLoad(tf_table, c + vec2<i32>(1, 1), 0);
    return mix(mix(a, b, f.x), mix(d, e, f.x), f.y);
}

fn cast_ray(position: vec2<f32>) -> RayResult {
    var out: RayResult;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;

    let r = primary_ray(position);
    let stroke = stroke_at(position, r.p0, r.dir);
    let stroke_alpha = stroke.x * strokes.color.a;
    let dvr = ray_mode() == RAY_MODE_DVR;
    if !r.hits {
        if dvr {
            out.color = vec4<f32>(strokes.color.rgb * stroke_alpha, stroke_alpha);
        }
        return out;
    }
    let p0 = r.p0;
    let dir = r.dir;
    let q0 = r.q0;
    let dq = r.dq;
    let t_out = r.t_out;
    // DVR composites an embedded stroke at its depth; MIP and iso ignore strokes.
    var stroke_pending = dvr && stroke_alpha > 0.0;

    let h = ray.step_world;
    let step_voxels = ray.step_voxels;
    var start = r.t_in;
    if ray.jitter != 0u {
        start += h * hash(position);
    }
    let mode = ray_mode();
    let shading = select(ray.shading, u32(RAY_SHADING), RAY_SHADING >= 0);
    let l = ray.light;

    if mode == RAY_MODE_MIP {
        return cast_mip(r, start, h);
    }

    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var best = -1e30;
    var best_t = -1.0;
    var previous_value = 0.0;
    var previous_t = 0.0;
    var previous_normal = vec3<f32>(0.0);
    var hit_t = -1.0;
    // Pre-integration: the value at the previous sample (NO_DATA: none; the segment restarts).
    var segment_front = NO_DATA;
    let count = min(u32(max(floor((t_out - start) / h), -1.0) + 1.0), 65536u);

    let skipping = ray.skip_empty != 0u;
    for (var k = 0u; k < count; k++) {
        let t = start + f32(k) * h;
        if stroke_pending && t >= stroke.y {
            stroke_pending = false;
            color += (1.0 - alpha) * stroke_alpha * strokes.color.rgb;
            alpha += (1.0 - alpha) * stroke_alpha;
            if alpha >= ray.early_termination {
                break;
            }
        }
        let p = p0 + dir * t;
        let q = q0 + dq * t;
        if skipping {
            // Bricks whose samples cannot change the result: DVR, all transparent; MIP, none
            // above the maximum so far; iso, all below the iso value.
            let range = brick_range(q);
            // An empty range (min > max) holds only "no data".
            var skip = range.x > range.y;
            if !skip && mode == RAY_MODE_DVR {
                var seen = range;
                if preintegrated() && !no_data(segment_front) {
                    // The segment into the brick runs from the previous sample's value.
                    seen = vec2<f32>(min(seen.x, segment_front), max(seen.y, segment_front));
                }
                skip = range_is_invisible(seen);
            } else if !skip && mode == RAY_MODE_MIP {
                skip = range.y <= best;
            } else if !skip {
                skip = range.y < ray.iso;
            }
            if skip {
                // Jump to the first sample past the brick, on the same lattice of t, so the
                // samples taken are exactly those taken without skipping.
                let exit = brick_exit(q, dq, t) - 1e-4 * h;
                let next = min(max(ceil((exit - start) / h), f32(k + 1u)), f32(count));
                if mode == RAY_MODE_ISO {
                    // The iso hit interpolates from the sample before it: take that one.
                    let t_before = start + (next - 1.0) * h;
                    previous_value = value_at(q0 + dq * t_before);
                    previous_t = t_before;
                }
                if preintegrated() {
                    // The next segment starts at the sample before it, as without skipping.
                    segment_front = value_at(q0 + dq * (start + (next - 1.0) * h));
                }
                k = u32(next) - 1u;
                // κv restarts after a gap, as after any transparent sample.
                previous_normal = vec3<f32>(0.0);
                continue;
            }
        }
        let v = value_at(q);
        if no_data(v) {
            // Transparent; the next iso crossing starts afresh, κv restarts after the gap.
            previous_value = NO_DATA;
            previous_normal = vec3<f32>(0.0);
            segment_front = NO_DATA;
            continue;
        }

        if mode == RAY_MODE_MIP {
            if v > best {
                best = v;
                best_t = t;
            }
            continue;
        }
        if mode == RAY_MODE_ISO {
            if v >= ray.iso {
                var t_hit = t;
                if k > 0u && v != previous_value && !no_data(previous_value) {
                    t_hit = previous_t + h * (ray.iso - previous_value) / (v - previous_value);
                }
                hit_t = t_hit;
                break;
            }
            previous_value = v;
            previous_t = t;
            continue;
        }

        // Direct volume rendering. Classify first: samples the transfer function makes fully
        // transparent contribute nothing, so they skip the six gradient fetches.
        let row = table_row_at(q);
        var entry = vec4<f32>(0.0);
        // The gradient, taken before classification where a 2-D function needs its magnitude.
        var g = vec3<f32>(0.0);
        if RAY_TF2D == TF2D_GRADIENT {
            g = gradient_at(q);
            let s = clamp(length(g) / max(ray.max_gradient, 1e-20), 0.0, 1.0);
            entry = table2d_lookup(v, s, enhancement.second_domain);
        } else if RAY_TF2D == TF2D_LAPLACIAN {
            entry = table2d_lookup(v, laplacian_at(q), enhancement.second_domain);
        } else if RAY_TF2D == TF2D_SECOND {
            // w < 0: the second field has no data here (transparent, as for the volume).
            let w = field_sample(second_field, q).w;
            let range = enhancement.second_range;
            if w >= 0.0 {
                entry = table2d_lookup(v, range.x + w * (range.y - range.x), enhancement.second_domain);
            }
        } else {
            entry = table_lookup_row(v, row.row, row.domain);
        }
        // Colour TFs keep opacity in .a, style TFs α_u in .y.
        var classified = entry.a;
        if shading == SHADING_STYLE {
            classified = entry.y;
        }
        var segment = vec4<f32>(0.0);
        if preintegrated() {
            // The segment from the previous sample to this one (this one alone at the start).
            segment = preintegrated_lookup(select(segment_front, v, no_data(segment_front)), v);
            segment_front = v;
            classified = segment.a;
        }
        if classified <= 0.0 {
            // κv restarts after a gap (no normal to compare with).
            previous_normal = vec3<f32>(0.0);
            continue;
        }
        if enhanced(ENHANCE_BANDING) {
            // The banding widget maps the classified opacity (α_u of a style TF).
            if shading == SHADING_STYLE {
                entry.y = banding(entry.y);
            } else {
                entry.a = banding(entry.a);
            }
        }
        if RAY_TF2D != TF2D_GRADIENT {
            g = gradient_at(q);
        }
        let g_length = length(g);
        let n = view_normal(g);
        let v_dir = view_direction(p);
        let hv = normalize(l + v_dir);
        let g_norm = clamp(g_length / max(ray.max_gradient, 1e-20), 0.0, 1.0);

        var c = vec3<f32>(0.0);
        var a = 0.0;
        // Eq. 3's Phong term, computed once for the colour and eq. 5.
        var phong = 1.0;
        if shading == SHADING_STYLE {
            // κv: angle between successive normals over the step (§3.3).
            var kappa_v = 0.0;
            if k > 0u && dot(previous_normal, previous_normal) > 0.5 && g_length > 1e-12 {
                kappa_v = acos(clamp(dot(n, previous_normal), -1.0, 1.0)) / h;
            }
            let styled = style_shade(entry, row, n, v_dir, g_norm, kappa_v);
            c = styled.rgb;
            a = styled.a;
            previous_normal = n;
        } else {
            c = entry.rgb;
            a = entry.a;
            if shading == SHADING_PHONG || shading == SHADING_CONTEXT {
                phong = phong_term(n, l, hv);
                c = clamp(c * phong, vec3<f32>(0.0), vec3<f32>(1.0));
            }
        }
        if shading == SHADING_LIGHTING {
            // VolumeShop lighting transfer function, eq. 8: it enhances the TF's opacity α_u,
            // before the step correction below (the two differ when the step is not 1 voxel).
            let lt = lighting_lookup(dot(n, l), dot(n, hv));
            c = clamp((lt.x + lt.y) * c + lt.z, vec3<f32>(0.0), vec3<f32>(1.0));
            a = min(1.0, a / max(1e-6, min(1.0, lt.w + (1.0 - g_norm))));
        }
        if enhanced(ENHANCE_BOUNDARY | ENHANCE_SILHOUETTE) {
            if RAY_ENHANCE_FIELD == ENHANCE_FROM_RENDERED {
                a *= enhancement_factor(g_norm, n, v_dir);
            } else {
                // Already divided by its largest magnitude, in world axes.
                var f = vec3<f32>(0.0);
                if RAY_ENHANCE_FIELD == ENHANCE_FROM_SECOND {
                    f = field_sample(second_field, q).xyz;
                } else {
                    f = field_sample(vector_field, q).xyz;
                }
                a *= enhancement_factor(clamp(length(f), 0.0, 1.0), view_normal(f), v_dir);
            }
        }
        // Global alpha ρ (Yuan & Chen §5), then the opacity correction for the step length
        // (TF opacities are per voxel).
        a = 1.0 - pow(1.0 - clamp(a * ray.rho, 0.0, 1.0), step_voxels);
        if preintegrated() {
            // The segment's opacity (ρ and the step are in the table) and its mean colour.
            a = segment.a;
            c = clamp(segment.rgb / max(segment.a, 1e-6) * phong, vec3<f32>(0.0), vec3<f32>(1.0));
        }
        if shading == SHADING_CONTEXT {
            // Context-preserving opacity, eq. 5 (applied to the corrected opacity).
            a = context_preserving(a, phong, g_norm, p, p0, alpha);
        }
        color += (1.0 - alpha) * a * c;
        alpha += (1.0 - alpha) * a;
        if hit_t < 0.0 && alpha >= ray.hit_opacity {
            hit_t = t;
            out.normal = vec4<f32>(n, 1.0);
        }
        if alpha >= ray.early_termination {
            break;
        }
    }

    if mode == RAY_MODE_MIP {
        if best_t < 0.0 {
            return out;
        }
        let entry = table_lookup(best);
        out.color = vec4<f32>(entry.rgb * entry.a, entry.a);
        out.depth = to_window_depth(p0 + dir * best_t);
        out.normal = vec4<f32>(0.0, 0.0, 0.0, 1.0);
        return out;
    }
    if mode == RAY_MODE_ISO {
        if hit_t < 0.0 {
            return out;
        }
        let p = p0 + dir * hit_t;
        let n = view_normal(gradient_at(q0 + dq * hit_t));
        let hv = normalize(l + view_direction(p));
        out.color = vec4<f32>(shade_surface(table_lookup(ray.iso).rgb, n, l, hv, shading), 1.0);
        out.normal = vec4<f32>(n, 1.0);
        out.depth = to_window_depth(p);
        return out;
    }
    if stroke_pending && alpha < ray.early_termination {
        color += (1.0 - alpha) * stroke_alpha * strokes.color.rgb;
        alpha += (1.0 - alpha) * stroke_alpha;
    }
    out.color = vec4<f32>(color, alpha);
    if hit_t >= 0.0 {
        out.depth = to_window_depth(p0 + dir * hit_t);
    }
    return out;
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    return fragment_out(cast_ray(in.position.xy));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !outside_frame(id.xy) {
        store_result(id.xy, cast_ray(vec2<f32>(id.xy) + 0.5));
    }
}
