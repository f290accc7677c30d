// Schlieren: simulated Schlieren photographs and shadowgraphs of a volume (Svakhine, Ebert et
// al. 2005, "Illustration and photography inspired visualization of flows and volumes", §4
// "Photographic techniques", eq. 1–5; in ../shared/seeds/viola2005_illustrative_visualization_
// tutorial.md). Prepended: ray_common (uniforms, sampling, the primary ray) and ray_bspline.
//
// Pass 1 of the paper (the integral along the light path) and pass 2 (displacement → picture)
// are one ray here: each ray integrates, over the volume's box, the density gradient's
// components across the ray along the image's x and y axes (eq. 1: the deflection ε) and the
// Laplacian across the ray (eq. 2: the shadowgraph's L), with central differences at ±h along
// the two transverse world directions; then maps them to intensity by eq. 3 (knife edge),
// eq. 4 (circular cutoff), a colour wheel (colour Schlieren) or eq. 5 (shadowgraph).

struct Schlieren {
    // The knife edge's normal k in the image plane (x right, y up), unit length.
    knife: vec2<f32>,
    // The sensitivity (eq. 1's constant) and s of eq. 3–5.
    gain: f32,
    brightness: f32,
    // A SCHLIEREN_* constant.
    mode: u32,
    // Samples whose transverse gradient (per voxel, in value ranges) is below this add nothing.
    threshold: f32,
    // The finite-difference spacing h in world units.
    difference: f32,
    // 1 / the volume's value range: ε in value ranges.
    deflection_scale: f32,
    // The smallest spacing / the value range: L (and the threshold's gradient) per voxel, in
    // value ranges.
    per_voxel_scale: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
};

@group(1) @binding(0) var<uniform> schlieren: Schlieren;

// Schlieren.mode (hatchery_nodes::schlieren::SchlierenMode).
const SCHLIEREN_KNIFE_EDGE: u32 = 0u;
const SCHLIEREN_CIRCULAR: u32 = 1u;
const SCHLIEREN_COLOR: u32 = 2u;
const SCHLIEREN_SHADOWGRAPH: u32 = 3u;
const SCHLIEREN_SHADOWGRAPH_ABS: u32 = 4u;

// The ray integrals of pixel position `position`: (ε_x, ε_y) = ∫ ∂ρ/∂x', ∂ρ/∂y' dz (eq. 1,
// x', y' the image's axes made perpendicular to the ray) in units of the value range, and
// L = ∫ ∂²ρ/∂x'² + ∂²ρ/∂y'² dz (eq. 2) per voxel of the smallest spacing in units of the value
// range. Midpoint rule over the box of voxel centres, as many equal steps as the sample distance
// asks for; samples next to "no data" add nothing.
fn deflection(position: vec2<f32>) -> vec3<f32> {
    let r = primary_ray(position);
    if !r.hits {
        return vec3<f32>(0.0);
    }
    // The image's right and up axes made perpendicular to this ray (exact for orthographic
    // cameras): right is the view matrix's first row.
    let right = vec3<f32>(ray.view[0].x, ray.view[1].x, ray.view[2].x);
    let ex = normalize(right - dot(right, r.dir) * r.dir);
    let ey = cross(-r.dir, ex);
    let h = schlieren.difference;
    let qx = (ray.to_voxel * vec4<f32>(ex * h, 0.0)).xyz;
    let qy = (ray.to_voxel * vec4<f32>(ey * h, 0.0)).xyz;
    let span = r.t_out - r.t_in;
    let count = u32(clamp(ceil(span / ray.step_world), 1.0, 65536.0));
    let dt = span / f32(count);
    var sum = vec3<f32>(0.0);
    for (var k = 0u; k < count; k++) {
        let q = r.q0 + r.dq * (r.t_in + (f32(k) + 0.5) * dt);
        let c = value_at(q);
        let xp = value_at(q + qx);
        let xm = value_at(q - qx);
        let yp = value_at(q + qy);
        let ym = value_at(q - qy);
        if no_data(c) || no_data(xp) || no_data(xm) || no_data(yp) || no_data(ym) {
            continue;
        }
        let g = vec2<f32>(xp - xm, yp - ym) / (2.0 * h);
        if length(g) * schlieren.per_voxel_scale < schlieren.threshold {
            continue;
        }
        let laplacian = (xp + xm + yp + ym - 4.0 * c) / (h * h);
        sum += vec3<f32>(g, laplacian) * dt;
    }
    return vec3<f32>(
        sum.xy * schlieren.deflection_scale,
        sum.z * schlieren.per_voxel_scale
    );
}

// Hue h (radians; 0 red, 2π/3 green, 4π/3 blue), saturation s, value v → RGB.
fn hsv_to_rgb(h: f32, s: f32, v: f32) -> vec3<f32> {
    let sector = fract(h / 6.283185307) * 6.0;
    let k = (vec3<f32>(5.0, 3.0, 1.0) + sector) % 6.0;
    return v - v * s * clamp(min(k, 4.0 - k), vec3<f32>(0.0), vec3<f32>(1.0));
}

// The picture of the integrals d = (ε_x, ε_y, L): eq. 3–5 with ε and L scaled by the gain.
fn photograph(d: vec3<f32>) -> vec3<f32> {
    let s = schlieren.brightness;
    let eps = d.xy * schlieren.gain;
    let l = d.z * schlieren.gain;
    var c = vec3<f32>(0.0);
    switch schlieren.mode {
        case SCHLIEREN_CIRCULAR: {
            c = vec3<f32>(s * length(eps));
        }
        case SCHLIEREN_COLOR: {
            let m = length(eps);
            var hue = 0.0;
            if m > 0.0 {
                hue = atan2(eps.y, eps.x);
            }
            c = hsv_to_rgb(hue, min(m, 1.0), s);
        }
        case SCHLIEREN_SHADOWGRAPH: {
            c = vec3<f32>(s * (1.0 + l) / 2.0);
        }
        case SCHLIEREN_SHADOWGRAPH_ABS: {
            c = vec3<f32>(s * (1.0 + abs(l)) / 2.0);
        }
        default: {
            c = vec3<f32>(s * (1.0 + dot(eps, schlieren.knife)) / 2.0);
        }
    }
    return clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
}

// The colour target holds the photograph (opaque), the normal target the integrals
// (ε_x, ε_y, L, 1) before the gain; no depth.
fn cast_schlieren(position: vec2<f32>) -> RayResult {
    let d = deflection(position);
    var out: RayResult;
    out.color = vec4<f32>(photograph(d), 1.0);
    out.normal = vec4<f32>(d, 1.0);
    out.depth = 1.0;
    return out;
}

@fragment
fn fs_main(in: ScreenOut) -> FragmentOut {
    return fragment_out(cast_schlieren(in.position.xy));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !outside_frame(id.xy) {
        store_result(id.xy, cast_schlieren(vec2<f32>(id.xy) + 0.5));
    }
}
