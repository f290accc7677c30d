// Curvature: principal curvatures κ1 ≥ κ2 and the first principal direction of the iso-surface
// seen in a G-buffer (Hadwiger's deferred iso-surface shading in the tutorial, §1; the shape
// operator from gradient and Hessian as in Kindlmann et al. 2003). Per pixel: the surface point
// p from the G-buffer's depth; the volume's world gradient g at p (central differences, as the
// ray casters shade) and its Hessian H by central differences of that gradient along the world
// axes at ±h; with n = −g/|g| (outward where the field is larger inside) and a tangent basis
// (t1, t2) of n, the 2×2 shape operator A_ab = −t_a·H t_b / |g|; κ1,2 its eigenvalues (positive
// for a convex bump) and the first principal direction its κ1 eigenvector. Output: (κ1, κ2, θ1,
// θ2), κ in world units⁻¹, θ1, θ2 the screen angles of the principal directions (radians in
// [−π/2, π/2), x right, y down); (0, 0, −10, −10) where the G-buffer holds no surface.
// Prepended: fullscreen, ray_common, ray_bspline, curvature_shape (the shape operator),
// curvature_common.

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let surface = surface_point(in.position);
    if surface.w == 0.0 {
        return vec4<f32>(0.0, 0.0, NONE, NONE);
    }
    let p = surface.xyz;
    let g = world_gradient(p);
    let g_length = length(g);
    if g_length < 1e-12 {
        return vec4<f32>(0.0, 0.0, NONE, NONE);
    }
    let hessian = hessian_at(p);
    let s = shape_operator(g, g_length, hessian);
    let n = s.n;
    let t1 = s.t1;
    let t2 = s.t2;
    let a = s.a;
    let b = s.b;
    let c = s.c;
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
    return vec4<f32>(k1, k2, screen_angle(p, d), screen_angle(p, cross(n, d)));
}
