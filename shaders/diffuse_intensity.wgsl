// Diffuse intensity of a G-buffer layer (Fischer et al. 2005, eq. 1 and 6): max(n · l, 0).

struct Diffuse {
    // View-space unit vector towards the light.
    light_dir: vec4<f32>,
    // x = value where the layer is empty, y = 1 for two-sided lighting.
    options: vec4<f32>,
    // Inverse projection, to find the view direction of a pixel.
    inverse_proj: mat4x4<f32>,
    // x, y = frame size in pixels.
    frame: vec4<f32>,
};

@group(0) @binding(0) var layer_depth: texture_depth_2d;
@group(0) @binding(1) var layer_normal: texture_2d<f32>;
@group(0) @binding(2) var<uniform> diffuse: Diffuse;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let normal = textureLoad(layer_normal, p, 0);
    if normal.w < 0.5 {
        return vec4<f32>(diffuse.options.x, 0.0, 0.0, 1.0);
    }
    var n = normalize(normal.xyz);
    if diffuse.options.y > 0.5 {
        let depth = textureLoad(layer_depth, p, 0);
        let ndc = vec2<f32>(in.position.x / diffuse.frame.x * 2.0 - 1.0, 1.0 - in.position.y / diffuse.frame.y * 2.0);
        let view = diffuse.inverse_proj * vec4<f32>(ndc, depth, 1.0);
        let view_pos = view.xyz / view.w;
        // Orthographic cameras look along -z everywhere; perspective ones towards the point.
        var to_viewer = normalize(-view_pos);
        if diffuse.frame.z > 0.5 {
            to_viewer = vec3<f32>(0.0, 0.0, 1.0);
        }
        if dot(n, to_viewer) < 0.0 {
            n = -n;
        }
    }
    return vec4<f32>(max(dot(n, diffuse.light_dir.xyz), 0.0), 0.0, 0.0, 1.0);
}
