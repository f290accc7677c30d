// Shared by Curvature and CurvatureContours (prepended after fullscreen, ray_common, ray_bspline
// and curvature_shape): the G-buffer depth, the finite-difference step, the volume's Hessian at a
// surface point with that step (curvature_shape's world_hessian), and the screen angle of a
// world direction.

@group(1) @binding(0) var gbuffer_depth: texture_depth_2d;

// θ of a pixel without a surface (outside [−π/2, π/2)).
const NONE: f32 = -10.0;

// The screen angle of world direction d at world point p, wrapped into [−π/2, π/2) (a
// direction, not an orientation): p and p + ε·d (ε = the finite-difference step) projected to
// the screen (x right, y down), so perspective foreshortening off the view axis is included.
fn screen_angle(p: vec3<f32>, d: vec3<f32>) -> f32 {
    // One finite-difference step: far enough for f32 precision, near enough to be linear.
    let eps = max(curvature_params.step, 1e-6);
    let a = ray.view_proj * vec4<f32>(p, 1.0);
    let b = ray.view_proj * vec4<f32>(p + eps * d, 1.0);
    let s = b.xy / b.w - a.xy / a.w;
    var theta = atan2(-s.y * ray.frame.y, s.x * ray.frame.x);
    if theta >= 1.5707964 {
        theta -= 3.1415927;
    } else if theta < -1.5707964 {
        theta += 3.1415927;
    }
    return theta;
}

struct CurvatureParams {
    // Finite-difference step h (world units).
    step: f32,
    pad0: f32,
    pad1: f32,
    pad2: f32,
};
@group(1) @binding(1) var<uniform> curvature_params: CurvatureParams;


// The surface point under the fragment (world), w = 0 where the G-buffer holds no surface.
fn surface_point(position: vec4<f32>) -> vec4<f32> {
    let z = textureLoad(gbuffer_depth, pixel_of(position), 0);
    if z >= 1.0 {
        return vec4<f32>(0.0);
    }
    let ndc = vec2<f32>(position.x / ray.frame.x * 2.0 - 1.0, 1.0 - position.y / ray.frame.y * 2.0);
    let h4 = ray.inv_view_proj * vec4<f32>(ndc, z, 1.0);
    return vec4<f32>(h4.xyz / h4.w, 1.0);
}

// The Hessian of the volume at world point p with this pass's finite-difference step (see
// curvature_shape's world_hessian).
fn hessian_at(p: vec3<f32>) -> mat3x3<f32> {
    return world_hessian(p, curvature_params.step);
}
