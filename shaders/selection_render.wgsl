// SelectionRender: VolumeShop's selective illustration (Bruckner & Gröller; the tutorial's
// VolumeShop chapter §4 eq. 1–5, §6.2 cutaways and ghosting, §6.3 selection placement).
//
// Three objects from one scalar volume f_V and a selection function f_S (the filtered binary
// mask of the selected label ids, so values in [0, 1]):
//   selection sets (eq. 1)  μ_SS(p) = f_S(T⁻¹ p), μ_SG(p) = f_S(p), μ_SB(p) = 1 − f_S(p)
//   volume sets (eq. 2)     μ_VS(p) = α_S(f_V(T⁻¹ p)), μ_VG(p) = α_G(f_V(p)), μ_VB = α_B(f_V(p))
//   object sets (eq. 3)     S = S_S ∩ V_S, G = S_G ∩ V_G, B = S_B ∩ V_B (∩ = min)
//   colour (eq. 4)          c = Σ c_i μ_i / Σ μ_i;  opacity (eq. 5) α = max μ_i (∪ = max)
// T is the selection's transform (here T⁻¹ maps a displaced point back to where the selection
// was). Intersections of selection with ghost or background use eq. 4–5 (VolumeShop's default,
// the opacity-weighted average; no 2-D intersection transfer functions).
//
// Cutaways (§6.2) act on the background only: where a ray passes through the ghost (or the
// selection), background samples in front of its far side are in the cutaway region, and their
// opacity is reduced by the ghosting factor g combined with the lighting transfer function's
// opacity enhancement (eq. 8): α_B ← α_B · (1 − g)^(1 − e), e = 1 − min(1, s_α + 1 − |N|), so
// g = 0 leaves the background as it is, g = 1 removes it, and in between enhanced contours
// (e > 0) fade more slowly than the rest.
// Prepended: ray_common, ray_classify, ray_shade, ray_skip.

struct Selection {
    // World → voxel coordinates of the selection's source: to_voxel · T⁻¹.
    to_source: mat4x4<f32>,
    // The selection's rotation (T's linear part, world space): turns the source's gradients.
    rotation: mat4x4<f32>,
    // Transfer-function domains (lo, hi) of the background, the ghost and the selection.
    background_domain: vec2<f32>,
    ghost_domain: vec2<f32>,
    selection_domain: vec2<f32>,
    // The ghosting factor g.
    ghosting: f32,
    // Whose far side the background is cut in front of (a CUT_* constant).
    cutaway: u32,
    // 1 to shade with the lighting transfer function.
    shaded: u32,
    // 1 to skip bricks the background transfer function hides (ray_skip).
    skip_empty: u32,
    // Spacing (voxels) of the smoothed selection-mask gradient that shades the selection and
    // its ghost; 0: the data's gradient (see `smooth_selection_gradient`).
    surface_smoothing: f32,
    pad2: f32,
    // The voxel-space box beyond which f_S is 0: the selected voxels' box widened by one voxel
    // (a trilinear sample reaches one voxel), on the volume's grid and on the source's.
    mask_min: vec3<f32>,
    pad3: f32,
    mask_max: vec3<f32>,
    pad4: f32,
};

// Selection.cutaway (hatchery_nodes::selection_render::Cutaway).
const CUT_GHOST: u32 = 0u;
const CUT_SELECTION: u32 = 1u;
const CUT_BOTH: u32 = 2u;
const CUT_NONE: u32 = 3u;
@group(1) @binding(0) var<uniform> selection: Selection;
// Indicator of the selected ids (1 inside; R8Unorm, R16Unorm on CPU adapters), on the
// volume's grid: filtered trilinearly it is f_S.
@group(1) @binding(1) var selection_mask: texture_3d<f32>;

// Whether voxel-space q lies in the box of voxel centres (the domain Raycast samples).
fn inside_grid(q: vec3<f32>) -> bool {
    return all(q >= ray.box_min) && all(q <= ray.box_max);
}

// f_S at voxel-space q (0 outside the box).
fn selected(q: vec3<f32>) -> f32 {
    if !inside_grid(q) {
        return 0.0;
    }
    return textureSampleLevel(selection_mask, linear_clamp, grid_uv(q), 0.0).r;
}

// Voxel-space gradient of the selection mask f_S averaged over ±h voxels: the 3-D Sobel
// operator at spacing h (as two-level's smooth_object_gradient). A label map given as the data
// (the frog) has a gradient that steps at every slice and between neighbouring ids; the mask's,
// smoothed, shades the selected object as the smooth surface it stands for. 27 fetches.
fn smooth_selection_gradient(q: vec3<f32>, h: f32) -> vec3<f32> {
    var g = vec3<f32>(0.0);
    for (var i = 0; i < 27; i++) {
        let o = sobel_offset(i);
        g += selected(q + h * o) * sobel_weights(o);
    }
    return g / h;
}

// f_V at voxel-space q, NO_DATA outside the box.
fn value_inside(q: vec3<f32>) -> f32 {
    if !inside_grid(q) {
        return NO_DATA;
    }
    return value_at(q);
}

// One object's classified sample: membership μ (eq. 3), colour.
struct Member {
    mu: f32,
    color: vec3<f32>,
};

fn member(v: f32, degree: f32, row: i32, domain: vec2<f32>) -> Member {
    var m: Member;
    m.mu = 0.0;
    m.color = vec3<f32>(0.0);
    if no_data(v) || degree <= 0.0 {
        return m;
    }
    let entry = table_lookup_row(v, row, domain);
    m.mu = min(degree, entry.a);
    m.color = entry.rgb;
    return m;
}

// Index of the first lattice sample (t = start + k·h) at or after t.
fn first_sample(t: f32, start: f32, h: f32) -> f32 {
    return max(ceil((t - start) / h), 0.0);
}

fn cast_selection(position: vec2<f32>) -> RayResult {
    var out: RayResult;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;
    let ndc = vec2<f32>(position.x / ray.frame.x * 2.0 - 1.0, 1.0 - position.y / ray.frame.y * 2.0);
    let near4 = ray.inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    let far4 = ray.inv_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    let p0 = near4.xyz / near4.w;
    let dir = normalize(far4.xyz / far4.w - p0);
    // The ray in the volume's and in the selection source's voxel space.
    let q0 = (ray.to_voxel * vec4<f32>(p0, 1.0)).xyz;
    let dq = (ray.to_voxel * vec4<f32>(dir, 0.0)).xyz;
    let s0 = (selection.to_source * vec4<f32>(p0, 1.0)).xyz;
    let ds = (selection.to_source * vec4<f32>(dir, 0.0)).xyz;
    // Where each object can be non-zero along the ray: the background in the volume's box,
    // the ghost in the mask's box on the volume's grid, the selection in the mask's box on
    // its source. Outside them a sample's membership is exactly 0, so their work is skipped.
    let volume_span = box_interval(q0, dq, ray.box_min, ray.box_max);
    let ghost_span = box_interval(q0, dq, selection.mask_min, selection.mask_max);
    let moved_span = box_interval(s0, ds, selection.mask_min, selection.mask_max);
    let t_in = min(volume_span.x, moved_span.x);
    let t_out = max(volume_span.y, moved_span.y);
    if t_in > t_out {
        return out;
    }
    let h = ray.step_world;
    let step_voxels = ray.step_voxels;
    // Samples on a lattice anchored at the near plane (t = 0), not at the box: a decoupled
    // selection, the same in view space from every viewpoint, is then sampled alike.
    var start = ceil(t_in / h) * h;
    if ray.jitter != 0u {
        start += h * hash(position);
    }
    let count = min(u32(max(floor((t_out - start) / h), -1.0) + 1.0), 65536u);
    let last = f32(count) - 1.0;
    let cutaway = selection.cutaway;
    // The cutaway region along this ray: in front of the far side of the ghost and/or the
    // selection (the last sample where its selection set exceeds 1/2), searched backwards
    // from the far end of that object's span.
    var t_cut = -1.0e30;
    if cutaway != CUT_NONE && selection.ghosting > 0.0 {
        if cutaway == CUT_GHOST || cutaway == CUT_BOTH {
            let lo = first_sample(ghost_span.x, start, h);
            for (var k = min(floor((ghost_span.y - start) / h) + 1.0, last); k >= lo; k -= 1.0) {
                let t = start + k * h;
                if selected(q0 + dq * t) > 0.5 {
                    t_cut = t;
                    break;
                }
            }
        }
        if cutaway == CUT_SELECTION || cutaway == CUT_BOTH {
            let lo = max(first_sample(moved_span.x, start, h), first_sample(t_cut, start, h));
            for (var k = min(floor((moved_span.y - start) / h) + 1.0, last); k >= lo; k -= 1.0) {
                let t = start + k * h;
                if selected(s0 + ds * t) > 0.5 {
                    t_cut = max(t_cut, t);
                    break;
                }
            }
        }
    }
    let g = selection.ghosting;
    let shaded = selection.shaded != 0u;
    let skipping = selection.skip_empty != 0u;
    let l = ray.light;
    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var hit_t = -1.0;
    for (var k = 0u; k < count; k++) {
        let t = start + f32(k) * h;
        let q = q0 + dq * t;
        let qs = s0 + ds * t;
        let in_ghost = t >= ghost_span.x && t <= ghost_span.y;
        let in_moved = t >= moved_span.x && t <= moved_span.y;
        if !in_ghost && !in_moved {
            // Only the background can show here: jump over what it hides — outside the
            // volume, and bricks whose values its transfer function makes transparent — to the
            // next sample on the lattice that may show something.
            var skip_to = -1.0;
            if t < volume_span.x || t > volume_span.y {
                skip_to = select(t_out, volume_span.x, t < volume_span.x);
            } else if skipping {
                let range = brick_range(q);
                if range.x > range.y || range_is_invisible(range) {
                    skip_to = brick_exit(q, dq, t) - 1e-4 * h;
                }
            }
            if skip_to > t {
                if ghost_span.x > t {
                    skip_to = min(skip_to, ghost_span.x);
                }
                if moved_span.x > t {
                    skip_to = min(skip_to, moved_span.x);
                }
                let next = min(max(ceil((skip_to - start) / h), f32(k + 1u)), f32(count));
                k = u32(next) - 1u;
                continue;
            }
        }
        let v = value_inside(q);
        var f_s = 0.0;
        if in_ghost {
            f_s = selected(q);
        }
        var sel: Member;
        sel.mu = 0.0;
        sel.color = vec3<f32>(0.0);
        if in_moved {
            sel = member(value_inside(qs), selected(qs), 2, selection.selection_domain);
        }
        let ghost = member(v, f_s, 1, selection.ghost_domain);
        var back = member(v, 1.0 - f_s, 0, selection.background_domain);
        let total = sel.mu + ghost.mu + back.mu;
        if total <= 0.0 {
            continue;
        }
        // Shading normal: the dominant object's gradient (the selection's from its source).
        var n = vec3<f32>(0.0);
        var g_norm = 0.0;
        var lt = vec4<f32>(1.0, 0.0, 0.0, 1.0);
        let p = p0 + dir * t;
        let hv = normalize(l + view_direction(p));
        if shaded {
            var grad = vec3<f32>(0.0);
            // The direction from the smoothed mask where asked, the magnitude (eq. 8's
            // enhancement) from the data as always.
            var normal_grad = vec3<f32>(0.0);
            let h = selection.surface_smoothing;
            if sel.mu >= max(ghost.mu, back.mu) {
                grad = (selection.rotation * vec4<f32>(gradient_at(qs), 0.0)).xyz;
                normal_grad = grad;
                if h > 0.0 {
                    let g = (ray.grad_to_world * vec4<f32>(smooth_selection_gradient(qs, h), 0.0)).xyz;
                    // The mask rises into the selection: its gradient points inwards, as a
                    // denser object's data gradient does.
                    normal_grad = (selection.rotation * vec4<f32>(g, 0.0)).xyz;
                }
            } else {
                grad = gradient_at(q);
                normal_grad = grad;
                if h > 0.0 && ghost.mu >= back.mu {
                    normal_grad = (ray.grad_to_world * vec4<f32>(smooth_selection_gradient(q, h), 0.0)).xyz;
                }
            }
            n = view_normal(normal_grad);
            g_norm = clamp(length(grad) / max(ray.max_gradient, 1e-20), 0.0, 1.0);
            lt = lighting_lookup(dot(n, l), dot(n, hv));
        }
        // Eq. 8's opacity enhancement, and ghosting of the background in the cutaway region.
        let keep = min(1.0, lt.w + (1.0 - g_norm));
        if t < t_cut {
            let e = 1.0 - keep;
            back.mu = back.mu * pow(max(1.0 - g, 0.0), max(1.0 - e, 0.05));
        }
        let weights = sel.mu + ghost.mu + back.mu;
        var a_sample = max(sel.mu, max(ghost.mu, back.mu));
        if a_sample <= 0.0 {
            continue;
        }
        var c = (sel.color * sel.mu + ghost.color * ghost.mu + back.color * back.mu) / weights;
        if shaded {
            // Eq. 8 enhances the per-voxel opacity, before the step correction (as Raycast).
            c = clamp((lt.x + lt.y) * c + lt.z, vec3<f32>(0.0), vec3<f32>(1.0));
            a_sample = min(1.0, a_sample / max(1e-6, keep));
        }
        // Opacity correction for the step (TF opacities are per voxel).
        a_sample = 1.0 - pow(1.0 - clamp(a_sample, 0.0, 1.0), step_voxels);
        color += (1.0 - alpha) * a_sample * c;
        alpha += (1.0 - alpha) * a_sample;
        if hit_t < 0.0 && alpha >= ray.hit_opacity {
            hit_t = t;
            out.normal = vec4<f32>(n, 1.0);
        }
        if alpha >= ray.early_termination {
            break;
        }
    }
    out.color = vec4<f32>(color, alpha);
    if hit_t >= 0.0 {
        out.depth = to_window_depth(p0 + dir * hit_t);
    }
    return out;
}

// Where a ray (voxel space) enters and leaves the box [lo, hi]; (1e30, −1e30) if not.
fn box_interval(q0: vec3<f32>, dq: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> vec2<f32> {
    var t_in = 0.0;
    var t_out = 1e30;
    for (var axis = 0; axis < 3; axis++) {
        if abs(dq[axis]) < 1e-12 {
            if q0[axis] < lo[axis] || q0[axis] > hi[axis] {
                return vec2<f32>(1e30, -1e30);
            }
        } else {
            let a = (lo[axis] - q0[axis]) / dq[axis];
            let b = (hi[axis] - q0[axis]) / dq[axis];
            t_in = max(t_in, min(a, b));
            t_out = min(t_out, max(a, b));
        }
    }
    if t_in > t_out {
        return vec2<f32>(1e30, -1e30);
    }
    return vec2<f32>(t_in, t_out);
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    return fragment_out(cast_selection(in.position.xy));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !outside_frame(id.xy) {
        store_result(id.xy, cast_selection(vec2<f32>(id.xy) + 0.5));
    }
}
