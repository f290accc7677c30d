//! The WGSL parts shared by several programs, and the program list. Each module declares its
//! own programs (`declare`, see [`crate::kinds`]) from its own shader files and these shared
//! parts: `mesh_common.wgsl` is prepended to the mesh shaders, `fullscreen.wgsl` to the
//! image-space ones, the `ray_*.wgsl` parts to the ray casters (WGSL has no includes).

use crate::kinds::{Kinds, Program};
use std::sync::OnceLock;

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

pub const MESH_COMMON: &str = shader_file!("mesh_common.wgsl");
pub const FULLSCREEN: &str = shader_file!("fullscreen.wgsl");
pub const RAY_COMMON: &str = shader_file!("ray_common.wgsl");
pub const RAY_CLASSIFY: &str = shader_file!("ray_classify.wgsl");
pub const RAY_SHADE: &str = shader_file!("ray_shade.wgsl");
pub const RAY_SKIP: &str = shader_file!("ray_skip.wgsl");
pub const RAY_OBJECTS: &str = shader_file!("ray_objects.wgsl");
pub const CURVATURE_COMMON: &str = shader_file!("curvature_common.wgsl");
pub const CURVATURE_FIELD: &str = shader_file!("curvature_field.wgsl");

type Parts = Vec<(&'static str, &'static str)>;

/// A mesh program: the shared camera block and vertex layout, then `file`.
pub fn mesh(file: &'static str, source: &'static str) -> Parts {
    vec![("mesh_common.wgsl", MESH_COMMON), (file, source)]
}

/// An image-space program: the full-screen triangle and texel helpers, then `file`.
pub fn screen(file: &'static str, source: &'static str) -> Parts {
    vec![("fullscreen.wgsl", FULLSCREEN), (file, source)]
}

/// A ray caster: the shared sampling, classification, shading and skipping parts, then `file`.
pub fn ray(file: &'static str, source: &'static str) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("ray_classify.wgsl", RAY_CLASSIFY),
        ("ray_shade.wgsl", RAY_SHADE),
        ("ray_skip.wgsl", RAY_SKIP),
        (file, source),
    ]
}

/// A ray caster of segmented volumes: [`ray`]'s parts, the object tables, then `file`.
pub fn ray_objects(file: &'static str, source: &'static str) -> Parts {
    let mut parts = ray("ray_objects.wgsl", RAY_OBJECTS);
    parts.push((file, source));
    parts
}

/// A curvature pass: primary rays and the curvature helpers, then `file`.
pub fn curvature(file: &'static str, source: &'static str) -> Parts {
    vec![
        ("fullscreen.wgsl", FULLSCREEN),
        ("ray_common.wgsl", RAY_COMMON),
        ("curvature_common.wgsl", CURVATURE_COMMON),
        (file, source),
    ]
}

/// Every compilable program, (name, parts), as the modules declare them. The name is used in
/// error messages.
pub fn programs() -> &'static [Program] {
    static PROGRAMS: OnceLock<Vec<Program>> = OnceLock::new();
    PROGRAMS.get_or_init(|| Kinds::all().programs)
}

/// The full source of a program.
pub fn source(name: &str) -> Option<String> {
    programs()
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, parts)| parts.iter().map(|(_, s)| *s).collect())
}
