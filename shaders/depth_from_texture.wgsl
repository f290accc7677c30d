// Writes window depths held in an r32float texture into a depth attachment (the compute ray
// caster's G-buffer depth: storage textures cannot be depth formats).

@group(0) @binding(0) var depth_in: texture_2d<f32>;

@fragment
fn fs_main(in: ScreenOut) -> @builtin(frag_depth) f32 {
    return textureLoad(depth_in, pixel_of(in.position), 0).r;
}
