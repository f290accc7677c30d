// DepthLayers: the first two depth layers of a mesh in one geometry pass — a k-buffer with k = 2
// (Bavoil et al. 2007) in place of the two passes of depth peeling (Fischer et al. 2005, §3.1).
// Every fragment is a 64-bit key: window depth in the high word (positive floats order like their
// bits), its octahedron-encoded view-space normal in the low word. Per pixel two slots keep the
// two smallest keys with atomics only: a fragment's key goes into slot 0 by atomic minimum, and
// whichever of it and the slot's previous key is larger goes into slot 1 — every key but the
// overall smallest reaches slot 1 once, so slot 1 ends with the second smallest. Keys are stored
// bit-inverted (with atomic maximum) so that a buffer cleared to zero means "empty".
// One difference from depth peeling: a second fragment at exactly layer 1's depth (coincident
// triangles) becomes layer 2 here, where peeling skips it for the next depth behind; meshes
// from MarchingCubes have none.

struct LayersFrame {
    // Frame width in pixels; the slot is the resolve step's (unused here).
    width: u32,
    slot: u32,
    pad0: u32,
    pad1: u32,
};

@group(0) @binding(1) var<storage, read_write> layers: array<atomic<u64>>;
@group(0) @binding(2) var<uniform> frame: LayersFrame;

// Octahedral encoding of a direction (any length), two 16-bit signed normalised halves.
fn oct_encode(n: vec3<f32>) -> u32 {
    var p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if n.z < 0.0 {
        p = (1.0 - abs(p.yx)) * select(vec2<f32>(-1.0), vec2<f32>(1.0), p >= vec2<f32>(0.0));
    }
    return pack2x16snorm(p);
}

@fragment
fn fs_main(in: VertexOut) {
    let pixel = vec2<u32>(floor(in.clip.xy));
    let slot = (pixel.y * frame.width + pixel.x) * 2u;
    // The octahedral code divides by the L1 norm: no need to normalise first.
    let key = (u64(bitcast<u32>(in.clip.z)) << 32u) | u64(oct_encode(in.view_normal));
    let inverted = ~key;
    let previous = atomicMax(&layers[slot], inverted);
    atomicMax(&layers[slot + 1u], min(previous, inverted));
}
