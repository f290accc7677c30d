// mix(base, over, mask) per pixel: over is an image, or a colour when no image is connected.
// The mix of the §3.3.4 pseudocode of Fischer et al. 2005.
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

struct MixParams {
    // Premultiplied colour used when `over` is not connected.
    color: vec4<f32>,
};

// `use_over` (an image is connected to `over`) is a constant of the pass.
fn mix_by_mask(p: vec2<i32>, u: MixParams, base: vec4<f32>, mask: vec4<f32>, over_image: vec4<f32>, use_over: bool) -> vec4<f32> {
    var top = u.color;
    if use_over {
        top = over_image;
    }
    return mix(base, top, clamp(mask.r, 0.0, 1.0));
}
