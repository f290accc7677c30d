// Curvature: principal curvatures κ1 ≥ κ2 and the first principal direction of the iso-surface
// seen in a G-buffer (Hadwiger's deferred iso-surface shading in the tutorial, §1; the shape
// operator from gradient and Hessian as in Kindlmann et al. 2003). Per pixel: the surface point
// p from the G-buffer's depth; the volume's world gradient g at p (central differences, as the
// ray casters shade) and its Hessian H by central differences of that gradient along the world
// axes at ±h; with n = −g/|g| (outward where the field is larger inside) and a tangent basis
// (t1, t2) of n, the 2×2 shape operator A_ab = −t_a·H t_b / |g|; κ1,2 its eigenvalues (positive
// for a convex bump) and the first principal direction its κ1 eigenvector. Output: (κ1, κ2, θ,
// 1) in world units⁻¹, θ the screen angle of the first principal direction (radians in
// [−π/2, π/2), x right, y down); (0, 0, 0, 0) where the G-buffer holds no surface.
// Prepended: fullscreen, ray_common.

@group(0) @binding(20) var gbuffer_depth: texture_depth_2d;

// θ of a pixel without a surface (outside [−π/2, π/2)).
const NONE: f32 = -10.0;

// The screen angle of world direction d, wrapped into [−π/2, π/2) (a direction, not an
// orientation).
fn screen_angle(d: vec3<f32>) -> f32 {
    let dv = (ray.view * vec4<f32>(d, 0.0)).xyz;
    var theta = atan2(-dv.y, dv.x);
    if theta >= 1.5707964 {
        theta -= 3.1415927;
    } else if theta < -1.5707964 {
        theta += 3.1415927;
    }
    return theta;
}

struct CurvatureParams {
    // x = finite-difference step h (world units).
    step: vec4<f32>,
};
@group(0) @binding(22) var<uniform> curvature_params: CurvatureParams;

fn world_gradient(p: vec3<f32>) -> vec3<f32> {
    return gradient_at((ray.to_voxel * vec4<f32>(p, 1.0)).xyz);
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let pixel = pixel_of(in.position);
    let z = textureLoad(gbuffer_depth, pixel, 0);
    if z >= 1.0 {
        return vec4<f32>(0.0, 0.0, NONE, NONE);
    }
    let ndc = vec2<f32>(in.position.x / ray.frame.x * 2.0 - 1.0, 1.0 - in.position.y / ray.frame.y * 2.0);
    let h4 = ray.inv_view_proj * vec4<f32>(ndc, z, 1.0);
    let p = h4.xyz / h4.w;
    let g = world_gradient(p);
    let g_length = length(g);
    if g_length < 1e-12 {
        return vec4<f32>(0.0, 0.0, NONE, NONE);
    }
    let h = curvature_params.step.x;
    var columns: array<vec3<f32>, 3>;
    for (var axis = 0; axis < 3; axis++) {
        var e = vec3<f32>(0.0);
        e[axis] = h;
        columns[axis] = (world_gradient(p + e) - world_gradient(p - e)) / (2.0 * h);
    }
    var hessian = mat3x3<f32>(columns[0], columns[1], columns[2]);
    hessian = 0.5 * (hessian + transpose(hessian));
    let n = -g / g_length;
    var helper = vec3<f32>(1.0, 0.0, 0.0);
    if abs(n.x) > 0.9 {
        helper = vec3<f32>(0.0, 1.0, 0.0);
    }
    let t1 = normalize(cross(n, helper));
    let t2 = cross(n, t1);
    let a = -dot(t1, hessian * t1) / g_length;
    let b = -dot(t1, hessian * t2) / g_length;
    let c = -dot(t2, hessian * t2) / g_length;
    let mean = 0.5 * (a + c);
    let spread = sqrt(0.25 * (a - c) * (a - c) + b * b);
    let k1 = mean + spread;
    let k2 = mean - spread;
    var v = vec2<f32>(1.0, 0.0);
    if abs(b) > 1e-9 * max(abs(a) + abs(c), 1e-20) {
        v = vec2<f32>(b, k1 - a);
    } else if c > a {
        v = vec2<f32>(0.0, 1.0);
    }
    let d = normalize(v.x * t1 + v.y * t2);
    return vec4<f32>(k1, k2, screen_angle(d), screen_angle(cross(n, d)));
}
