// Depth peeling (Fischer et al. 2005, §3.1): a fragment survives only behind the previous
// layer's depth; the ordinary depth test then keeps the nearest survivor.

@group(0) @binding(1) var previous_depth: texture_depth_2d;

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    let previous = textureLoad(previous_depth, vec2<i32>(floor(in.clip.xy)), 0);
    if in.clip.z <= previous {
        discard;
    }
    return vec4<f32>(normalize(in.view_normal), 1.0);
}
