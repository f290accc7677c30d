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
    /// (field name, byte offset, byte size, Rust type as written), in declaration order.
    pub fields: Vec<(&'static str, usize, usize, &'static str)>,
}

/// Declares a `#[repr(C)]`, `Pod` uniform block mirroring a WGSL struct of `program`, with a
/// `layout()` that reports its fields for the reflection test. Fields are `f32`, `u32`, `i32`,
/// `[T; 2|3|4]` (vectors), `[[f32; 4]; 4]` (mat4x4) or arrays of those, named as in WGSL; the
/// test compares every field's name, offset, size and type with naga's reflection, so padding
/// WGSL inserts must be an explicit field here (e.g. `pad0: f32`). Named scalar fields
/// (`SilhouetteUniforms`) are the form new blocks take; older blocks still pack scalars into
/// `[f32; 4]` by position (issue 29 item 2).
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
                        $( (
                            stringify!($field),
                            std::mem::offset_of!($name, $field),
                            std::mem::size_of::<$ty>(),
                            stringify!($ty),
                        ), )*
                    ],
                }
            }
        }
    };
}

/// A Rust enum mirrored by WGSL constants: `(program, [(WGSL constant, value)])`, checked by
/// `tests/shaders.rs` against the `const NAME: u32 = value;` declarations of the program.
#[derive(Clone, Debug)]
pub struct GpuEnumLayout {
    /// Shader program (a name of `kinds::programs`) that declares the constants.
    pub program: &'static str,
    /// The Rust enum's name.
    pub rust_enum: &'static str,
    /// (WGSL constant name, value), one per variant.
    pub constants: Vec<(&'static str, u32)>,
}

/// Declares a `#[repr(u32)]` enum whose variants a shader reads as `u32` codes, each variant
/// naming the WGSL `const` that mirrors it (see [`wgsl_constants!`]).
#[macro_export]
macro_rules! gpu_enum {
    (
        $(#[$meta:meta])*
        pub enum $name:ident in $program:literal {
            $( $(#[$vmeta:meta])* $variant:ident = $value:literal as $wgsl:literal ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[repr(u32)]
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum $name {
            $( $(#[$vmeta])* $variant = $value, )*
        }

        $crate::wgsl_constants! { $name in $program { $( $variant = $wgsl ),* } }
    };
}

/// Gives a field-less enum (a parameter choice, a value enum) the codes a shader reads: its
/// discriminants, mirrored by the named WGSL constants of `program`. `code()` is the value a
/// uniform field or table texel carries; `wgsl()` reports the constants for the reflection
/// test, so a code changed on one side only fails a test.
#[macro_export]
macro_rules! wgsl_constants {
    ($name:ident in $program:literal { $( $variant:ident = $wgsl:literal ),* $(,)? }) => {
        impl $name {
            /// The code the shader compares with its constants.
            pub const fn code(self) -> u32 {
                self as u32
            }

            /// The WGSL constants mirroring the variants, for the reflection test.
            pub fn wgsl() -> $crate::uniforms::GpuEnumLayout {
                $crate::uniforms::GpuEnumLayout {
                    program: $program,
                    rust_enum: stringify!($name),
                    constants: vec![ $( ($wgsl, $name::$variant as u32), )* ],
                }
            }
        }
    };
}
