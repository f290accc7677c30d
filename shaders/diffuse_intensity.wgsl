// Diffuse intensity of a G-buffer layer (Fischer et al. 2005, eq. 1 and 6): max(n · l, 0).
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

struct Diffuse {
    // Inverse projection, to find the view direction of a pixel.
    inverse_proj: mat4x4<f32>,
    // View-space unit vector towards the light, and the value where the layer is empty
    // (two-sided lighting is a constant of the pass).
    light_dir: vec3<f32>,
    empty: f32,
    // Frame size in pixels, and 1 for an orthographic camera.
    frame: vec2<f32>,
    orthographic: u32,
    pad0: f32,
};

// The intensity at pixel p from the layer's window depth and normal (w = coverage) there.
// `two_sided` is a constant of the pass (a uniform branch costs its code on lavapipe).
fn diffuse_intensity(p: vec2<i32>, u: Diffuse, depth: f32, normal: vec4<f32>, two_sided: bool) -> vec4<f32> {
    if normal.w < 0.5 {
        return vec4<f32>(u.empty, 0.0, 0.0, 1.0);
    }
    var n = normalize(normal.xyz);
    if two_sided {
        // The pixel's centre in normalised device coordinates.
        let centre = vec2<f32>(p) + 0.5;
        let ndc = vec2<f32>(centre.x / u.frame.x * 2.0 - 1.0, 1.0 - centre.y / u.frame.y * 2.0);
        let view = u.inverse_proj * vec4<f32>(ndc, depth, 1.0);
        let view_pos = view.xyz / view.w;
        // Orthographic cameras look along -z everywhere; perspective ones towards the point.
        var to_viewer = normalize(-view_pos);
        if u.orthographic != 0u {
            to_viewer = vec3<f32>(0.0, 0.0, 1.0);
        }
        if dot(n, to_viewer) < 0.0 {
            n = -n;
        }
    }
    return vec4<f32>(max(dot(n, u.light_dir), 0.0), 0.0, 0.0, 1.0);
}
