// Objects of a segmented volume, shared by TwoLevelRaycast and ImportanceCompositing: the id
// texture, the object table, and which object a voxel-space point belongs to (boundary
// filtering, Hadwiger §2.3). Prepended after ray_common (needs `ray`, `value_at`,
// `gradient_at`, `linear_clamp`).

// Binding 9 (`bricks`, see ray_common) holds (0, 1, id, 0) for bricks a drawn object reaches
// and (1, 0, id, 0) for the others, so an empty brick reads as one to skip; id is the one object
// every sample of the brick sees, −1 where several meet.
// Object ids (R16Uint), on the volume's grid.
@group(0) @binding(11) var object_ids: texture_3d<u32>;
// Per id, at column id % 256 of rows 2 · (id / 256) and the one after: (table row + 1, or 0
// when not drawn; rendering mode; local compositing; iso value) and (TF domain lo, hi,
// importance, 0).
@group(0) @binding(12) var objects: texture_2d<f32>;

// 1 where a voxel belongs to a drawn object (R8Unorm, filtered): the union of the drawn
// objects' masks, an upper bound of each one's filtered mask.
@group(0) @binding(14) var drawn_mask: texture_3d<f32>;

struct TwoLevel {
    // x = global compositing (0 over, 1 mip, 2 sum); y = 1 for boundary filtering, 0 for point
    // sampling; z = number of columns of `objects` (largest id + 1); w = 1 to take normals from
    // each object's own filtered mask instead of the data (label maps without intensities).
    options: vec4<f32>,
    // Importance-driven rendering (TwoLevelRaycast with an `importance` input): x = method (0
    // none, 1 MImP, 2 AImC image space, 3 AImC object space, 4 VPImC); y = level of sparseness
    // (0 opacity, 1 colour saturation, 2 screen door, 3 sparse style); z = focus id; w = 1 in
    // VPImC's first pass, which draws only the occluding context.
    importance: vec4<f32>,
    // x, y = rendering mode and local compositing of the sparse style; z = depth band behind a
    // countersink cut shaded with the cut's normal (world units); w = 0.
    sparse: vec4<f32>,
};
@group(0) @binding(13) var<uniform> two_level: TwoLevel;

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

