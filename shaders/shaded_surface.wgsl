// Blinn–Phong shading: the "standard rendering" illustrative pipelines are compared with.

struct Shading {
    base_color: vec4<f32>,
    // View-space unit vector towards the light.
    light_dir: vec3<f32>,
    // 1 for two-sided lighting.
    two_sided: u32,
    // The light's colour and intensity.
    light_color: vec3<f32>,
    intensity: f32,
    ambient: f32,
    specular: f32,
    shininess: f32,
    pad0: f32,
};

@group(0) @binding(1) var<uniform> shading: Shading;

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    var n = normalize(in.view_normal);
    let v = to_viewer(in.view_pos);
    if shading.two_sided != 0u && dot(n, v) < 0.0 {
        n = -n;
    }
    let l = shading.light_dir;
    let h = normalize(l + v);
    let diffuse = max(dot(n, l), 0.0);
    var specular = 0.0;
    if diffuse > 0.0 {
        specular = pow(max(dot(n, h), 0.0), shading.shininess);
    }
    let light = shading.light_color * shading.intensity;
    let base = shading.base_color.rgb;
    let rgb = base * shading.ambient + base * diffuse * light + shading.specular * specular * light;
    let alpha = shading.base_color.a;
    return vec4<f32>(rgb * alpha, alpha);
}
