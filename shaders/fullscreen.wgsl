// Shared by every image-space pass: one triangle covering the frame, and pixel addressing.
// Prepended to the mask and compositing shaders when they are compiled.

struct ScreenOut {
    @builtin(position) position: vec4<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> ScreenOut {
    // Vertices (-1,-1), (3,-1), (-1,3): a triangle that covers the whole viewport.
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    var out: ScreenOut;
    out.position = vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
    return out;
}

// Integer pixel (x right, y down from the top-left) of a fragment.
fn pixel_of(position: vec4<f32>) -> vec2<i32> {
    return vec2<i32>(floor(position.xy));
}

// Texel of a 2-D texture, coordinates clamped to the image.
fn load_clamped(t: texture_2d<f32>, p: vec2<i32>) -> vec4<f32> {
    let size = vec2<i32>(textureDimensions(t));
    return textureLoad(t, clamp(p, vec2<i32>(0), size - 1), 0);
}

fn load_depth_clamped(t: texture_depth_2d, p: vec2<i32>) -> f32 {
    let size = vec2<i32>(textureDimensions(t));
    return textureLoad(t, clamp(p, vec2<i32>(0), size - 1), 0);
}

// v as an Rgba16Float colour target stores it on lavapipe: rounded toward zero to binary16 —
// what a fused pass does to an image it passes between stages, so that fused and unfused frames
// agree bit for bit there. (Vulkan lets a driver round such writes to nearest or toward zero;
// where it rounds to nearest, a fused image differs by at most one binary16 step per fused edge.
// quantizeToF16 rounds to nearest and costs several times more on lavapipe.) For finite values
// within binary16's range.
fn as_rgba16float(v: vec4<f32>) -> vec4<f32> {
    // Normal binary16 values: 10 mantissa bits kept.
    let normal = bitcast<vec4<f32>>(bitcast<vec4<u32>>(v) & vec4<u32>(0xffffe000u));
    // Below 2^-14 binary16 is subnormal: multiples of 2^-24.
    let tiny = trunc(v * 16777216.0) / 16777216.0;
    return select(normal, tiny, abs(v) < vec4<f32>(6.103515625e-5));
}
