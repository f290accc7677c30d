// mix(base, over, mask) per pixel: over is an image, or a colour when no image is connected.
// The mix of the §3.3.4 pseudocode of Fischer et al. 2005.

struct MixParams {
    // Premultiplied colour used when `over` is not connected.
    color: vec4<f32>,
    // x = 1 when `over` is an image.
    options: vec4<f32>,
};

@group(0) @binding(0) var base: texture_2d<f32>;
@group(0) @binding(1) var over: texture_2d<f32>;
@group(0) @binding(2) var mask: texture_2d<f32>;
@group(0) @binding(3) var<uniform> mixing: MixParams;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    var top = mixing.color;
    if mixing.options.x > 0.5 {
        top = textureLoad(over, p, 0);
    }
    let m = clamp(textureLoad(mask, p, 0).r, 0.0, 1.0);
    return mix(textureLoad(base, p, 0), top, m);
}
