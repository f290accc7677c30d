// Porter–Duff "over" of premultiplied colours: front + (1 − front.a) · back.
// A stage of a fused image-space pass (crates/hatchery-nodes/src/fused_pass/).

fn over(p: vec2<i32>, front: vec4<f32>, back: vec4<f32>) -> vec4<f32> {
    return front + (1.0 - front.a) * back;
}
