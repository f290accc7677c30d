// GPU volume ray casting: direct volume rendering (front-to-back, tutorial eq. 1 of the
// context-preserving paper), maximum intensity projection, and first hit of an iso value.
// Shading: none, Blinn–Phong (eq. 3), the VolumeShop lighting transfer function (eq. 8),
// context-preserving opacity (eq. 5), and style transfer functions (Bruckner & Gröller 2007:
// lit-sphere styles §3.1/§4.1, style contours §3.3, illustrative transparency eq. 2).
// The sampling rule is shared with the CPU reference in tests/common/raycast_reference.rs.

struct Ray {
    inv_view_proj: mat4x4<f32>,
    view: mat4x4<f32>,
    view_proj: mat4x4<f32>,
    // xyz voxel-space box of the voxel centres (slightly widened); box_min.w = step in world
    // units, box_max.w = step in voxels.
    box_min: vec4<f32>,
    box_max: vec4<f32>,
    // xyz world origin (centre of voxel 0, informative); w = lowest finite value (the
    // visibility table's range).
    origin: vec4<f32>,
    // xyz voxel spacing (informative); w = highest finite value.
    spacing: vec4<f32>,
    // xyz voxel counts; w = largest gradient magnitude (normalises |g| to [0, 1]).
    dims: vec4<f32>,
    // xyz view-space unit vector towards the light; w = 1 for an orthographic camera.
    light: vec4<f32>,
    // x, y = frame size; z = 1 to jitter the first sample; w = early-termination opacity.
    frame: vec4<f32>,
    // x = mode (0 DVR, 1 MIP, 2 iso); y = iso value; z = shading (0 none, 1 Phong,
    // 2 lighting TF, 3 context-preserving, 4 style); w = accumulated opacity that counts as "hit".
    mode: vec4<f32>,
    // ambient, diffuse, specular, exponent of eq. 3.
    phong: vec4<f32>,
    // kappa_t, kappa_s, nearest and farthest eye-to-box-corner distances (eq. 5).
    context: vec4<f32>,
    // transfer-function domain (lo, hi); z = number of style nodes N; w = contour thickness T.
    tf: vec4<f32>,
    // x = 1 for style contours, y = 1 for illustrative transparency (eq. 2), z = mip bias,
    // w = style map size in texels.
    style: vec4<f32>,
    // xyz world eye position (perspective cameras).
    eye: vec4<f32>,
    // x = 1 when a label volume selects per-object style rows (§4.2); y, z = its texel range
    // (the texture is normalised like the volume's); w = width of the label → row table.
    labels: vec4<f32>,
    // x = 1 to skip empty bricks (DVR); y = voxels per brick side; z = visibility bins.
    skip: vec4<f32>,
    // World → voxel transform (voxel centres at integers); rays march in voxel space.
    to_voxel: mat4x4<f32>,
    // Voxel-space gradient → world-space gradient: the inverse transpose of the linear part.
    grad_to_world: mat4x4<f32>,
    // x, y: data values of texel 0 and 1 (value = x + (y - x) · texel; the texture's format
    // follows the voxel type, see hatchery_nodes::volume_texture).
    texel: vec4<f32>,
};

@group(0) @binding(0) var<uniform> ray: Ray;
@group(0) @binding(1) var volume: texture_3d<f32>;
@group(0) @binding(2) var linear_clamp: sampler;
// 256×1: colour TF (rgb, opacity per voxel), or for styles (fractional node index, α_u, 0, 0).
@group(0) @binding(3) var tf_table: texture_2d<f32>;
// 64×64 lighting transfer function over (N·L, N·H) in [-1, 1]²: (s_a, s_d, s_s, s_alpha).
@group(0) @binding(4) var lighting_table: texture_2d<f32>;
// One layer per distinct style, each with its own mip chain (no mixing between styles, §4.3).
@group(0) @binding(5) var styles: texture_2d_array<f32>;
// N×rows: node index -> style layer (the index function texture ift of §4.1), one row per object.
@group(0) @binding(6) var style_index: texture_2d<f32>;
// Object labels on the volume's grid (read at the nearest voxel: never interpolated).
@group(0) @binding(7) var label_volume: texture_3d<f32>;
// Row 0: table row of each label; row 1: (domain lo, hi, node count N, 0) of each table row.
@group(0) @binding(8) var label_rows: texture_2d<f32>;
// [min, max] of the values trilinear samples can take in each brick (hatchery_data::bricks).
@group(0) @binding(9) var bricks: texture_3d<f32>;
// Cumulative count of visible bins over the volume's value range (any table row, any object).
@group(0) @binding(10) var visibility: texture_2d<f32>;

const LUT_SIZE: f32 = 256.0;
const LIGHTING_SIZE: f32 = 64.0;

struct FragmentOut {
    @location(0) color: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @builtin(frag_depth) depth: f32,
};

// Returned by value_at where the sample leans on a "no data" voxel (the texture holds
// NO_DATA_TEXEL = -1000 there; NaN is not used because shader compilers may assume no NaN).
const NO_DATA: f32 = -1.0e30;

// Data value at continuous voxel coordinates q (clamped to the grid, trilinear), or NO_DATA.
fn value_at(q: vec3<f32>) -> f32 {
    let uv = (clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0) + 0.5) / ray.dims.xyz;
    let normalised = textureSampleLevel(volume, linear_clamp, uv, 0.0).r;
    if normalised < -0.5 {
        return NO_DATA;
    }
    return ray.texel.x + normalised * (ray.texel.y - ray.texel.x);
}

// Whether a value from value_at is "no data" (transparent).
fn no_data(v: f32) -> bool {
    return v <= NO_DATA;
}

// World-space gradient by central differences in voxel space (one-sided at the border and next
// to "no data", 0 with no data on both sides), mapped to world units through the transform.
fn gradient_at(q: vec3<f32>) -> vec3<f32> {
    let top = ray.dims.xyz - 1.0;
    let p = clamp(q, vec3<f32>(0.0), top);
    var g = vec3<f32>(0.0);
    for (var axis = 0; axis < 3; axis++) {
        var lo = p;
        var hi = p;
        lo[axis] = max(p[axis] - 1.0, 0.0);
        hi[axis] = min(p[axis] + 1.0, top[axis]);
        let a = value_at(lo);
        let b = value_at(hi);
        if !no_data(a) && !no_data(b) {
            g[axis] = (b - a) / (hi[axis] - lo[axis]);
        } else if !no_data(a) && p[axis] > lo[axis] {
            g[axis] = (value_at(p) - a) / (p[axis] - lo[axis]);
        } else if !no_data(b) && hi[axis] > p[axis] {
            g[axis] = (b - value_at(p)) / (hi[axis] - p[axis]);
        }
    }
    return (ray.grad_to_world * vec4<f32>(g, 0.0)).xyz;
}

// The LUT rule of hatchery_data::transfer_function::TransferFunction1D::lookup, on table row `row`.
fn table_lookup_row(v: f32, row: i32, domain: vec2<f32>) -> vec4<f32> {
    let span = domain.y - domain.x;
    var u = 0.0;
    if span > 0.0 {
        u = clamp((v - domain.x) / span, 0.0, 1.0);
    }
    let x = u * (LUT_SIZE - 1.0);
    let k = min(floor(x), LUT_SIZE - 2.0);
    let f = x - k;
    let a = textureLoad(tf_table, vec2<i32>(i32(k), row), 0);
    let b = textureLoad(tf_table, vec2<i32>(i32(k) + 1, row), 0);
    return mix(a, b, f);
}

fn table_lookup(v: f32) -> vec4<f32> {
    return table_lookup_row(v, 0, ray.tf.xy);
}

// Bilinear lookup of the lighting transfer function at signed (N·L, N·H).
fn lighting_lookup(nl: f32, nh: f32) -> vec4<f32> {
    let x = clamp((nl + 1.0) * 0.5, 0.0, 1.0) * (LIGHTING_SIZE - 1.0);
    let y = clamp((nh + 1.0) * 0.5, 0.0, 1.0) * (LIGHTING_SIZE - 1.0);
    let x0 = min(floor(x), LIGHTING_SIZE - 2.0);
    let y0 = min(floor(y), LIGHTING_SIZE - 2.0);
    let fx = x - x0;
    let fy = y - y0;
    let p = vec2<i32>(i32(x0), i32(y0));
    let a = mix(textureLoad(lighting_table, p, 0), textureLoad(lighting_table, p + vec2<i32>(1, 0), 0), fx);
    let b = mix(textureLoad(lighting_table, p + vec2<i32>(0, 1), 0), textureLoad(lighting_table, p + vec2<i32>(1, 1), 0), fx);
    return mix(a, b, fy);
}

// Eq. 1 of Bruckner & Gröller 2007: sqrt(T κv (2 − T κv)), T κv clamped to [0, 1].
fn contour_limit(kappa_v: f32) -> f32 {
    let tk = clamp(ray.tf.w * kappa_v, 0.0, 1.0);
    return sqrt(tk * (2.0 - tk));
}

// One style layer at sphere-map coordinates (nx, ny), with an explicit mip level.
fn style_sample(layer: i32, nxy: vec2<f32>, lod: f32) -> vec4<f32> {
    let uv = vec2<f32>(nxy.x * 0.5 + 0.5, 0.5 - nxy.y * 0.5);
    return textureSampleLevel(styles, linear_clamp, uv, layer, lod);
}

fn hash(p: vec2<f32>) -> f32 {
    return fract(sin(dot(p, vec2<f32>(12.9898, 78.233))) * 43758.5453);
}

// [min, max] of the values trilinear samples can take in the brick holding voxel-space q.
fn brick_range(q: vec3<f32>) -> vec2<f32> {
    let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0) / ray.skip.y));
    return textureLoad(bricks, brick, 0).xy;
}

// Whether no value in `range` is visible under any row of the transfer function.
fn range_is_invisible(range: vec2<f32>) -> bool {
    let lo = ray.origin.w;
    let span = max(ray.spacing.w - lo, 1e-30);
    let last = i32(ray.skip.z) - 1;
    let a = clamp(i32(floor((range.x - lo) / span * ray.skip.z)), 0, last);
    let b = clamp(i32(floor((range.y - lo) / span * ray.skip.z)), 0, last);
    var before = 0.0;
    if a > 0 {
        before = textureLoad(visibility, vec2<i32>(a - 1, 0), 0).r;
    }
    return textureLoad(visibility, vec2<i32>(b, 0), 0).r - before == 0.0;
}

// The ray parameter where the ray leaves the brick holding q (q = q0 + dq·t).
fn brick_exit(q: vec3<f32>, dq: vec3<f32>, t: f32) -> f32 {
    let brick = floor(clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0) / ray.skip.y);
    var exit = 1e30;
    for (var axis = 0; axis < 3; axis++) {
        if dq[axis] > 1e-12 {
            exit = min(exit, t + ((brick[axis] + 1.0) * ray.skip.y - q[axis]) / dq[axis]);
        } else if dq[axis] < -1e-12 {
            exit = min(exit, t + (brick[axis] * ray.skip.y - q[axis]) / dq[axis]);
        }
    }
    return exit;
}

fn to_window_depth(p: vec3<f32>) -> f32 {
    let clip = ray.view_proj * vec4<f32>(p, 1.0);
    return clip.z / clip.w;
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    var out: FragmentOut;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;

    let ndc = vec2<f32>(in.position.x / ray.frame.x * 2.0 - 1.0, 1.0 - in.position.y / ray.frame.y * 2.0);
    let near4 = ray.inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    let far4 = ray.inv_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    let p0 = near4.xyz / near4.w;
    let dir = normalize(far4.xyz / far4.w - p0);
    // The same ray in voxel space; t stays in world units.
    let q0 = (ray.to_voxel * vec4<f32>(p0, 1.0)).xyz;
    let dq = (ray.to_voxel * vec4<f32>(dir, 0.0)).xyz;

    // Slab test against the box of voxel centres, in voxel space.
    var t_in = 0.0;
    var t_out = 1e30;
    for (var axis = 0; axis < 3; axis++) {
        if abs(dq[axis]) < 1e-12 {
            if q0[axis] < ray.box_min[axis] || q0[axis] > ray.box_max[axis] {
                return out;
            }
        } else {
            let a = (ray.box_min[axis] - q0[axis]) / dq[axis];
            let b = (ray.box_max[axis] - q0[axis]) / dq[axis];
            t_in = max(t_in, min(a, b));
            t_out = min(t_out, max(a, b));
        }
    }
    if t_in > t_out {
        return out;
    }

    let h = ray.box_min.w;
    let step_voxels = ray.box_max.w;
    var start = t_in;
    if ray.frame.z > 0.5 {
        start += h * hash(in.position.xy);
    }
    let mode = i32(ray.mode.x + 0.5);
    let shading = i32(ray.mode.z + 0.5);
    let orthographic = ray.light.w > 0.5;
    let l = ray.light.xyz;

    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var best = -1e30;
    var best_t = -1.0;
    var previous_value = 0.0;
    var previous_t = 0.0;
    var previous_normal = vec3<f32>(0.0);
    var hit_t = -1.0;
    let count = min(u32(max(floor((t_out - start) / h), -1.0) + 1.0), 65536u);

    let skipping = ray.skip.x > 0.5;
    for (var k = 0u; k < count; k++) {
        let t = start + f32(k) * h;
        let p = p0 + dir * t;
        let q = q0 + dq * t;
        if skipping {
            // Bricks whose samples cannot change the result: DVR, all transparent; MIP, none
            // above the maximum so far; iso, all below the iso value.
            let range = brick_range(q);
            // An empty range (min > max) holds only "no data".
            var skip = range.x > range.y;
            if !skip && mode == 0 {
                skip = range_is_invisible(range);
            } else if !skip && mode == 1 {
                skip = range.y <= best;
            } else if !skip {
                skip = range.y < ray.mode.y;
            }
            if skip {
                // Jump to the first sample past the brick, on the same lattice of t, so the
                // samples taken are exactly those taken without skipping.
                let exit = brick_exit(q, dq, t) - 1e-4 * h;
                let next = min(max(ceil((exit - start) / h), f32(k + 1u)), f32(count));
                if mode == 2 {
                    // The iso hit interpolates from the sample before it: take that one.
                    let t_before = start + (next - 1.0) * h;
                    previous_value = value_at(q0 + dq * t_before);
                    previous_t = t_before;
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
            continue;
        }

        if mode == 1 {
            if v > best {
                best = v;
                best_t = t;
            }
            continue;
        }
        if mode == 2 {
            if v >= ray.mode.y {
                var t_hit = t;
                if k > 0u && v != previous_value && !no_data(previous_value) {
                    t_hit = previous_t + h * (ray.mode.y - previous_value) / (v - previous_value);
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
        var row = 0;
        var domain = ray.tf.xy;
        var node_count = ray.tf.z;
        if shading == 4 && ray.labels.x > 0.5 {
            // The object at the nearest voxel picks the table row (§4.2).
            let voxel = vec3<i32>(round(clamp(q, vec3<f32>(0.0), ray.dims.xyz - 1.0)));
            let label = round(ray.labels.y + textureLoad(label_volume, voxel, 0).r * (ray.labels.z - ray.labels.y));
            let slot = clamp(i32(label), 0, i32(ray.labels.w) - 1);
            row = i32(textureLoad(label_rows, vec2<i32>(slot, 0), 0).r + 0.5);
            let info = textureLoad(label_rows, vec2<i32>(row, 1), 0);
            domain = info.xy;
            node_count = info.z;
        }
        let entry = table_lookup_row(v, row, domain);
        // Colour TFs keep opacity in .a, style TFs α_u in .y.
        var classified = entry.a;
        if shading == 4 {
            classified = entry.y;
        }
        if classified <= 0.0 {
            // κv restarts after a gap (no normal to compare with).
            previous_normal = vec3<f32>(0.0);
            continue;
        }
        let g = gradient_at(q);
        let g_length = length(g);
        var n_world = vec3<f32>(0.0);
        if g_length > 1e-12 {
            // Unit normal towards lower values (outward for bright objects).
            n_world = -g / g_length;
        }
        let n = (ray.view * vec4<f32>(n_world, 0.0)).xyz;
        let view_pos = (ray.view * vec4<f32>(p, 1.0)).xyz;
        var v_dir = vec3<f32>(0.0, 0.0, 1.0);
        if !orthographic {
            v_dir = -normalize(view_pos);
        }
        let hv = normalize(l + v_dir);
        let g_norm = clamp(g_length / max(ray.dims.w, 1e-20), 0.0, 1.0);

        var c = vec3<f32>(0.0);
        var a = 0.0;
        if shading == 4 {
            // Style transfer function (§4.1): (i, α_u) from tft, whole styles j0, j1 from ift.
            let i = entry.x;
            let alpha_u = entry.y;
            let last = max(node_count - 1.0, 0.0);
            let i0 = clamp(floor(i), 0.0, last);
            let i1 = min(i0 + 1.0, last);
            let w = clamp(i - i0, 0.0, 1.0);
            let j0 = i32(textureLoad(style_index, vec2<i32>(i32(i0), row), 0).r + 0.5);
            let j1 = i32(textureLoad(style_index, vec2<i32>(i32(i1), row), 0).r + 0.5);
            // κv: angle between successive normals over the step (§3.3).
            var kappa_v = 0.0;
            if k > 0u && dot(previous_normal, previous_normal) > 0.5 && g_length > 1e-12 {
                kappa_v = acos(clamp(dot(n, previous_normal), -1.0, 1.0)) / h;
            }
            let n_dot_v = dot(n, v_dir);
            let limit = contour_limit(kappa_v);
            var nxy = n.xy;
            let r = length(nxy);
            if ray.style.x > 0.5 && limit > 0.0 && abs(n_dot_v) <= limit && r > 0.0 {
                // Push the sphere-map coordinates outwards: r' = min(1, r / δ).
                let delta = 1.0 - min(1.0, (limit - abs(n_dot_v)) / limit);
                var r_new = 1.0;
                if delta > 0.0 {
                    r_new = min(1.0, r / delta);
                }
                nxy = nxy * (r_new / r);
            }
            // Mip level from how far the normal turns across one step (§4.3), plus a bias.
            let lod = max(log2(max(kappa_v * h * ray.style.w * 0.5, 1.0)) + ray.style.z, 0.0);
            let styled = mix(style_sample(j0, nxy, lod), style_sample(j1, nxy, lod), w);
            c = styled.rgb;
            if ray.style.y > 0.5 {
                // Illustrative transparency, eq. 2.
                let exponent = 0.5 + max(0.0, abs(n_dot_v) - limit) * (1.0 - g_norm);
                var factor = 0.0;
                if alpha_u > 0.0 {
                    factor = pow(alpha_u, exponent);
                }
                a = styled.a * factor;
            } else {
                a = styled.a * alpha_u;
            }
            previous_normal = n;
        } else {
            c = entry.rgb;
            a = entry.a;
            let s = ray.phong.y * abs(dot(l, n)) + ray.phong.z * pow(abs(dot(hv, n)), ray.phong.w) + ray.phong.x;
            if shading == 1 || shading == 3 {
                c = clamp(c * s, vec3<f32>(0.0), vec3<f32>(1.0));
            }
        }
        // Opacity correction for the step length (TF opacities are per voxel).
        a = 1.0 - pow(1.0 - clamp(a, 0.0, 1.0), step_voxels);
        if shading == 2 {
            // VolumeShop lighting transfer function, eq. 8 (on the corrected opacity).
            let lt = lighting_lookup(dot(n, l), dot(n, hv));
            c = clamp((lt.x + lt.y) * c + lt.z, vec3<f32>(0.0), vec3<f32>(1.0));
            a = min(1.0, a / max(1e-6, min(1.0, lt.w + (1.0 - g_norm))));
        }
        if shading == 3 {
            // Context-preserving opacity, eq. 5 (applied to the corrected opacity).
            let s = ray.phong.y * abs(dot(l, n)) + ray.phong.z * pow(abs(dot(hv, n)), ray.phong.w) + ray.phong.x;
            var eye = ray.eye.xyz;
            if orthographic {
                eye = p0;
            }
            let dist = clamp((length(p - eye) - ray.context.z) / max(ray.context.w - ray.context.z, 1e-20), 0.0, 1.0);
            let base = ray.context.x * s * (1.0 - dist) * (1.0 - alpha);
            var exponent = 0.0;
            if base > 0.0 {
                exponent = pow(base, ray.context.y);
            }
            if exponent != 0.0 {
                a = a * pow(g_norm, exponent);
            }
        }
        color += (1.0 - alpha) * a * c;
        alpha += (1.0 - alpha) * a;
        if hit_t < 0.0 && alpha >= ray.mode.w {
            hit_t = t;
            out.normal = vec4<f32>(n, 1.0);
        }
        if alpha >= ray.frame.w {
            break;
        }
    }

    if mode == 1 {
        if best_t < 0.0 {
            return out;
        }
        let entry = table_lookup(best);
        out.color = vec4<f32>(entry.rgb * entry.a, entry.a);
        let p = p0 + dir * best_t;
        out.depth = to_window_depth(p);
        out.normal = vec4<f32>(0.0, 0.0, 0.0, 1.0);
        return out;
    }
    if mode == 2 {
        if hit_t < 0.0 {
            return out;
        }
        let p = p0 + dir * hit_t;
        let q = q0 + dq * hit_t;
        let g = gradient_at(q);
        var n_world = vec3<f32>(0.0);
        if length(g) > 1e-12 {
            n_world = -normalize(g);
        }
        let n = (ray.view * vec4<f32>(n_world, 0.0)).xyz;
        var c = table_lookup(ray.mode.y).rgb;
        let view_pos = (ray.view * vec4<f32>(p, 1.0)).xyz;
        var v_dir = vec3<f32>(0.0, 0.0, 1.0);
        if !orthographic {
            v_dir = -normalize(view_pos);
        }
        let hv = normalize(l + v_dir);
        if shading == 1 || shading == 3 {
            let s = ray.phong.y * abs(dot(l, n)) + ray.phong.z * pow(abs(dot(hv, n)), ray.phong.w) + ray.phong.x;
            c = clamp(c * s, vec3<f32>(0.0), vec3<f32>(1.0));
        } else if shading == 2 {
            let lt = lighting_lookup(dot(n, l), dot(n, hv));
            c = clamp((lt.x + lt.y) * c + lt.z, vec3<f32>(0.0), vec3<f32>(1.0));
        }
        out.color = vec4<f32>(c, 1.0);
        out.normal = vec4<f32>(n, 1.0);
        out.depth = to_window_depth(p);
        return out;
    }
    out.color = vec4<f32>(color, alpha);
    if hit_t >= 0.0 {
        out.depth = to_window_depth(p0 + dir * hit_t);
    }
    return out;
}
