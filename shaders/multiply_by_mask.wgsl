// Colour times a mask (or one minus it): the "pixelColor *= ..." lines of the §3.3.4 pseudocode
// of Fischer et al. 2005. Alpha is kept, so the colour darkens towards black ink.
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

// `invert` (multiply by 1 − mask) is a constant of the pass.
fn multiply_by_mask(p: vec2<i32>, image: vec4<f32>, mask: vec4<f32>, invert: bool) -> vec4<f32> {
    var m = clamp(mask.r, 0.0, 1.0);
    if invert {
        m = 1.0 - m;
    }
    return vec4<f32>(image.rgb * m, image.a);
}
