// Porter–Duff "over" of premultiplied colours: front + (1 − front.a) · back.

@group(0) @binding(0) var front: texture_2d<f32>;
@group(0) @binding(1) var back: texture_2d<f32>;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let f = textureLoad(front, p, 0);
    return f + (1.0 - f.a) * textureLoad(back, p, 0);
}
