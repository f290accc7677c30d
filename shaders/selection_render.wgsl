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
// Prepended: ray_common, ray_classify, ray_shade.

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
    pad0: f32,
    pad1: f32,
    pad2: f32,
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

fn inside_grid(q: vec3<f32>) -> bool {
    return all(q >= vec3<f32>(-0.5)) && all(q <= ray.dims - 0.5);
}

// f_S at voxel-space q (0 outside the grid).
fn selected(q: vec3<f32>) -> f32 {
    if !inside_grid(q) {
        return 0.0;
    }
    return textureSampleLevel(selection_mask, linear_clamp, grid_uv(q), 0.0).r;
}

// f_V at voxel-space q, NO_DATA outside the grid.
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
    let a = box_interval(q0, dq);
    let b = box_interval(s0, ds);
    let t_in = min(a.x, b.x);
    let t_out = max(a.y, b.y);
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
    let cutaway = selection.cutaway;
    // The cutaway region along this ray: in front of the far side of the ghost and/or the
    // selection (the last sample where its selection set exceeds 1/2).
    var t_cut = -1.0e30;
    if cutaway != CUT_NONE && selection.ghosting > 0.0 {
        for (var k = 0u; k < count; k++) {
            let t = start + f32(k) * h;
            let ghost = (cutaway == CUT_GHOST || cutaway == CUT_BOTH) && selected(q0 + dq * t) > 0.5;
            let moved = (cutaway == CUT_SELECTION || cutaway == CUT_BOTH) && selected(s0 + ds * t) > 0.5;
            if ghost || moved {
                t_cut = t;
            }
        }
    }
    let g = selection.ghosting;
    let shaded = selection.shaded != 0u;
    let l = ray.light;
    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var hit_t = -1.0;
    for (var k = 0u; k < count; k++) {
        let t = start + f32(k) * h;
        let q = q0 + dq * t;
        let qs = s0 + ds * t;
        let v = value_inside(q);
        let vs = value_inside(qs);
        let f_s = selected(q);
        let sel = member(vs, selected(qs), 2, selection.selection_domain);
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
            if sel.mu >= max(ghost.mu, back.mu) {
                grad = (selection.rotation * vec4<f32>(gradient_at(qs), 0.0)).xyz;
            } else {
                grad = gradient_at(q);
            }
            n = view_normal(grad);
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

// Where a ray (voxel space) enters and leaves the box of voxel centres; (1e30, −1e30) if not.
fn box_interval(q0: vec3<f32>, dq: vec3<f32>) -> vec2<f32> {
    var t_in = 0.0;
    var t_out = 1e30;
    for (var axis = 0; axis < 3; axis++) {
        if abs(dq[axis]) < 1e-12 {
            if q0[axis] < ray.box_min[axis] || q0[axis] > ray.box_max[axis] {
                return vec2<f32>(1e30, -1e30);
            }
        } else {
            let a = (ray.box_min[axis] - q0[axis]) / dq[axis];
            let b = (ray.box_max[axis] - q0[axis]) / dq[axis];
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
