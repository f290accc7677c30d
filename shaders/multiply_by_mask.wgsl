// Colour times a mask (or one minus it): the "pixelColor *= ..." lines of the §3.3.4 pseudocode
// of Fischer et al. 2005. Alpha is kept, so the colour darkens towards black ink.

struct MultiplyParams {
    // x = 1 to multiply by (1 - mask).
    options: vec4<f32>,
};

@group(0) @binding(0) var image: texture_2d<f32>;
@group(0) @binding(1) var mask: texture_2d<f32>;
@group(0) @binding(2) var<uniform> multiply: MultiplyParams;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    var m = clamp(textureLoad(mask, p, 0).r, 0.0, 1.0);
    if multiply.options.x > 0.5 {
        m = 1.0 - m;
    }
    let c = textureLoad(image, p, 0);
    return vec4<f32>(c.rgb * m, c.a);
}
