//! Typed uniform blocks: each `#[repr(C)]` struct mirrors one WGSL struct field by field, and
//! `tests/shaders.rs` checks every field (of [`crate::kinds::uniform_blocks`])'s offset and size, and the struct's size, against
//! naga's reflection of the shader (so a field added on one side only fails a test instead of
//! shifting every value after it).

/// The layout of a Rust uniform block, to compare with its WGSL struct.
#[derive(Clone, Debug)]
pub struct UniformLayout {
    /// Shader program (a name of `kinds::programs`) whose `var<uniform>` uses the struct.
    pub program: &'static str,
    /// The WGSL struct's name.
    pub wgsl_struct: &'static str,
    /// `size_of` the Rust struct, bytes.
    pub size: usize,
    /// (field name, byte offset, byte size), in declaration order.
    pub fields: Vec<(&'static str, usize, usize)>,
}

/// Declares a `#[repr(C)]`, `Pod` uniform block mirroring a WGSL struct of `program`, with a
/// `layout()` that reports its fields for the reflection test. Fields are `f32`, `[f32; 4]`
/// (vec4) or `[[f32; 4]; 4]` (mat4x4), so Rust and WGSL agree on alignment without padding.
#[macro_export]
macro_rules! uniform_block {
    (
        $(#[$meta:meta])*
        pub struct $name:ident in $program:literal as $wgsl:literal {
            $( $(#[$field_meta:meta])* pub $field:ident : $ty:ty ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[repr(C)]
        #[derive(Clone, Copy, Debug, Default, bytemuck::Pod, bytemuck::Zeroable)]
        pub struct $name {
            $( $(#[$field_meta])* pub $field: $ty, )*
        }

        impl $name {
            /// The block's layout, for the WGSL reflection test.
            pub fn layout() -> $crate::uniforms::UniformLayout {
                $crate::uniforms::UniformLayout {
                    program: $program,
                    wgsl_struct: $wgsl,
                    size: std::mem::size_of::<$name>(),
                    fields: vec![
                        $( (stringify!($field), std::mem::offset_of!($name, $field), std::mem::size_of::<$ty>()), )*
                    ],
                }
            }
        }
    };
}
