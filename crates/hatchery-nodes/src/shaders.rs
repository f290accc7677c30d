//! Every WGSL shader, embedded at build time. Some are assembled from shared parts
//! (`mesh_common.wgsl` is prepended to the mesh shaders, `fullscreen.wgsl` to the
//! image-space ones, the `ray_*.wgsl` parts to the ray casters): WGSL has no includes.

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
pub const DEPTH_PEEL: &str = shader_file!("depth_peel.wgsl");
pub const SECONDARY_GEOMETRY: &str = shader_file!("secondary_geometry.wgsl");
pub const FULLSCREEN: &str = shader_file!("fullscreen.wgsl");
pub const DIFFUSE_INTENSITY: &str = shader_file!("diffuse_intensity.wgsl");
pub const SILHOUETTE: &str = shader_file!("silhouette.wgsl");
pub const HALFTONE: &str = shader_file!("halftone.wgsl");
pub const FILL: &str = shader_file!("fill.wgsl");
pub const MIX_BY_MASK: &str = shader_file!("mix_by_mask.wgsl");
pub const MULTIPLY_BY_MASK: &str = shader_file!("multiply_by_mask.wgsl");
pub const DEPTH_TEST_MASK: &str = shader_file!("depth_test_mask.wgsl");
pub const MASK_COMBINE: &str = shader_file!("mask_combine.wgsl");
pub const RAY_COMMON: &str = shader_file!("ray_common.wgsl");
pub const RAY_CLASSIFY: &str = shader_file!("ray_classify.wgsl");
pub const RAY_SHADE: &str = shader_file!("ray_shade.wgsl");
pub const RAY_SKIP: &str = shader_file!("ray_skip.wgsl");
pub const RAY_OBJECTS: &str = shader_file!("ray_objects.wgsl");
pub const IMPORTANCE: &str = shader_file!("importance.wgsl");
pub const SELECTION_RENDER: &str = shader_file!("selection_render.wgsl");
pub const CURVATURE_COMMON: &str = shader_file!("curvature_common.wgsl");
pub const CURVATURE: &str = shader_file!("curvature.wgsl");
pub const CURVATURE_CONTOURS: &str = shader_file!("curvature_contours.wgsl");
pub const CURVATURE_COLOR: &str = shader_file!("curvature_color.wgsl");
pub const RIDGE_VALLEY: &str = shader_file!("ridge_valley.wgsl");
pub const RAYCAST: &str = shader_file!("raycast.wgsl");
pub const TWO_LEVEL_RAYCAST: &str = shader_file!("two_level_raycast.wgsl");
pub const DEPTH_FROM_TEXTURE: &str = shader_file!("depth_from_texture.wgsl");
pub const OVER: &str = shader_file!("over.wgsl");
pub const DISPLAY: &str = shader_file!("display.wgsl");
pub const OVERLAY: &str = shader_file!("overlay.wgsl");
pub const CURVATURE_FIELD: &str = shader_file!("curvature_field.wgsl");
pub const HATCH_STROKES: &str = shader_file!("hatch_strokes.wgsl");
pub const CURVATURE_FLOW: &str = shader_file!("curvature_flow.wgsl");
pub const MASK_COPY: &str = shader_file!("mask_copy.wgsl");
pub const CUSTOM_SHADER_VERTEX: &str = shader_file!("custom_shader_vertex.wgsl");
pub const DEPTH_LAYERS: &str = shader_file!("depth_layers.wgsl");
pub const DEPTH_LAYERS_RESOLVE: &str = shader_file!("depth_layers_resolve.wgsl");

/// Compilable shader programs: (name, parts). The name is used in error messages.
pub fn programs() -> Vec<(&'static str, Vec<(&'static str, &'static str)>)> {
    let mesh = |file, source| vec![("mesh_common.wgsl", MESH_COMMON), (file, source)];
    let screen = |file, source| vec![("fullscreen.wgsl", FULLSCREEN), (file, source)];
    // The ray casters share their sampling, classification, shading and skipping parts.
    let ray = |file, source| {
        vec![
            ("fullscreen.wgsl", FULLSCREEN),
            ("ray_common.wgsl", RAY_COMMON),
            ("ray_classify.wgsl", RAY_CLASSIFY),
            ("ray_shade.wgsl", RAY_SHADE),
            ("ray_skip.wgsl", RAY_SKIP),
            (file, source),
        ]
    };
    vec![
        ("gbuffer", mesh("gbuffer.wgsl", GBUFFER)),
        (
            "shaded_surface",
            mesh("shaded_surface.wgsl", SHADED_SURFACE),
        ),
        ("depth_peel", mesh("depth_peel.wgsl", DEPTH_PEEL)),
        ("depth_layers", mesh("depth_layers.wgsl", DEPTH_LAYERS)),
        (
            "depth_layers_resolve",
            screen("depth_layers_resolve.wgsl", DEPTH_LAYERS_RESOLVE),
        ),
        (
            "secondary_geometry",
            mesh("secondary_geometry.wgsl", SECONDARY_GEOMETRY),
        ),
        (
            "diffuse_intensity",
            screen("diffuse_intensity.wgsl", DIFFUSE_INTENSITY),
        ),
        ("silhouette", screen("silhouette.wgsl", SILHOUETTE)),
        ("halftone", screen("halftone.wgsl", HALFTONE)),
        ("fill", screen("fill.wgsl", FILL)),
        ("mix_by_mask", screen("mix_by_mask.wgsl", MIX_BY_MASK)),
        (
            "multiply_by_mask",
            screen("multiply_by_mask.wgsl", MULTIPLY_BY_MASK),
        ),
        (
            "depth_test_mask",
            screen("depth_test_mask.wgsl", DEPTH_TEST_MASK),
        ),
        ("mask_combine", screen("mask_combine.wgsl", MASK_COMBINE)),
        ("raycast", ray("raycast.wgsl", RAYCAST)),
        ("two_level_raycast", {
            let mut parts = ray("ray_objects.wgsl", RAY_OBJECTS);
            parts.push(("two_level_raycast.wgsl", TWO_LEVEL_RAYCAST));
            parts
        }),
        (
            "selection_render",
            ray("selection_render.wgsl", SELECTION_RENDER),
        ),
        (
            "curvature",
            vec![
                ("fullscreen.wgsl", FULLSCREEN),
                ("ray_common.wgsl", RAY_COMMON),
                ("curvature_common.wgsl", CURVATURE_COMMON),
                ("curvature.wgsl", CURVATURE),
            ],
        ),
        (
            "curvature_contours",
            vec![
                ("fullscreen.wgsl", FULLSCREEN),
                ("ray_common.wgsl", RAY_COMMON),
                ("curvature_common.wgsl", CURVATURE_COMMON),
                ("curvature_contours.wgsl", CURVATURE_CONTOURS),
            ],
        ),
        ("importance", {
            let mut parts = ray("ray_objects.wgsl", RAY_OBJECTS);
            parts.push(("importance.wgsl", IMPORTANCE));
            parts
        }),
        (
            "depth_from_texture",
            screen("depth_from_texture.wgsl", DEPTH_FROM_TEXTURE),
        ),
        ("over", screen("over.wgsl", OVER)),
        (
            "curvature_color",
            screen("curvature_color.wgsl", CURVATURE_COLOR),
        ),
        ("ridge_valley", screen("ridge_valley.wgsl", RIDGE_VALLEY)),
        ("display", screen("display.wgsl", DISPLAY)),
        // The vertex stage of every CustomShader (the fragment stage is the user's file).
        (
            "custom_shader_vertex",
            vec![("custom_shader_vertex.wgsl", CUSTOM_SHADER_VERTEX)],
        ),
        // Instanced quads with their own vertex stage (crate::overlay).
        ("overlay", vec![("overlay.wgsl", OVERLAY)]),
        // Compute tracing plus instanced segments (crate::hatch_strokes).
        (
            "hatch_strokes",
            vec![
                ("curvature_field.wgsl", CURVATURE_FIELD),
                ("hatch_strokes.wgsl", HATCH_STROKES),
            ],
        ),
        (
            "curvature_flow",
            vec![
                ("fullscreen.wgsl", FULLSCREEN),
                ("curvature_field.wgsl", CURVATURE_FIELD),
                ("curvature_flow.wgsl", CURVATURE_FLOW),
            ],
        ),
        ("mask_copy", screen("mask_copy.wgsl", MASK_COPY)),
    ]
}

/// The full source of a program.
pub fn source(name: &str) -> Option<String> {
    programs()
        .into_iter()
        .find(|(n, _)| *n == name)
        .map(|(_, parts)| parts.iter().map(|(_, s)| *s).collect())
}
