// Blinn–Phong shading: the "standard rendering" illustrative pipelines are compared with.

struct Shading {
    base_color: vec4<f32>,
    // View-space unit vector towards the light.
    light_dir: vec4<f32>,
    // rgb = light colour, w = intensity.
    light_color: vec4<f32>,
    // x = ambient, y = specular strength, z = shininess, w = 1 for two-sided lighting.
    params: vec4<f32>,
};

@group(0) @binding(1) var<uniform> shading: Shading;

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    var n = normalize(in.view_normal);
    let v = to_viewer(in.view_pos);
    if shading.params.w > 0.5 && dot(n, v) < 0.0 {
        n = -n;
    }
    let l = shading.light_dir.xyz;
    let h = normalize(l + v);
    let diffuse = max(dot(n, l), 0.0);
    var specular = 0.0;
    if diffuse > 0.0 {
        specular = pow(max(dot(n, h), 0.0), shading.params.z);
    }
    let light = shading.light_color.rgb * shading.light_color.w;
    let base = shading.base_color.rgb;
    let rgb = base * shading.params.x + base * diffuse * light + shading.params.y * specular * light;
    let alpha = shading.base_color.a;
    return vec4<f32>(rgb * alpha, alpha);
}
