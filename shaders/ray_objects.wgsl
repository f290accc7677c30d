// Objects of a segmented volume, shared by TwoLevelRaycast and ImportanceCompositing: the id
// texture, the object table, and which object a voxel-space point belongs to (boundary
// filtering, Hadwiger §2.3). Prepended after ray_common (needs `ray`, `value_at`,
// `gradient_at`, `linear_clamp`).

// Binding 9 (`bricks`, see ray_common) holds (0, 1, id, rows) for bricks a drawn object reaches
// and (1, 0, id, rows) for the others, so an empty brick reads as one to skip; id is the one
// object every sample of the brick sees, −1 where several meet; rows the bits of the drawn
// objects' table rows in the brick, as an exact float (−1 when a row past 23 is among them).
// Object ids (R16Uint), on the volume's grid.
@group(1) @binding(0) var object_ids: texture_3d<u32>;
// Per id, at column id % 256 of rows 2 · (id / 256) and the one after: (table row + 1, or 0
// when not drawn; rendering mode; local compositing; iso value) and (TF domain lo, hi,
// importance, 0).
@group(1) @binding(1) var objects: texture_2d<f32>;

// 1 where a voxel belongs to a drawn object (R8Unorm, filtered): the union of the drawn
// objects' masks, an upper bound of each one's filtered mask.
@group(1) @binding(3) var drawn_mask: texture_3d<f32>;

struct TwoLevel {
    // Global compositing of the segments (a GLOBAL_* constant of two_level_raycast.wgsl).
    global_mode: u32,
    // 1 for boundary filtering (§2.3), 0 for point sampling.
    boundary_filter: u32,
    // Columns of `objects` (largest id + 1).
    columns: u32,
    // 1 to take normals from each object's own filtered mask instead of the data (label maps
    // without intensities).
    mask_normals: u32,
    // Importance-driven rendering (TwoLevelRaycast with an `importance` input): the method (an
    // IMP_* constant), the level of sparseness (SPARSE_*), the focus id, and 1 in VPImC's first
    // pass, which draws only the occluding context.
    method: u32,
    level: u32,
    focus: u32,
    first_pass: u32,
    // Rendering mode (MODE_*) and local compositing (LOCAL_*) of the sparse style, and the
    // depth band behind a countersink cut shaded with the cut's normal (world units).
    sparse_mode: u32,
    sparse_local: u32,
    cut_band: f32,
    // Spacing (voxels) of the smoothed mask gradient at objects' iso-surfaces; 0: central
    // differences (see `surface_gradient`).
    surface_smoothing: f32,
    // Volume thinning (two_level_raycast's `thinning_key`): 1 / the volume's largest gradient
    // magnitude, the smallest spacing (world units: the Hessian's step and the unit of
    // curvature), and the number of gradient-magnitude levels B.
    thin_gradient: f32,
    thin_step: f32,
    thin_bands: f32,
    pad0: f32,
};
@group(1) @binding(2) var<uniform> two_level: TwoLevel;

// The boundary filter and mask normals as pipeline constants where a node specialises its
// pipeline (TwoLevelRaycast does; −1, the default, reads `two_level`).
override TL_FILTER: i32 = -1;
override TL_MASK_NORMALS: i32 = -1;
// 1 where `object_ids` holds 2×2 id quads (texel (i, j, k): the ids of (i, j), (i+1, j),
// (i, j+1), (i+1, j+1) in slice k; value/id_quads.rs), which CPU-adapter nodes bind: a
// footprint's 8 corners in 2 loads. `.r` is the voxel's own id either way.
override TL_ID_QUADS: i32 = 0;

fn boundary_filtered() -> bool {
    return select(two_level.boundary_filter != 0u, TL_FILTER > 0, TL_FILTER >= 0);
}

fn mask_normals() -> bool {
    return select(two_level.mask_normals != 0u, TL_MASK_NORMALS > 0, TL_MASK_NORMALS >= 0);
}

fn object_info(id: u32, which: u32) -> vec4<f32> {
    return textureLoad(objects, vec2<i32>(i32(id % 256u), i32((id / 256u) * 2u + which)), 0);
}

fn id_at(v: vec3<i32>) -> u32 {
    return textureLoad(object_ids, grid_texel(v), 0).r;
}

// The ids at the 8 corners base + (c & 1, c >> 1 & 1, c >> 2 & 1) of a trilinear footprint
// (base = floor(p) of a clamped point). Bricked, the footprint lies in base's brick and its
// apron: one page-table fetch for all 8.
fn corner_ids(base: vec3<i32>) -> array<u32, 8> {
    var ids: array<u32, 8>;
    if TL_ID_QUADS != 0 && !bricked() {
        // 2×2 id quads (value/id_quads.rs): slices z and z + 1, clamped as grid_texel does.
        let v = clamp(base, vec3<i32>(0), vec3<i32>(ray.dims) - 1);
        let near = textureLoad(object_ids, v, 0);
        let far = textureLoad(object_ids, vec3<i32>(v.xy, min(v.z + 1, i32(ray.dims.z) - 1)), 0);
        return array<u32, 8>(near.x, near.y, near.z, near.w, far.x, far.y, far.z, far.w);
    }
    if bricked() {
        let origin = grid_texel(base);
        for (var c = 0; c < 8; c++) {
            let o = vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1);
            ids[c] = textureLoad(object_ids, origin + o, 0).r;
        }
    } else {
        for (var c = 0; c < 8; c++) {
            ids[c] = id_at(base + vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1));
        }
    }
    return ids;
}

// The object at voxel-space q: boundary filtering (§2.3) or the nearest voxel; 0 for none
// (background, or no object's filtered mask above 0.5, as at a junction of three objects).
fn object_at(q: vec3<f32>) -> u32 {
    let p = clamp(q, vec3<f32>(0.0), ray.dims - 1.0);
    if !boundary_filtered() {
        return id_at(vec3<i32>(round(p)));
    }
    let base = vec3<i32>(floor(p));
    let f = p - floor(p);
    let ids = corner_ids(base);
    var weights: array<f32, 8>;
    for (var c = 0; c < 8; c++) {
        let o = vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1);
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
    let p = clamp(q, vec3<f32>(0.0), ray.dims - 1.0);
    let base = vec3<i32>(floor(p));
    let f = p - floor(p);
    var mask = 0.0;
    let ids = corner_ids(base);
    for (var c = 0; c < 8; c++) {
        let o = vec3<i32>(c & 1, (c >> 1u) & 1, (c >> 2u) & 1);
        if ids[c] == id {
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

// World-space gradient of object `id`'s filtered mask smoothed over ±h voxels: the 3-D Sobel
// operator at spacing h (differences of the mask at ±h along each axis, averaged over the 3×3
// points across it with weights 1-2-1). A label map segmented slice by slice steps its
// boundary at every slice; central differences of neighbouring voxels turn each step into a
// band of shading (the frog's 1.5 mm slices), this averages over them. 27 masks of 8 ids each:
// drawn once per ray, at iso-surface hits.
fn smooth_object_gradient(q: vec3<f32>, id: u32, h: f32) -> vec3<f32> {
    var g = vec3<f32>(0.0);
    for (var i = 0; i < 27; i++) {
        let o = sobel_offset(i);
        g += object_mask(q + h * o, id) * sobel_weights(o);
    }
    return (ray.grad_to_world * vec4<f32>(g / h, 0.0)).xyz;
}

// The gradient that shades object `id`'s iso-surface: smoothed over `surface_smoothing`
// voxels where set and the normals come from the masks, else as every other sample.
fn surface_gradient(q: vec3<f32>, id: u32) -> vec3<f32> {
    if mask_normals() && two_level.surface_smoothing > 0.0 {
        return smooth_object_gradient(q, id, two_level.surface_smoothing);
    }
    return shading_gradient(q, id);
}

// The gradient that shades a sample of object `id`: the data's, or the object mask's.
fn shading_gradient(q: vec3<f32>, id: u32) -> vec3<f32> {
    if mask_normals() {
        return object_gradient(q, id);
    }
    return gradient_at(q);
}

// The drawn objects' union mask at voxel-space q, filtered trilinearly by the sampler.
fn drawn_union(q: vec3<f32>) -> f32 {
    return textureSampleLevel(drawn_mask, linear_clamp, grid_uv(q), 0.0).r;
}

