// Pictures of values for screens (the editor's viewport and its pin thumbnails): a texture of any
// size scaled to the output with a box filter, images composited over a checkerboard so that
// transparency shows, masks as grey, G-buffer normals as colours. The output is opaque
// Rgba8Unorm holding display (sRGB-encoded) values, which is what egui draws textures as.

struct Display {
    // What the texture holds (a SHOW_* constant).
    mode: u32,
    // Side of a checkerboard square, output pixels.
    checker: f32,
    out_width: f32,
    out_height: f32,
};

// Display.mode (hatchery_nodes::display::Shows): a premultiplied image, a mask (grey), normals
// (n·0.5 + 0.5, w = coverage).
const SHOW_IMAGE: u32 = 0u;
const SHOW_MASK: u32 = 1u;
const SHOW_NORMALS: u32 = 2u;

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var<uniform> display: Display;

// A source texel as premultiplied RGBA.
fn as_premultiplied(t: vec4<f32>) -> vec4<f32> {
    if display.mode == SHOW_IMAGE {
        return t;
    }
    if display.mode == SHOW_MASK {
        let g = clamp(t.r, 0.0, 1.0);
        return vec4<f32>(g, g, g, 1.0);
    }
    let a = clamp(t.w, 0.0, 1.0);
    return vec4<f32>((t.xyz * 0.5 + 0.5) * a, a);
}

// Light and dark grey squares, as image editors show transparency.
fn checkerboard(p: vec2<i32>) -> vec3<f32> {
    let cell = vec2<i32>(floor(vec2<f32>(p) / max(display.checker, 1.0)));
    if ((cell.x + cell.y) & 1) == 0 {
        return vec3<f32>(0.9);
    }
    return vec3<f32>(0.75);
}

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    let p = pixel_of(in.position);
    let source_size = vec2<f32>(textureDimensions(source));
    let scale = source_size / vec2<f32>(display.out_width, display.out_height);
    // The source rectangle under this output pixel, averaged over at most 4×4 texels.
    let lo = vec2<f32>(p) * scale;
    let taps = clamp(vec2<i32>(ceil(scale)), vec2<i32>(1), vec2<i32>(4));
    let step = scale / vec2<f32>(taps);
    var sum = vec4<f32>(0.0);
    for (var j = 0; j < taps.y; j++) {
        for (var i = 0; i < taps.x; i++) {
            let at = lo + (vec2<f32>(f32(i), f32(j)) + 0.5) * step;
            sum += as_premultiplied(load_clamped(source, vec2<i32>(floor(at))));
        }
    }
    let c = sum / f32(taps.x * taps.y);
    let rgb = clamp(c.rgb, vec3<f32>(0.0), vec3<f32>(1.0));
    return vec4<f32>(rgb + (1.0 - clamp(c.a, 0.0, 1.0)) * checkerboard(p), 1.0);
}
