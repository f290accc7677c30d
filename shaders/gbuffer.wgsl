// GBuffer pass (Fischer et al. 2005, §3.1): the depth buffer keeps window-space depth, the colour
// target the interpolated view-space normal with coverage in w.

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(normalize(in.view_normal), 1.0);
}
