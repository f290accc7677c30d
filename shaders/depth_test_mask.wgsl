// 1 where depth A compares true against depth B, else 0 (the depth test of Fischer et al. 2005,
// eq. 10: depth_P2 <= depth_S).

struct DepthTest {
    // x = comparison (0 <=, 1 <, 2 >=, 3 >).
    options: vec4<f32>,
};

@group(0) @binding(0) var depth_a: texture_depth_2d;
@group(0) @binding(1) var depth_b: texture_depth_2d;
@group(0) @binding(2) var<uniform> test: DepthTest;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let a = textureLoad(depth_a, p, 0);
    let b = textureLoad(depth_b, p, 0);
    var pass_test = a <= b;
    switch i32(test.options.x + 0.5) {
        case 1: { pass_test = a < b; }
        case 2: { pass_test = a >= b; }
        case 3: { pass_test = a > b; }
        default: {}
    }
    return vec4<f32>(select(0.0, 1.0, pass_test), 0.0, 0.0, 1.0);
}
