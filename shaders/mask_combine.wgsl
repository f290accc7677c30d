// Per-pixel arithmetic of two masks: and (a·b), or (max), min, add, subtract (both clamped to
// [0, 1]), and a_not_b (a·(1 - b)).
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

// `operation`, a constant of the pass: 0 and, 1 or, 2 min, 3 add, 4 subtract, 5 a_not_b.
fn mask_combine(p: vec2<i32>, mask_a: vec4<f32>, mask_b: vec4<f32>, operation: i32) -> vec4<f32> {
    let a = mask_a.r;
    let b = mask_b.r;
    var r = a * b;
    switch operation {
        case 1: { r = max(a, b); }
        case 2: { r = min(a, b); }
        case 3: { r = clamp(a + b, 0.0, 1.0); }
        case 4: { r = clamp(a - b, 0.0, 1.0); }
        case 5: { r = a * (1.0 - b); }
        default: {}
    }
    return vec4<f32>(r, 0.0, 0.0, 1.0);
}
