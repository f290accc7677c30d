// ExplodedView: exploded views of a segmented volume (Viola et al., Vis 2005 tutorial §3
// "Exploded views and deformations": volume splitting, logical and geometrical). Parts — an
// object, a half of an object (split by a plane through its centre) or a half of the whole
// volume — are moved by their displacements d. A sample at voxel-space q is looked up in every
// part at q − d (the part's source); the first part, in the table's order, whose source holds
// a drawn object there (an object the part names, on the part's side of its plane) owns the
// sample, which is classified with that object's transfer function and rendering mode from the
// object table and composited front to back. Drawn objects no part names stay in place (a last
// part with no displacement) unless a part is a half of the whole volume.
// Prepended: ray_common, ray_bspline, ray_classify, ray_shade, ray_skip, ray_objects.

// One row per part (EXPLODED_PARTS rows), four texels: (displacement in voxels, object id or 0 for the whole
// volume), (voxel-space plane: normal, offset), (source box min, side: +1 the plane's positive
// half, −1 the negative, 0 whole), (source box max, 0).
@group(1) @binding(4) var parts: texture_2d<f32>;

// The codes of the object table (hatchery_nodes::value::RenderMode and Compositing, as in
// two_level_raycast.wgsl).
const MODE_SHADED: u32 = 1u;
const MODE_TONE: u32 = 2u;
const MODE_CONTOURS: u32 = 3u;
const MODE_ISO: u32 = 5u;
const LOCAL_ISO: u32 = 2u;
const MAX_PARTS: u32 = 16u;
// The number of parts, and 1 to draw the objects no part names where they are: pipeline
// constants, so the per-part loops have constant bounds, which lets the compiler unroll them
// and keep the parts' arrays in registers (CPU drivers otherwise index them in memory at
// every sample).
override EXPLODED_PARTS: u32 = 16u;
override EXPLODED_REST: u32 = 1u;

fn part_texel(i: u32, j: i32) -> vec4<f32> {
    return textureLoad(parts, vec2<i32>(j, i32(i)), 0);
}

// The ray o + d·t's interval inside the box [lo, hi] (lo > hi components: empty), clipped to
// t ≥ 0; x > y where it misses.
fn slab(o: vec3<f32>, d: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> vec2<f32> {
    let tiny = vec3<f32>(1e-12);
    let safe = select(d, tiny, abs(d) < tiny);
    let a = (lo - o) / safe;
    let b = (hi - o) / safe;
    let near = min(a, b);
    let far = max(a, b);
    return vec2<f32>(max(max(near.x, near.y), max(near.z, 0.0)), min(min(far.x, far.y), far.z));
}

// Whether voxel-space q lies in the box of voxel centres.
fn in_grid(q: vec3<f32>) -> bool {
    return all(q >= ray.box_min) && all(q <= ray.box_max);
}

// The object brick table's entry for the brick around q (see ray_objects.wgsl): x > y where no
// drawn object reaches the brick, z the one object every sample of it sees (−1: several).
fn brick_entry(q: vec3<f32>) -> vec4<f32> {
    let brick = vec3<i32>(floor(clamp(q, vec3<f32>(0.0), ray.dims - 1.0) / f32(ray.brick_size)));
    return textureLoad(bricks, brick, 0);
}

// The drawn object at voxel-space q inside the grid, given its brick entry (boundary
// filtering or the nearest voxel, as TwoLevelRaycast); 0 for none.
fn drawn_object(q: vec3<f32>, info: vec4<f32>) -> u32 {
    var id = 0u;
    if info.z >= 0.0 {
        id = u32(info.z);
    } else if boundary_filtered() && drawn_union(q) < 0.45 {
        return 0u;
    } else {
        id = object_at(q);
    }
    if id == 0u || id >= two_level.columns || object_info(id, 0u).x < 0.5 {
        return 0u;
    }
    return id;
}

// Whether a part whose object is `want` (0: any) may own object `id`; the rest (want = −1)
// owns the objects no part names.
fn part_takes(want: i32, id: u32) -> bool {
    if want == 0 {
        return true;
    }
    if want > 0 {
        return u32(want) == id;
    }
    for (var i = 0u; i < min(EXPLODED_PARTS, MAX_PARTS); i++) {
        if u32(part_texel(i, 0).w + 0.5) == id {
            return false;
        }
    }
    return true;
}

// Cool-to-warm tone shading, TwoLevelRaycast's `tone` mode (Gooch et al. 1998).
fn exploded_tone(c: vec3<f32>, n: vec3<f32>, l: vec3<f32>) -> vec3<f32> {
    let w = (1.0 + dot(n, l)) * 0.5;
    let cool = 0.25 * c + vec3<f32>(0.0, 0.0, 0.55);
    let warm = 0.5 * c + vec3<f32>(0.3, 0.3, 0.0);
    return clamp(mix(cool, warm, w), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn cast_exploded(position: vec2<f32>) -> RayResult {
    var out: RayResult;
    out.color = vec4<f32>(0.0);
    out.normal = vec4<f32>(0.0);
    out.depth = 1.0;
    let r = primary_ray(position);
    let h = ray.step_world;
    // Samples on TwoLevelRaycast's lattice: anchored where the ray enters the volume's box
    // (at the near plane where it misses it), extended both ways over the moved parts.
    var base = select(0.0, r.t_in, r.hits);
    if ray.jitter != 0u {
        base += h * hash(position);
    }
    // The parts along this ray, the rest (the objects no part names, in place) last: the
    // displacement, the plane and side, the object (0: any, −1: the rest's) and where the ray
    // meets the part's moved box.
    let parts_moved = min(EXPLODED_PARTS, MAX_PARTS);
    let n = parts_moved + min(EXPLODED_REST, 1u);
    var disp: array<vec3<f32>, 17>;
    var planes: array<vec4<f32>, 17>;
    var sides: array<f32, 17>;
    var wants: array<i32, 17>;
    var spans: array<vec2<f32>, 17>;
    var t_min = 1e30;
    var t_max = -1e30;
    for (var i = 0u; i < parts_moved; i++) {
        let first = part_texel(i, 0);
        let lo = part_texel(i, 2);
        disp[i] = first.xyz;
        wants[i] = i32(first.w + 0.5);
        planes[i] = part_texel(i, 1);
        sides[i] = lo.w;
        spans[i] = slab(r.q0 - first.xyz, r.dq, lo.xyz, part_texel(i, 3).xyz);
    }
    if EXPLODED_REST != 0u {
        // Empty where the ray misses the volume.
        disp[parts_moved] = vec3<f32>(0.0);
        wants[parts_moved] = -1;
        sides[parts_moved] = 0.0;
        spans[parts_moved] = select(vec2<f32>(1.0, 0.0), vec2<f32>(r.t_in, r.t_out), r.hits);
    }
    for (var i = 0u; i < n; i++) {
        if spans[i].x <= spans[i].y {
            t_min = min(t_min, spans[i].x);
            t_max = max(t_max, spans[i].y);
        }
    }
    if t_min > t_max {
        return out;
    }
    let k_last = floor((t_max - base) / h);
    let l = ray.light;
    var color = vec3<f32>(0.0);
    var alpha = 0.0;
    var hit_t = -1.0;
    for (var k = ceil((t_min - base) / h); k <= k_last; k += 1.0) {
        let t = base + k * h;
        let q = r.q0 + r.dq * t;
        var id = 0u;
        var qs = q;
        // How far no part can show anything: the next part's box, the far side of a part's
        // plane, the exit of a brick no drawn object reaches (in the part's source).
        var skip_to = 1e30;
        for (var i = 0u; i < n; i++) {
            let span = spans[i];
            if t > span.y {
                continue;
            }
            if t < span.x {
                skip_to = min(skip_to, span.x);
                continue;
            }
            let qi = q - disp[i];
            if sides[i] != 0.0 {
                let plane = planes[i];
                let dist = dot(plane.xyz, qi) + plane.w;
                if (sides[i] > 0.0 && dist < 0.0) || (sides[i] < 0.0 && dist >= 0.0) {
                    // On the other side: the part starts where the ray crosses its plane.
                    let rate = dot(plane.xyz, r.dq);
                    var cross = span.y;
                    if abs(rate) > 1e-12 && -dist / rate > 0.0 {
                        cross = min(cross, t - dist / rate - 1e-4 * h);
                    }
                    skip_to = min(skip_to, cross);
                    continue;
                }
            }
            if !in_grid(qi) {
                skip_to = t;
                continue;
            }
            let info = brick_entry(qi);
            if info.x > info.y {
                skip_to = min(skip_to, brick_exit(qi, r.dq, t) - 1e-4 * h);
                continue;
            }
            skip_to = t;
            let o = drawn_object(qi, info);
            if o != 0u && part_takes(wants[i], o) {
                id = o;
                qs = qi;
                break;
            }
        }
        if id == 0u {
            if skip_to >= 1e29 {
                break;
            }
            k = max(ceil((skip_to - base) / h), k + 1.0) - 1.0;
            continue;
        }
        let info = object_info(id, 0u);
        let row = i32(info.x + 0.5) - 1;
        let mode = u32(info.y + 0.5);
        let domain = object_info(id, 1u).xy;
        let v = value_at(qs);
        if no_data(v) {
            continue;
        }
        let p = r.p0 + r.dir * t;
        let hv = normalize(l + view_direction(p));
        var c = vec3<f32>(0.0);
        var a = 0.0;
        var nrm = vec3<f32>(0.0);
        if mode == MODE_ISO || u32(info.z + 0.5) == LOCAL_ISO {
            // An iso-surface: its first sample at or above the iso value, opaque.
            if v < info.w {
                continue;
            }
            nrm = view_normal(surface_gradient(qs, id));
            c = table_lookup_row(info.w, row, domain).rgb;
            if mode == MODE_SHADED || mode == MODE_ISO {
                c = shade_surface(c, nrm, l, hv, 1);
            } else if mode == MODE_TONE {
                c = exploded_tone(c, nrm, l);
            }
            a = 1.0;
        } else {
            let entry = table_lookup_row(v, row, domain);
            if entry.a <= 0.0 {
                continue;
            }
            c = entry.rgb;
            a = entry.a;
            if mode == MODE_SHADED || mode == MODE_TONE || mode == MODE_CONTOURS {
                let g = shading_gradient(qs, id);
                nrm = view_normal(g);
                if mode == MODE_SHADED {
                    c = clamp(c * phong_term(nrm, l, hv), vec3<f32>(0.0), vec3<f32>(1.0));
                } else if mode == MODE_TONE {
                    c = exploded_tone(c, nrm, l);
                } else {
                    let g_norm = clamp(length(g) / max(ray.max_gradient, 1e-20), 0.0, 1.0);
                    a = a * g_norm * pow(1.0 - abs(dot(nrm, view_direction(p))), 8.0);
                }
            }
            // Opacity corrected for the step (TF opacities are per voxel).
            a = 1.0 - pow(1.0 - clamp(a, 0.0, 1.0), ray.step_voxels);
        }
        if a <= 0.0 {
            continue;
        }
        color += (1.0 - alpha) * a * c;
        alpha += (1.0 - alpha) * a;
        if hit_t < 0.0 && alpha >= ray.hit_opacity {
            hit_t = t;
            out.normal = vec4<f32>(nrm, 1.0);
        }
        if alpha >= ray.early_termination {
            break;
        }
    }
    out.color = min(vec4<f32>(color, alpha), vec4<f32>(1.0));
    if hit_t >= 0.0 {
        out.depth = to_window_depth(r.p0 + r.dir * hit_t);
    }
    return out;
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    return fragment_out(cast_exploded(in.position.xy));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !outside_frame(id.xy) {
        store_result(id.xy, cast_exploded(vec2<f32>(id.xy) + 0.5));
    }
}
