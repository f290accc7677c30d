//! Typed bind groups (issue 29): a struct per bind group of a program, one field per binding,
//! named as the WGSL variable and numbered by declaration order, so a pass fills bindings by
//! name (`RayBindings { volume: Some(&view), .. }`) instead of by number. `tests/shaders.rs`
//! checks every declared group against naga's reflection of its program: the same names at the
//! same binding numbers, and no binding of the group left undeclared.
//!
//! The ray casters' convention: group 0 is shaders/ray_common.wgsl's shared bindings
//! ([`crate::raycast::RayBindings`]); group 1 holds the program's own, numbered from 0 (the
//! casters of segmented volumes start it with ray_objects.wgsl's object tables,
//! [`crate::raycast::objects::ObjectBindings`], and number their own after them); group 2 the
//! compute kernel's outputs.

/// The layout a bind-group struct declares, for the reflection test.
#[derive(Clone, Debug)]
pub struct BindingLayout {
    /// Shader program (a name of `kinds::programs`) whose variables the struct binds.
    pub program: &'static str,
    /// The Rust struct's name.
    pub rust_struct: &'static str,
    pub group: u32,
    /// Binding number of the first field; the others follow in declaration order.
    pub first: u32,
    /// Field (= WGSL variable) names in declaration order.
    pub names: Vec<&'static str>,
}

/// A resource a binding takes: a buffer (bound whole), a texture view or a sampler.
pub trait Resource {
    fn resource(&self) -> wgpu::BindingResource<'_>;
}

impl Resource for wgpu::Buffer {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        self.as_entire_binding()
    }
}

impl Resource for wgpu::TextureView {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::TextureView(self)
    }
}

impl Resource for wgpu::Sampler {
    fn resource(&self) -> wgpu::BindingResource<'_> {
        wgpu::BindingResource::Sampler(self)
    }
}

/// Declares a bind group of `program`: a struct of optional references, one per binding
/// (`Buffer`, `TextureView` or `Sampler`), numbered from `first` in declaration order.
/// `entries()` lists the bindings that are set: a pass sets those its entry point reads (an
/// auto-derived layout holds only those), and one it forgets is a validation error that the
/// node reports. `layout()` is for the reflection test.
#[macro_export]
macro_rules! bind_group {
    (
        $(#[$meta:meta])*
        pub struct $name:ident in $program:literal, group $group:literal from $first:literal {
            $( $(#[$fmeta:meta])* pub $field:ident: $kind:ident ),* $(,)?
        }
    ) => {
        $(#[$meta])*
        #[derive(Clone, Copy, Default)]
        pub struct $name<'a> {
            $( $(#[$fmeta])* pub $field: Option<&'a wgpu::$kind>, )*
        }

        impl<'a> $name<'a> {
            /// The bind group's index.
            pub const GROUP: u32 = $group;

            /// The entries of the bindings that are set.
            #[allow(unused_assignments)]
            pub fn entries(&self) -> Vec<wgpu::BindGroupEntry<'a>> {
                let mut entries = Vec::new();
                let mut binding: u32 = $first;
                $(
                    if let Some(r) = self.$field {
                        entries.push(wgpu::BindGroupEntry {
                            binding,
                            resource: $crate::bindings::Resource::resource(r),
                        });
                    }
                    binding += 1;
                )*
                entries
            }

            /// The declared layout, for the reflection test.
            pub fn layout() -> $crate::bindings::BindingLayout {
                $crate::bindings::BindingLayout {
                    program: $program,
                    rust_struct: stringify!($name),
                    group: $group,
                    first: $first,
                    names: vec![ $( stringify!($field), )* ],
                }
            }
        }
    };
}

/// Bind groups 0..groups.len() of `layout_of` (a pipeline's auto-derived layouts) from
/// `groups`' entries; a group the entry point does not read gets an empty layout and an empty
/// group. Errors (a binding the entry point reads but `groups` lacks, or the reverse) come back
/// as messages naming `label`.
pub fn bind_groups(
    gpu: &hatchery_gpu::GpuContext,
    label: &str,
    layout_of: impl Fn(u32) -> wgpu::BindGroupLayout,
    groups: &[Vec<wgpu::BindGroupEntry>],
) -> Result<Vec<wgpu::BindGroup>, hatchery_gpu::GpuError> {
    groups
        .iter()
        .enumerate()
        .map(|(i, entries)| {
            let layout = layout_of(i as u32);
            gpu.checked(&format!("{label} bind group {i}"), |device| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(label),
                    layout: &layout,
                    entries,
                })
            })
        })
        .collect()
}
