// Secondary geometry (Fischer et al. 2005, §3.2): diffuse intensity (eq. 1) attenuated by how many
// iso-surface layers lie in front (eq. 2): 1 in front of layer 1, alpha between layers 1 and 2,
// beta behind layer 2.

struct Secondary {
    // View-space unit vector towards the light.
    light_dir: vec3<f32>,
    // 1 for two-sided lighting.
    two_sided: u32,
    // Attenuation behind one layer (α) and behind two (β), eq. 10.
    alpha: f32,
    beta: f32,
    pad0: f32,
    pad1: f32,
};

@group(0) @binding(1) var layer1_depth: texture_depth_2d;
@group(0) @binding(2) var layer2_depth: texture_depth_2d;
@group(0) @binding(3) var<uniform> secondary: Secondary;

struct SecondaryOut {
    @location(0) intensity: vec4<f32>,
    @location(1) normal: vec4<f32>,
};

@fragment
fn fs_main(in: VertexOut) -> SecondaryOut {
    var n = normalize(in.view_normal);
    if secondary.two_sided != 0u && dot(n, to_viewer(in.view_pos)) < 0.0 {
        n = -n;
    }
    let i0 = max(dot(n, secondary.light_dir), 0.0);
    let p = vec2<i32>(floor(in.clip.xy));
    let d = in.clip.z;
    let d1 = textureLoad(layer1_depth, p, 0);
    let d2 = textureLoad(layer2_depth, p, 0);
    var factor = secondary.beta;
    if d < d1 {
        factor = 1.0;
    } else if d < d2 {
        factor = secondary.alpha;
    }
    var out: SecondaryOut;
    out.intensity = vec4<f32>(i0 * factor, 0.0, 0.0, 1.0);
    out.normal = vec4<f32>(n, 1.0);
    return out;
}
