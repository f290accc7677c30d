// Shared by the ray casters (Raycast, TwoLevelRaycast): the uniform block, the volume and its
// tables, sampling in voxel space, gradients, and the primary ray of a pixel. The programs are
// assembled from parts (see hatchery_nodes::shaders): ray_common, ray_bspline (the tricubic
// B-spline filter), ray_classify, ray_shade,
// ray_skip, then the caster's own compositing loop. The sampling rule is shared with the CPU
// reference in tests/common/raycast_reference.rs.

struct Ray {
    inv_view_proj: mat4x4<f32>,
    view: mat4x4<f32>,
    view_proj: mat4x4<f32>,
    // World → voxel transform (voxel centres at integers); rays march in voxel space.
    to_voxel: mat4x4<f32>,
    // Voxel-space gradient → world-space gradient: the inverse transpose of the linear part.
    grad_to_world: mat4x4<f32>,
    // Voxel-space box of the voxel centres (slightly widened), and the sample distance in
    // world units and in voxels.
    box_min: vec3<f32>,
    step_world: f32,
    box_max: vec3<f32>,
    step_voxels: f32,
    // Voxel counts, and the largest gradient magnitude (normalises |g| to [0, 1]).
    dims: vec3<f32>,
    max_gradient: f32,
    // View-space unit vector towards the light; 1 for an orthographic camera.
    light: vec3<f32>,
    orthographic: u32,
    // World eye position (perspective cameras); 1 for Schlick's approximation in eq. 5.
    eye: vec3<f32>,
    fast_exponent: u32,
    // Frame size in pixels; 1 to jitter the first sample; the early-termination opacity.
    frame: vec2<f32>,
    jitter: u32,
    early_termination: f32,
    // A MODE_* constant (raycast.wgsl), the iso value, a SHADING_* constant (ray_shade.wgsl),
    // and the accumulated opacity that counts as "hit".
    mode: u32,
    iso: f32,
    shading: u32,
    hit_opacity: f32,
    // c_a, c_d, c_s, c_e of eq. 3.
    ambient: f32,
    diffuse: f32,
    specular: f32,
    shininess: f32,
    // κ_t, κ_s and the nearest and farthest eye-to-box-corner distances (eq. 5).
    kappa_t: f32,
    kappa_s: f32,
    distance_near: f32,
    distance_far: f32,
    // Transfer-function domain (lo, hi) of table row 0; its style nodes N (0 for a colour
    // TF); the style contour thickness T.
    tf_domain: vec2<f32>,
    style_nodes: u32,
    contour_thickness: f32,
    // 1 for style contours; 1 for illustrative transparency (eq. 2); the style mip bias; the
    // style map size in texels.
    contours: u32,
    transparency: u32,
    mip_bias: f32,
    style_map_size: f32,
    // The label volume's texel range (normalised like the volume's), the width of the
    // label → row table, and 1 when a label volume selects per-object style rows (§4.2).
    label_texels: vec2<f32>,
    label_rows: u32,
    use_labels: u32,
    // Lowest and highest finite value (the visibility table's range); voxels per brick side;
    // visibility bins.
    value_range: vec2<f32>,
    brick_size: u32,
    visibility_bins: u32,
    // Data values of texel 0 and 1 (value = x + (y - x) · texel; the texture's format follows
    // the voxel type, see hatchery_nodes::volume_texture); 1 to skip empty bricks (DVR); 1 when
    // strokes are embedded (Raycast).
    texel_values: vec2<f32>,
    skip_empty: u32,
    embed_strokes: u32,
    // Global alpha ρ scaling every sample's opacity (Raycast, DVR); 1 when the volume's grid
    // textures are bricked (see grid_uv); the voxels of a brick's own per side (its stored side
    // less the two apron voxels).
    rho: f32,
    bricked: u32,
    page_inner: f32,
    pad0: f32,
    // 1 / the atlas size in texels (bricked grids).
    atlas_inv: vec3<f32>,
    pad1: f32,
};

// Ray.mode (hatchery_nodes::raycast::RayMode).
const RAY_MODE_DVR: u32 = 0u;
const RAY_MODE_MIP: u32 = 1u;
const RAY_MODE_ISO: u32 = 2u;

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
// Bricked grids (hatchery_nodes::brick_pool): the atlas slot of each brick, x | y << 10 | z << 20.
// Every texture on the volume's grid (volume, labels, masks) shares it: their atlases are laid
// out alike.
@group(0) @binding(11) var page_table: texture_3d<u32>;

const LUT_SIZE: f32 = 256.0;
const LIGHTING_SIZE: f32 = 64.0;

// Two per-frame switches as pipeline constants where a node specialises its pipeline (Raycast
// does; −1, the default, reads the uniform): folded, the unused branch costs nothing per
// sample — as a uniform branch both sides stayed in the loop on lavapipe.
override RAY_ORTHOGRAPHIC: i32 = -1;
override RAY_FAST_EXPONENT: i32 = -1;
override RAY_BRICKED: i32 = -1;
// The reconstruction filter of values and gradients (a RECONSTRUCTION_* constant,
// hatchery_nodes::reconstruction); always specialised, 0 by default.
override RAY_RECONSTRUCTION: i32 = 0;
// 0 where the node knows the volume has no "no data" voxels (VolumeData::has_no_data): central
// differences then skip their one-sided fallbacks. Never taken on such data, the fallbacks'
// extra fetches still cost llvmpipe a third of a gradient-heavy march (volume thinning's
// Hessian). 1, the default, keeps them.
override RAY_NO_DATA: i32 = 1;
const RECONSTRUCTION_TRILINEAR: i32 = 0;
const RECONSTRUCTION_BSPLINE: i32 = 1;

fn reconstruction() -> i32 {
    return RAY_RECONSTRUCTION;
}

// Whether the grid textures are bricked (ray.bricked, unless RAY_BRICKED says).
fn bricked() -> bool {
    return select(ray.bricked != 0u, RAY_BRICKED > 0, RAY_BRICKED >= 0);
}

// The atlas texel where brick `brick`'s own first voxel lies (past the apron).
fn brick_origin(brick: vec3<f32>) -> vec3<f32> {
    let s = textureLoad(page_table, vec3<i32>(brick), 0).r;
    let slot = vec3<u32>(s & 1023u, (s >> 10u) & 1023u, s >> 20u);
    return vec3<f32>(slot) * (ray.page_inner + 2.0) + 1.0;
}

// Texture coordinates of voxel-space point q (clamped to the grid) in a filtered grid texture:
// in the whole texture, or in the atlas slot of the brick holding q. The brick's one-voxel
// apron (copies of its neighbours' voxels, or of the edge) holds the other corners of q's
// trilinear footprint, so a bricked sample equals the whole texture's.
fn grid_uv(q: vec3<f32>) -> vec3<f32> {
    let p = clamp(q, vec3<f32>(0.0), ray.dims - 1.0);
    if !bricked() {
        return (p + 0.5) / ray.dims;
    }
    let brick = floor(p / ray.page_inner);
    return (brick_origin(brick) + (p - brick * ray.page_inner) + 0.5) * ray.atlas_inv;
}

// Texel coordinates of voxel v (clamped to the grid) in a grid texture read without filtering.
fn grid_texel(v: vec3<i32>) -> vec3<i32> {
    let c = clamp(v, vec3<i32>(0), vec3<i32>(ray.dims) - 1);
    if !bricked() {
        return c;
    }
    let inner = i32(ray.page_inner);
    let brick = c / inner;
    return vec3<i32>(brick_origin(vec3<f32>(brick))) + c - brick * inner;
}

// Whether the camera is orthographic (ray.orthographic, unless RAY_ORTHOGRAPHIC says).
fn orthographic() -> bool {
    return select(ray.orthographic != 0u, RAY_ORTHOGRAPHIC > 0, RAY_ORTHOGRAPHIC >= 0);
}

// Whether eq. 5 uses Schlick's approximation (ray.fast_exponent, unless RAY_FAST_EXPONENT says).
fn fast_exponent() -> bool {
    return select(ray.fast_exponent != 0u, RAY_FAST_EXPONENT > 0, RAY_FAST_EXPONENT >= 0);
}

// Returned by value_at where the sample leans on a "no data" voxel (the texture holds
// NO_DATA_TEXEL = -1000 there; NaN is not used because shader compilers may assume no NaN).
const NO_DATA: f32 = -1.0e30;

// The volume's normalised texel at continuous voxel coordinates q (clamped to the grid), by
// the reconstruction filter (RAY_RECONSTRUCTION); below −0.5 where it leans on "no data".
fn texel_at(q: vec3<f32>) -> f32 {
    if reconstruction() == RECONSTRUCTION_BSPLINE {
        return bspline_texel(q);
    }
    return trilinear_texel(q);
}

fn trilinear_texel(q: vec3<f32>) -> f32 {
    return textureSampleLevel(volume, linear_clamp, grid_uv(q), 0.0).r;
}

// Data value at continuous voxel coordinates q (clamped to the grid), or NO_DATA.
fn value_at(q: vec3<f32>) -> f32 {
    let normalised = texel_at(q);
    if normalised < -0.5 {
        return NO_DATA;
    }
    return ray.texel_values.x + normalised * (ray.texel_values.y - ray.texel_values.x);
}

// Whether a value from value_at is "no data" (transparent).
fn no_data(v: f32) -> bool {
    return v <= NO_DATA;
}

// World-space gradient at voxel-space q by the reconstruction filter: central differences of
// trilinear samples, or the B-spline's own derivative (Hadwiger §1.3); mapped to world units
// through the transform.
fn gradient_at(q: vec3<f32>) -> vec3<f32> {
    if reconstruction() == RECONSTRUCTION_BSPLINE {
        let g = bspline_gradient(q);
        if g.w == 0.0 {
            return (ray.grad_to_world * vec4<f32>(g.xyz, 0.0)).xyz;
        }
    }
    return central_gradient(q);
}

// Central differences in voxel space (one-sided at the border and next to "no data", 0 with no
// data on both sides), mapped to world units.
fn central_gradient(q: vec3<f32>) -> vec3<f32> {
    let top = ray.dims - 1.0;
    let p = clamp(q, vec3<f32>(0.0), top);
    var g = vec3<f32>(0.0);
    for (var axis = 0; axis < 3; axis++) {
        var lo = p;
        var hi = p;
        lo[axis] = max(p[axis] - 1.0, 0.0);
        hi[axis] = min(p[axis] + 1.0, top[axis]);
        let a = trilinear_value(lo);
        let b = trilinear_value(hi);
        if RAY_NO_DATA == 0 || (!no_data(a) && !no_data(b)) {
            g[axis] = (b - a) / (hi[axis] - lo[axis]);
        } else if !no_data(a) && p[axis] > lo[axis] {
            g[axis] = (trilinear_value(p) - a) / (p[axis] - lo[axis]);
        } else if !no_data(b) && hi[axis] > p[axis] {
            g[axis] = (b - trilinear_value(p)) / (hi[axis] - p[axis]);
        }
    }
    return (ray.grad_to_world * vec4<f32>(g, 0.0)).xyz;
}

// value_at with the trilinear filter whatever the reconstruction.
fn trilinear_value(q: vec3<f32>) -> f32 {
    let normalised = trilinear_texel(q);
    if normalised < -0.5 {
        return NO_DATA;
    }
    return ray.texel_values.x + normalised * (ray.texel_values.y - ray.texel_values.x);
}

// A hash of the pixel at `p` in [0, 1): PCG (O'Neill 2014) of the integer pixel, the same bits
// on every device. The usual fract(sin(x)·43758) rests on each driver's sin at large arguments,
// so the jitter, and the pictures, differed between drivers (lavapipe natively, SwiftShader in
// the browser, each real GPU).
fn hash(p: vec2<f32>) -> f32 {
    let q = bitcast<vec2<u32>>(vec2<i32>(floor(p)));
    return f32(ray_pcg(q.x ^ ray_pcg(q.y)) >> 8u) / 16777216.0;
}

fn ray_pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn to_window_depth(p: vec3<f32>) -> f32 {
    let clip = ray.view_proj * vec4<f32>(p, 1.0);
    return clip.z / clip.w;
}

// A pixel's ray: world-space origin p0 and unit direction dir, the same ray in voxel space
// (q = q0 + dq·t, t in world units), and where it enters and leaves the box of voxel centres.
struct PrimaryRay {
    p0: vec3<f32>,
    dir: vec3<f32>,
    q0: vec3<f32>,
    dq: vec3<f32>,
    t_in: f32,
    t_out: f32,
    // false when the ray misses the volume's box.
    hits: bool,
};

// The ray through pixel position `position` (pixel centres at .5, top-left origin).
fn primary_ray(position: vec2<f32>) -> PrimaryRay {
    var r: PrimaryRay;
    let ndc = vec2<f32>(position.x / ray.frame.x * 2.0 - 1.0, 1.0 - position.y / ray.frame.y * 2.0);
    let near4 = ray.inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    let far4 = ray.inv_view_proj * vec4<f32>(ndc, 1.0, 1.0);
    r.p0 = near4.xyz / near4.w;
    r.dir = normalize(far4.xyz / far4.w - r.p0);
    r.q0 = (ray.to_voxel * vec4<f32>(r.p0, 1.0)).xyz;
    r.dq = (ray.to_voxel * vec4<f32>(r.dir, 0.0)).xyz;
    // Slab test against the box of voxel centres, in voxel space.
    r.t_in = 0.0;
    r.t_out = 1e30;
    r.hits = true;
    for (var axis = 0; axis < 3; axis++) {
        if abs(r.dq[axis]) < 1e-12 {
            if r.q0[axis] < ray.box_min[axis] || r.q0[axis] > ray.box_max[axis] {
                r.hits = false;
            }
        } else {
            let a = (ray.box_min[axis] - r.q0[axis]) / r.dq[axis];
            let b = (ray.box_max[axis] - r.q0[axis]) / r.dq[axis];
            r.t_in = max(r.t_in, min(a, b));
            r.t_out = min(r.t_out, max(a, b));
        }
    }
    if r.t_in > r.t_out {
        r.hits = false;
    }
    return r;
}

// Unit vector from a world-space point towards the viewer, in view space.
fn view_direction(p: vec3<f32>) -> vec3<f32> {
    if orthographic() {
        return vec3<f32>(0.0, 0.0, 1.0);
    }
    return -normalize((ray.view * vec4<f32>(p, 1.0)).xyz);
}

// View-space unit normal from a world-space gradient (towards lower values: outward for bright
// objects); 0 where the gradient vanishes.
fn view_normal(g: vec3<f32>) -> vec3<f32> {
    let g_length = length(g);
    if g_length <= 1e-12 {
        return vec3<f32>(0.0);
    }
    return (ray.view * vec4<f32>(-g / g_length, 0.0)).xyz;
}

// What a ray leaves in its pixel: premultiplied colour, the view-space normal where it first
// became visible (w = 1 where there is one), and that point's window depth (1: none).
struct RayResult {
    color: vec4<f32>,
    normal: vec4<f32>,
    depth: f32,
};

// The fragment path's outputs: colour and normal attachments, the depth attachment.
struct FragmentOut {
    @location(0) color: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @builtin(frag_depth) depth: f32,
};

fn fragment_out(r: RayResult) -> FragmentOut {
    var out: FragmentOut;
    out.color = r.color;
    out.normal = r.normal;
    out.depth = r.depth;
    return out;
}

// The compute path: one invocation per pixel in 8×8 tiles writes storage textures (the depth
// as r32float; the pass copies it into the G-buffer's depth texture). On GPUs whose graphics
// pipeline runs on part of the chip only (H100/H200) this is the fast path.
@group(2) @binding(0) var out_color: texture_storage_2d<rgba16float, write>;
@group(2) @binding(1) var out_normal: texture_storage_2d<rgba16float, write>;
@group(2) @binding(2) var out_depth: texture_storage_2d<r32float, write>;

fn store_result(id: vec2<u32>, r: RayResult) {
    let pixel = vec2<i32>(id);
    textureStore(out_color, pixel, r.color);
    textureStore(out_normal, pixel, r.normal);
    textureStore(out_depth, pixel, vec4<f32>(r.depth, 0.0, 0.0, 0.0));
}

fn outside_frame(id: vec2<u32>) -> bool {
    return f32(id.x) >= ray.frame.x || f32(id.y) >= ray.frame.y;
}

// Tap i (0 … 26) of the 3-D Sobel operator of the smoothed mask gradients (two-level's object
// masks, SelectionRender's selection): its offset in {−1, 0, 1}³, and its weight in each
// axis' derivative — the offset along that axis times 1-2-1 across it, over 16 · 2 (the
// caller divides by the spacing h).
fn sobel_offset(i: i32) -> vec3<f32> {
    return vec3<f32>(f32(i % 3 - 1), f32((i / 3) % 3 - 1), f32(i / 9 - 1));
}

fn sobel_weights(o: vec3<f32>) -> vec3<f32> {
    let w = 2.0 - abs(o);
    return o * vec3<f32>(w.y * w.z, w.x * w.z, w.x * w.y) / 32.0;
}
