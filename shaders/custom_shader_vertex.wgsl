// The vertex stage of every CustomShader: one triangle covering the frame. The user's file has
// only the fragment stage, which may take `@builtin(position)` (pixel centres, y down) and
// `@location(0) uv: vec2<f32>` (0..1 across the frame, (0, 0) at the top-left, as texture
// coordinates run).

struct CustomVertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> CustomVertexOut {
    // Vertices (-1,-1), (3,-1), (-1,3) in clip space: the whole viewport.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: CustomVertexOut;
    out.position = vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
    // Clip y up → texture v down.
    out.uv = vec2<f32>(corner.x, 1.0 - corner.y);
    return out;
}
