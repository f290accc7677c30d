//! The WGSL parts shared by several programs. Each module declares its
//! own programs (`declare`; the list is [`crate::kinds::programs`]) from its own shader files and these shared
//! parts: `mesh_common.wgsl` is prepended to the mesh shaders, `fullscreen.wgsl` to the
//! image-space ones, the `ray_*.wgsl` parts to the ray casters (WGSL has no includes).

/// A file of `shaders/`, embedded at build time.
macro_rules! shader_file {
    ($name:literal) => {
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shaders/",
            $name
        ))
    };
}
pub(crate) use shader_file;

/// A program part: the file of `shaders/` and its text, embedded at build time.
macro_rules! part {
    ($name:literal) => {
        ($name, $crate::shaders::shader_file!($name))
    };
}
pub(crate) use part;

pub const MESH_COMMON: &str = shader_file!("mesh_common.wgsl");
pub const FULLSCREEN: &str = shader_file!("fullscreen.wgsl");
pub const RAY_COMMON: &str = shader_file!("ray_common.wgsl");
pub const RAY_CLASSIFY: &str = shader_file!("ray_classify.wgsl");
pub const RAY_SHADE: &str = shader_file!("ray_shade.wgsl");
pub const RAY_SKIP: &str = shader_file!("ray_skip.wgsl");
pub const RAY_OBJECTS: &str = shader_file!("ray_objects.wgsl");
pub const CURVATURE_COMMON: &str = shader_file!("curvature_common.wgsl");
pub const CURVATURE_FIELD: &str = shader_file!("curvature_field.wgsl");

/// A program part: (file name, WGSL text).
pub type Part = (&'static str, &'static str);
type Parts = Vec<Part>;

/// A mesh program: the shared camera block and vertex layout, then `own`.
pub fn mesh(own: Part) -> Parts {
    vec![("mesh_common.wgsl", MESH_COMMON), own]
}

/// An image-space program: the full-screen triangle and texel helpers, then `own`.
pub fn screen(own: Part) -> Parts {
    vec![("fullscreen.wgsl", FULLSCREEN), own]
}

/// A ray caster: the shared sampling, classification, shading and skipping parts, then `own`.
pub fn ray(own: Part) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("ray_classify.wgsl", RAY_CLASSIFY),
        ("ray_shade.wgsl", RAY_SHADE),
        ("ray_skip.wgsl", RAY_SKIP),
        own,
    ]
}

/// A ray caster of segmented volumes: [`ray`]'s parts, the object tables, then `own`.
pub fn ray_objects(own: Part) -> Parts {
    let mut parts = ray(("ray_objects.wgsl", RAY_OBJECTS));
    parts.push(own);
    parts
}

/// A curvature pass: primary rays and the curvature helpers, then `own`.
pub fn curvature(own: Part) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("curvature_common.wgsl", CURVATURE_COMMON),
        own,
    ]
}
