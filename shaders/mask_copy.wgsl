// Copies the first channel of a texture into a Mask (R32Float): HatchStrokes draws into a
// blendable R16Float target (max blending of overlapping strokes), Masks are 32-bit.

@group(0) @binding(0) var source: texture_2d<f32>;

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(load_clamped(source, pixel_of(position)).r, 0.0, 0.0, 1.0);
}
