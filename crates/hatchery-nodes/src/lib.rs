//! hatchery's node catalogue. One module per node kind (or per family of kinds); each declares
//! its kinds, shader programs and uniform blocks in its `declare` ([`kinds`]), and
//! [`declaring_modules!`] below lists it once. docs/contributing.md has a worked example.
#![forbid(unsafe_code)]

pub mod annotations;
pub mod bindings;
pub mod brick_pool;
pub mod context;
pub mod export;
pub mod framing;
pub mod fused_pass;
pub mod graph_inputs;
pub mod kernel;
pub mod kinds;
pub mod label_font;
pub mod label_sources;
pub mod memory_inputs;
pub mod mesh_pass;
pub mod progress;
pub mod reconstruction;
pub mod relative;
pub mod screen_pass;
mod session;
pub mod shaders;
pub mod stage;
pub mod uniforms;
pub mod value;
pub mod visual_conventions;
pub mod volume_texture;

/// Declares the modules that declare node kinds, shader programs or uniform blocks (each has a
/// `pub fn declare(k: &mut kinds::Kinds)`), and lists their `declare`s for [`kinds::Kinds::all`].
macro_rules! declaring_modules {
    ($($module:ident),* $(,)?) => {
        $(pub mod $module;)*
        /// Every declaring module's `declare`.
        pub(crate) const DECLARE: &[fn(&mut kinds::Kinds)] = &[$($module::declare),*];
    };
}

// Adding a node kind: its module, and its name here (alphabetical).
declaring_modules! {
    annotation_layout,
    annotation_list,
    annotation_overlay,
    annotations_from_labels,
    arrow,
    bounding_box,
    camera,
    curvature,
    curvature_color,
    curvature_contours,
    curvature_flow,
    custom_shader,
    depth_layers,
    depth_peel,
    depth_test_mask,
    diffuse_intensity,
    display,
    distance_to_object,
    exploded_view,
    fan,
    fill,
    gbuffer,
    halftone,
    hatch_strokes,
    importance_compositing,
    label_file,
    label_mask,
    labels_from_maps,
    labels_from_threshold,
    light,
    marching_cubes,
    mask_combine,
    mesh_file,
    mesh_transform,
    mix_by_mask,
    multiply_by_mask,
    object_styles,
    over,
    overlay,
    paint_labels,
    procedural_vector_field,
    procedural_volume,
    raycast,
    ridge_valley,
    save_image,
    save_svg,
    schlieren,
    secondary_geometry,
    select_image,
    selection_render,
    shaded_surface,
    silhouette,
    stipple,
    style_set,
    style_transfer_function,
    transfer_function_1d,
    transfer_function_2d,
    two_level_raycast,
    vector_field,
    vector_operator,
    volume_file,
}

pub use context::RenderContext;
pub use session::{Session, SessionError, parse_param};
pub use value::Value;

/// The context every node executes in.
pub type Ctx = RenderContext;
/// The registry of every node kind.
pub type Registry = hatchery_graph::Registry<Value, Ctx>;

/// Every node kind hatchery has.
pub fn registry() -> Registry {
    let mut r = kinds::Kinds::all().registry;
    r.set_fuser(fused_pass::ImageFuser);
    r
}
