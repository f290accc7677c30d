//! hatchery's node catalogue. One module per node kind; [`registry`] lists them all.

pub mod annotation_layout;
pub mod annotations;
pub mod camera;
pub mod context;
pub mod curvature;
pub mod curvature_color;
pub mod curvature_flow;
pub mod depth_peel;
pub mod depth_test_mask;
pub mod diffuse_intensity;
pub mod display;
pub mod export;
pub mod fill;
pub mod gbuffer;
pub mod halftone;
pub mod hatch_strokes;
pub mod importance_compositing;
pub mod label_font;
pub mod label_mask;
pub mod label_sources;
pub mod light;
pub mod marching_cubes;
pub mod mask_combine;
pub mod mesh_file;
pub mod mesh_pass;
pub mod mesh_transform;
pub mod mix_by_mask;
pub mod multiply_by_mask;
pub mod object_styles;
pub mod over;
pub mod overlay;
pub mod procedural_volume;
pub mod raycast;
pub mod ridge_valley;
pub mod save_image;
pub mod save_svg;
pub mod screen_pass;
pub mod secondary_geometry;
pub mod select_image;
pub mod selection_render;
mod session;
pub mod shaded_surface;
pub mod shaders;
pub mod silhouette;
pub mod style_set;
pub mod style_transfer_function;
pub mod transfer_function_1d;
pub mod two_level_raycast;
pub mod uniforms;
pub mod value;
pub mod visual_conventions;
pub mod volume_file;
pub mod volume_texture;

pub use context::RenderContext;
pub use session::{Session, SessionError};
pub use value::Value;

/// The context every node executes in.
pub type Ctx = RenderContext;
/// The registry of every node kind.
pub type Registry = hatchery_graph::Registry<Value, Ctx>;

/// Every node kind hatchery has.
pub fn registry() -> Registry {
    let mut r = Registry::default();
    r.register(procedural_volume::ProceduralVolumeNode);
    r.register(volume_file::VolumeFileNode);
    r.register(mesh_file::MeshFileNode);
    r.register(marching_cubes::MarchingCubesNode);
    r.register(label_mask::LabelMaskNode);
    r.register(mesh_transform::MeshTransformNode);
    r.register(camera::CameraNode);
    r.register(light::LightNode);
    r.register(gbuffer::GBufferNode);
    r.register(shaded_surface::ShadedSurfaceNode);
    r.register(depth_peel::DepthPeelNode);
    r.register(diffuse_intensity::DiffuseIntensityNode);
    r.register(secondary_geometry::SecondaryGeometryNode);
    r.register(silhouette::SilhouetteNode);
    r.register(halftone::HalftoneNode);
    r.register(fill::FillNode);
    r.register(mix_by_mask::MixByMaskNode);
    r.register(multiply_by_mask::MultiplyByMaskNode);
    r.register(depth_test_mask::DepthTestMaskNode);
    r.register(mask_combine::MaskCombineNode);
    r.register(over::OverNode);
    r.register(select_image::SelectImageNode);
    r.register(transfer_function_1d::TransferFunction1DNode);
    r.register(style_set::StyleSetNode);
    r.register(style_transfer_function::StyleTransferFunctionNode);
    r.register(raycast::RaycastNode);
    r.register(raycast::IsoSurfaceRaycastNode);
    r.register(label_sources::LabelFileNode);
    r.register(label_sources::LabelsFromThresholdNode);
    r.register(label_sources::LabelsFromMapsNode);
    r.register(object_styles::ObjectStylesNode);
    r.register(two_level_raycast::TwoLevelRaycastNode);
    r.register(importance_compositing::ImportanceCompositingNode);
    r.register(selection_render::SelectionRenderNode);
    r.register(annotations::AnnotationListNode);
    r.register(annotations::AnnotationsFromLabelsNode);
    r.register(annotation_layout::AnnotationLayoutNode);
    r.register(save_svg::SaveSvgNode);
    r.register(curvature::CurvatureNode);
    r.register(curvature_color::CurvatureColorNode);
    r.register(ridge_valley::RidgeValleyNode);
    r.register(hatch_strokes::HatchStrokesNode);
    r.register(curvature_flow::CurvatureFlowNode);
    r.register(overlay::AnnotationOverlayNode);
    r.register(visual_conventions::ArrowNode);
    r.register(visual_conventions::FanNode);
    r.register(visual_conventions::BoundingBoxNode);
    r.register(save_image::SaveImageNode);
    r
}
