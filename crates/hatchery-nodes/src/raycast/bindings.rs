//! The ray casters' typed bind groups (see [`crate::bindings`]): group 0 of every ray caster,
//! Raycast's own group 1, and group 2, the compute kernel's outputs.

crate::bind_group! {
    /// Group 0 of every ray caster: shaders/ray_common.wgsl's uniform block, the volume and its
    /// tables (what each holds is said there).
    pub struct RayBindings in "raycast", group 0 from 0 {
        pub ray: Buffer,
        pub volume: TextureView,
        pub linear_clamp: Sampler,
        pub tf_table: TextureView,
        pub lighting_table: TextureView,
        pub styles: TextureView,
        pub style_index: TextureView,
        pub label_volume: TextureView,
        pub label_rows: TextureView,
        pub bricks: TextureView,
        pub visibility: TextureView,
        pub page_table: TextureView,
    }
}

crate::bind_group! {
    /// Raycast's own group: the embedded strokes and the Table 1 enhancements with their
    /// second and vector fields (shaders/raycast.wgsl).
    pub struct StrokeBindings in "raycast", group 1 from 0 {
        pub stroke_depth: TextureView,
        pub stroke_mask: TextureView,
        pub strokes: Buffer,
        pub enhancement: Buffer,
        pub second_field: TextureView,
        pub vector_field: TextureView,
    }
}

crate::bind_group! {
    /// The compute kernel's outputs (`cs_main` of shaders/ray_common.wgsl).
    pub struct RayOutputs in "raycast", group 2 from 0 {
        pub out_color: TextureView,
        pub out_normal: TextureView,
        pub out_depth: TextureView,
    }
}
