//! Every WGSL shader, embedded at build time. Some are assembled from shared parts
//! (`mesh_common.wgsl` is prepended to the mesh shaders): WGSL has no includes.

macro_rules! shader_file {
    ($name:literal) => {
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../shaders/",
            $name
        ))
    };
}

pub const MESH_COMMON: &str = shader_file!("mesh_common.wgsl");
pub const GBUFFER: &str = shader_file!("gbuffer.wgsl");
pub const SHADED_SURFACE: &str = shader_file!("shaded_surface.wgsl");

/// Compilable shader programs: (name, parts). The name is used in error messages.
pub fn programs() -> Vec<(&'static str, Vec<(&'static str, &'static str)>)> {
    vec![
        (
            "gbuffer",
            vec![("mesh_common.wgsl", MESH_COMMON), ("gbuffer.wgsl", GBUFFER)],
        ),
        (
            "shaded_surface",
            vec![
                ("mesh_common.wgsl", MESH_COMMON),
                ("shaded_surface.wgsl", SHADED_SURFACE),
            ],
        ),
    ]
}

/// The full source of a program.
pub fn source(name: &str) -> Option<String> {
    programs()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, parts)| parts.iter().map(|(_, s)| *s).collect())
}
