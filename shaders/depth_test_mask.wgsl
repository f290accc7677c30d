// 1 where depth A compares true against depth B, else 0 (the depth test of Fischer et al. 2005,
// eq. 10: depth_P2 <= depth_S). A stage of a fused image-space pass
// (crates/hatchery-nodes/src/fused_pass/).

// `compare`, a constant of the pass: 0 <=, 1 <, 2 >=, 3 >.
fn depth_test_mask(p: vec2<i32>, a: f32, b: f32, compare: i32) -> vec4<f32> {
    var pass_test = a <= b;
    switch compare {
        case 1: { pass_test = a < b; }
        case 2: { pass_test = a >= b; }
        case 3: { pass_test = a > b; }
        default: {}
    }
    return vec4<f32>(select(0.0, 1.0, pass_test), 0.0, 0.0, 1.0);
}
