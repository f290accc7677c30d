// DepthLayers, second step: one slot of the k-buffer (shaders/depth_layers.wgsl) written out as a
// G-buffer layer — its depth as the fragment depth, its decoded normal with coverage 1. Empty
// pixels are discarded, so they keep the cleared depth 1 and normal 0, as in a GBuffer pass.

struct ResolveFrame {
    // Frame width in pixels; the slot resolved (0: nearest layer, 1: the next).
    width: u32,
    slot: u32,
    pad0: u32,
    pad1: u32,
};

// The 64-bit keys as pairs of 32-bit words (little-endian: low word first).
@group(0) @binding(0) var<storage, read> layers: array<u32>;
@group(0) @binding(1) var<uniform> resolve: ResolveFrame;

struct LayerOut {
    @builtin(frag_depth) depth: f32,
    @location(0) normal: vec4<f32>,
};

fn oct_decode(packed: u32) -> vec3<f32> {
    let p = unpack2x16snorm(packed);
    var n = vec3<f32>(p, 1.0 - abs(p.x) - abs(p.y));
    if n.z < 0.0 {
        let xy = (1.0 - abs(n.yx)) * select(vec2<f32>(-1.0), vec2<f32>(1.0), n.xy >= vec2<f32>(0.0));
        n = vec3<f32>(xy, n.z);
    }
    return normalize(n);
}

@fragment
fn fs_main(in: ScreenOut) -> LayerOut {
    let pixel = vec2<u32>(pixel_of(in.position));
    let word = ((pixel.y * resolve.width + pixel.x) * 2u + resolve.slot) * 2u;
    let low = ~layers[word];
    let high = ~layers[word + 1u];
    if layers[word] == 0u && layers[word + 1u] == 0u {
        discard;
    }
    var out: LayerOut;
    out.depth = bitcast<f32>(high);
    out.normal = vec4<f32>(oct_decode(low), 1.0);
    return out;
}
