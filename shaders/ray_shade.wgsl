// Shading of a classified sample: Blinn–Phong (eq. 3 of the context-preserving paper), the
// VolumeShop lighting transfer function (eq. 8), context-preserving opacity (eq. 5) and style
// transfer functions (Bruckner & Gröller 2007: lit spheres §3.1/§4.1, style contours §3.3,
// illustrative transparency eq. 2).

// Ray.shading (hatchery_nodes::raycast::RayShading).
const SHADING_NONE: u32 = 0u;
const SHADING_PHONG: u32 = 1u;
const SHADING_LIGHTING: u32 = 2u;
const SHADING_CONTEXT: u32 = 3u;
const SHADING_STYLE: u32 = 4u;

// Eq. 3: c_a + c_d |L·N| + c_s |H·N|^c_e.
fn phong_term(n: vec3<f32>, l: vec3<f32>, hv: vec3<f32>) -> f32 {
    return ray.diffuse * abs(dot(l, n)) + ray.specular * pow(abs(dot(hv, n)), ray.shininess) + ray.ambient;
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
    let tk = clamp(ray.contour_thickness * kappa_v, 0.0, 1.0);
    return sqrt(tk * (2.0 - tk));
}

// One style layer at sphere-map coordinates (nx, ny), with an explicit mip level.
fn style_sample(layer: i32, nxy: vec2<f32>, lod: f32) -> vec4<f32> {
    let uv = vec2<f32>(nxy.x * 0.5 + 0.5, 0.5 - nxy.y * 0.5);
    return textureSampleLevel(styles, linear_clamp, uv, layer, lod);
}

// Schlick's rational approximation of x^n for x in [0, 1], n ≥ 0 (1 for n = 0 and x > 0).
fn schlick_pow(x: f32, n: f32) -> f32 {
    return x / max(n - n * x + x, 1e-30);
}

// Eq. 5: the opacity `a` of a sample at world position p with Phong term s, gradient magnitude
// g_norm ∈ [0, 1], after the accumulated opacity `alpha_before` (eye position from the uniforms;
// the near plane for orthographic cameras, p0 on the ray).
fn context_preserving(a: f32, s: f32, g_norm: f32, p: vec3<f32>, p0: vec3<f32>, alpha_before: f32) -> f32 {
    var eye = ray.eye;
    if orthographic() {
        eye = p0;
    }
    let dist = clamp((length(p - eye) - ray.distance_near) / max(ray.distance_far - ray.distance_near, 1e-20), 0.0, 1.0);
    let base = ray.kappa_t * s * (1.0 - dist) * (1.0 - alpha_before);
    if fast_exponent() {
        // The paper's §6: Schlick's x^n ≈ x / (n − n·x + x) for both exponentiations (eq. 6–7),
        // on [0, 1]; a base above 1 keeps pow for the inner one.
        if base <= 0.0 {
            return a;
        }
        var e: f32;
        if base <= 1.0 {
            e = schlick_pow(base, ray.kappa_s);
        } else {
            e = pow(base, ray.kappa_s);
        }
        return a * schlick_pow(clamp(g_norm, 0.0, 1.0), e);
    }
    var exponent = 0.0;
    if base > 0.0 {
        exponent = pow(base, ray.kappa_s);
    }
    if exponent != 0.0 {
        return a * pow(g_norm, exponent);
    }
    return a;
}

// A style transfer function's colour and opacity (§4.1–4.3, eq. 1 and 2) for table entry
// (i, α_u) on table row `t`, view-space normal n (0 if none), view direction v_dir, normalised
// gradient magnitude g_norm and curvature estimate kappa_v (angle between successive normals
// over the step; 0 at a ray's first sample or after a gap).
fn style_shade(entry: vec4<f32>, t: TableRow, n: vec3<f32>, v_dir: vec3<f32>, g_norm: f32, kappa_v: f32) -> vec4<f32> {
    let h = ray.step_world;
    let i = entry.x;
    let alpha_u = entry.y;
    let last = max(t.node_count - 1.0, 0.0);
    let i0 = clamp(floor(i), 0.0, last);
    let i1 = min(i0 + 1.0, last);
    let w = clamp(i - i0, 0.0, 1.0);
    let j0 = i32(textureLoad(style_index, vec2<i32>(i32(i0), t.row), 0).r + 0.5);
    let j1 = i32(textureLoad(style_index, vec2<i32>(i32(i1), t.row), 0).r + 0.5);
    let n_dot_v = dot(n, v_dir);
    let limit = contour_limit(kappa_v);
    var nxy = n.xy;
    let r = length(nxy);
    if ray.contours != 0u && limit > 0.0 && abs(n_dot_v) <= limit && r > 0.0 {
        // Push the sphere-map coordinates outwards: r' = min(1, r / δ).
        let delta = 1.0 - min(1.0, (limit - abs(n_dot_v)) / limit);
        var r_new = 1.0;
        if delta > 0.0 {
            r_new = min(1.0, r / delta);
        }
        nxy = nxy * (r_new / r);
    }
    // Mip level from how far the normal turns across one step (§4.3), plus a bias.
    let lod = max(log2(max(kappa_v * h * ray.style_map_size * 0.5, 1.0)) + ray.mip_bias, 0.0);
    let styled = mix(style_sample(j0, nxy, lod), style_sample(j1, nxy, lod), w);
    var a = styled.a * alpha_u;
    if ray.transparency != 0u {
        // Illustrative transparency, eq. 2.
        let exponent = 0.5 + max(0.0, abs(n_dot_v) - limit) * (1.0 - g_norm);
        var factor = 0.0;
        if alpha_u > 0.0 {
            factor = pow(alpha_u, exponent);
        }
        a = styled.a * factor;
    }
    return vec4<f32>(styled.rgb, a);
}

// Shaded colour of a surface point (iso mode): base colour c, view-space normal n.
fn shade_surface(c: vec3<f32>, n: vec3<f32>, l: vec3<f32>, hv: vec3<f32>, shading: u32) -> vec3<f32> {
    if shading == SHADING_PHONG || shading == SHADING_CONTEXT {
        return clamp(c * phong_term(n, l, hv), vec3<f32>(0.0), vec3<f32>(1.0));
    }
    if shading == SHADING_LIGHTING {
        let lt = lighting_lookup(dot(n, l), dot(n, hv));
        return clamp((lt.x + lt.y) * c + lt.z, vec3<f32>(0.0), vec3<f32>(1.0));
    }
    return c;
}
