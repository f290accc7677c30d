// Per-pixel arithmetic of two masks: and (a·b), or (max), min, add, subtract (both clamped to
// [0, 1]), and a_not_b (a·(1 - b)).

struct Combine {
    // x = operation (0 and, 1 or, 2 min, 3 add, 4 subtract, 5 a_not_b).
    options: vec4<f32>,
};

@group(0) @binding(0) var mask_a: texture_2d<f32>;
@group(0) @binding(1) var mask_b: texture_2d<f32>;
@group(0) @binding(2) var<uniform> combine: Combine;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let a = textureLoad(mask_a, p, 0).r;
    let b = textureLoad(mask_b, p, 0).r;
    var r = a * b;
    switch i32(combine.options.x + 0.5) {
        case 1: { r = max(a, b); }
        case 2: { r = min(a, b); }
        case 3: { r = clamp(a + b, 0.0, 1.0); }
        case 4: { r = clamp(a - b, 0.0, 1.0); }
        case 5: { r = a * (1.0 - b); }
        default: {}
    }
    return vec4<f32>(r, 0.0, 0.0, 1.0);
}
