// CurvatureContours: contours of constant image-space thickness from the normal curvature along
// the view direction (Kindlmann et al. 2003 §5, the tutorial's §1 "curvature-controlled
// contours"). A plain |n·v| ≤ ε contour is thin where the surface bends sharply and thick where
// it is flat; Kindlmann's test |n·v| ≤ √(T κv (2 − T κv)) (T κv < 1; always when T κv ≥ 1) marks
// a band about T wide on screen, κv = −w·H w / |g| the normal curvature along w, the view
// direction projected into the tangent plane, T = `thickness` pixels at the surface point's
// depth (world units). Surfaces concave along the view (κv ≤ 0) get no contour. Output: a mask,
// 1 on the contour. Prepended: fullscreen, ray_common, curvature_common.

struct ContourParams {
    // Contour width (pixels).
    thickness: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
};
@group(1) @binding(2) var<uniform> contour: ContourParams;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let surface = surface_point(in.position);
    if surface.w == 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let p = surface.xyz;
    let g = world_gradient(p);
    let g_length = length(g);
    if g_length < 1e-12 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let n = -g / g_length;
    // Towards the viewer, and one pixel's world size, from the points of the same depth and of
    // the near plane under neighbouring pixels (orthographic and perspective alike).
    let ndc = vec2<f32>(in.position.x / ray.frame.x * 2.0 - 1.0, 1.0 - in.position.y / ray.frame.y * 2.0);
    let near4 = ray.inv_view_proj * vec4<f32>(ndc, 0.0, 1.0);
    let v = normalize(near4.xyz / near4.w - p);
    let clip = ray.view_proj * vec4<f32>(p, 1.0);
    let side4 = ray.inv_view_proj * vec4<f32>(ndc + vec2<f32>(2.0 / ray.frame.x, 0.0), clip.z / clip.w, 1.0);
    let pixel_size = length(side4.xyz / side4.w - p);
    let along = v - dot(v, n) * n;
    if dot(along, along) < 1e-12 {
        // Facing the viewer head-on: no contour.
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let w = normalize(along);
    let kappa_v = -dot(w, hessian_at(p) * w) / g_length;
    let tk = contour.thickness * pixel_size * kappa_v;
    if tk <= 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    let limit = select(sqrt(tk * (2.0 - tk)), 1.0, tk >= 1.0);
    return vec4<f32>(select(0.0, 1.0, abs(dot(n, v)) <= limit), 0.0, 0.0, 1.0);
}
