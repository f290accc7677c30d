// A frame filled with one colour (premultiplied).

struct Fill {
    color: vec4<f32>,
};

@group(0) @binding(0) var<uniform> fill: Fill;

@fragment
fn fs_main(in: ScreenOut) -> @location(0) vec4<f32> {
    return vec4<f32>(fill.color.rgb * fill.color.a, fill.color.a);
}
