// The 2-D vector renderer of the overlay nodes (crate::overlay): one instanced quad per
// primitive, coverage computed per fragment in pixels (top-left origin, y down), premultiplied
// output blended over a copy of the image.
//
// Kinds (b.w): 0 segment p0–p1 with half width b.z and round caps; 1 disc at p0 of radius b.z;
// 2 triangle p0 p1 p2 (extra.x: bit i set = edge i, from vertex i to i+1, is anti-aliased);
// 3 text cell: screen pixels [p0, p0 + extra.zw) read atlas texels from extra.xy on, halo
// radius b.z in `halo`'s colour.

struct Overlay {
    // Frame width and height, pixels.
    frame: vec2<f32>,
    pad0: f32,
    pad1: f32,
};

@group(0) @binding(0) var atlas: texture_2d<f32>;
@group(0) @binding(1) var<uniform> overlay: Overlay;

struct Primitive {
    @location(0) a: vec4<f32>,
    @location(1) b: vec4<f32>,
    @location(2) color: vec4<f32>,
    @location(3) extra: vec4<f32>,
    @location(4) halo: vec4<f32>,
    @location(5) clip0: vec4<f32>,
    @location(6) clip1: vec4<f32>,
};

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) @interpolate(flat) a: vec4<f32>,
    @location(1) @interpolate(flat) b: vec4<f32>,
    @location(2) @interpolate(flat) color: vec4<f32>,
    @location(3) @interpolate(flat) extra: vec4<f32>,
    @location(4) @interpolate(flat) halo: vec4<f32>,
    @location(5) @interpolate(flat) clip0: vec4<f32>,
    @location(6) @interpolate(flat) clip1: vec4<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) index: u32, prim: Primitive) -> VertexOut {
    // Corner (u, v) ∈ {0, 1}² of two triangles: (0,0) (1,0) (0,1) (0,1) (1,0) (1,1).
    var corner = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0),
        vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
    );
    let uv = corner[index];
    let kind = u32(prim.b.w + 0.5);
    let p0 = prim.a.xy;
    let p1 = prim.a.zw;
    let p2 = prim.b.xy;
    var pixel: vec2<f32>;
    if (kind == 0u) {
        // An oriented quad around the segment, one pixel wider than its half width and caps.
        let grow = prim.b.z + 1.0;
        let length = distance(p0, p1);
        var along = vec2<f32>(1.0, 0.0);
        if (length > 1e-6) {
            along = (p1 - p0) / length;
        }
        let across = vec2<f32>(-along.y, along.x);
        let start = p0 - along * grow;
        let end = p1 + along * grow;
        pixel = mix(start, end, uv.x) + across * grow * (2.0 * uv.y - 1.0);
    } else if (kind == 1u) {
        let grow = prim.b.z + 1.0;
        pixel = p0 + (2.0 * uv - 1.0) * grow;
    } else if (kind == 2u) {
        let lo = min(min(p0, p1), p2) - 1.0;
        let hi = max(max(p0, p1), p2) + 1.0;
        pixel = mix(lo, hi, uv);
    } else {
        pixel = p0 + uv * prim.extra.zw;
    }
    var out: VertexOut;
    let ndc = vec2<f32>(pixel.x / overlay.frame.x * 2.0 - 1.0, 1.0 - pixel.y / overlay.frame.y * 2.0);
    out.position = vec4<f32>(ndc, 0.0, 1.0);
    out.a = prim.a;
    out.b = prim.b;
    out.color = prim.color;
    out.extra = prim.extra;
    out.halo = prim.halo;
    out.clip0 = prim.clip0;
    out.clip1 = prim.clip1;
    return out;
}

fn segment_distance(p: vec2<f32>, a: vec2<f32>, b: vec2<f32>) -> f32 {
    let ab = b - a;
    let len2 = dot(ab, ab);
    var t = 0.0;
    if (len2 > 1e-12) {
        t = clamp(dot(p - a, ab) / len2, 0.0, 1.0);
    }
    return distance(p, a + t * ab);
}

// Signed distance of p from the edge a → b, positive on the side of `inside`.
fn edge_distance(p: vec2<f32>, a: vec2<f32>, b: vec2<f32>, inside: vec2<f32>) -> f32 {
    let d = b - a;
    let len = max(length(d), 1e-6);
    var n = vec2<f32>(-d.y, d.x) / len;
    if (dot(inside - a, n) < 0.0) {
        n = -n;
    }
    return dot(p - a, n);
}

fn inside_rect(p: vec2<f32>, r: vec4<f32>) -> bool {
    return p.x >= r.x && p.y >= r.y && p.x <= r.z && p.y <= r.w;
}

fn atlas_coverage(texel: vec2<i32>, lo: vec2<i32>, hi: vec2<i32>) -> f32 {
    if (any(texel < lo) || any(texel >= hi)) {
        return 0.0;
    }
    return textureLoad(atlas, texel, 0).r;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    // Pixel centre, pixels from the top-left corner.
    let p = in.position.xy;
    if (inside_rect(p, in.clip0) || inside_rect(p, in.clip1)) {
        discard;
    }
    let kind = u32(in.b.w + 0.5);
    let p0 = in.a.xy;
    let p1 = in.a.zw;
    let p2 = in.b.xy;
    if (kind == 0u) {
        // Lines thinner than a pixel are drawn one pixel wide at proportionally lower alpha.
        let half_width = max(in.b.z, 0.5);
        let thin = min(in.b.z * 2.0, 1.0);
        let coverage = clamp(half_width + 0.5 - segment_distance(p, p0, p1), 0.0, 1.0) * thin;
        return in.color * coverage;
    }
    if (kind == 1u) {
        let coverage = clamp(in.b.z + 0.5 - distance(p, p0), 0.0, 1.0);
        return in.color * coverage;
    }
    if (kind == 2u) {
        let centre = (p0 + p1 + p2) / 3.0;
        let d = vec3<f32>(
            edge_distance(p, p0, p1, centre),
            edge_distance(p, p1, p2, centre),
            edge_distance(p, p2, p0, centre),
        );
        let mask = u32(in.extra.x + 0.5);
        var coverage = 1.0;
        for (var i = 0u; i < 3u; i++) {
            if ((mask & (1u << i)) != 0u) {
                coverage = min(coverage, clamp(d[i] + 0.5, 0.0, 1.0));
            } else if (d[i] < 0.0) {
                coverage = 0.0;
            }
        }
        return in.color * coverage;
    }
    // Text: the cell maps screen pixels one to one onto atlas texels.
    let cell = vec2<i32>(floor(p - p0));
    let lo = vec2<i32>(in.extra.xy);
    let hi = lo + vec2<i32>(in.extra.zw);
    let texel = lo + cell;
    let ink = atlas_coverage(texel, lo, hi);
    // Halo: the glyphs grown by a disc of radius r. A texel q of coverage c > 0 puts the glyph
    // outline about |q − p| + 0.5 − c from this pixel, so the halo's coverage here is
    // clamp(r + 0.5 − that, 0, 1) = clamp(r + c − |q − p|, 0, 1), the largest over q. Thin,
    // faint strokes (Ubuntu Light) so still get a solid halo, soft over its last pixel.
    let r = in.b.z;
    var halo = 0.0;
    if (r > 0.0) {
        let reach = i32(ceil(r + 1.0));
        for (var dy = -reach; dy <= reach; dy++) {
            for (var dx = -reach; dx <= reach; dx++) {
                let c = atlas_coverage(texel + vec2<i32>(dx, dy), lo, hi);
                if (c > 0.0) {
                    let d = length(vec2<f32>(f32(dx), f32(dy)));
                    halo = max(halo, clamp(r + c - d, 0.0, 1.0));
                }
            }
        }
    }
    let text = in.color * ink;
    return text + (1.0 - text.a) * in.halo * halo;
}
