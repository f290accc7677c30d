//! Annotations: labelled 3-D anchors and, once laid out, where their labels go (made by
//! AnnotationList and AnnotationsFromLabels, laid out by AnnotationLayout).

use glam::Vec3;
use hatchery_annotation::{Anchor, Layout, ProjectedAnchor};
use hatchery_graph::NodeError;
use std::sync::Arc;

/// Anchors and, once laid out, where their labels go.
#[derive(Clone)]
pub struct Annotations {
    pub anchors: Vec<Anchor>,
    /// Per anchor, the world-space box of its object (part of the silhouette hull's footprint);
    /// `None`: the anchor point alone.
    pub bounds: Vec<Option<[Vec3; 2]>>,
    /// Set by `AnnotationLayout`.
    pub placed: Option<Arc<Placed>>,
}

/// A layout of the anchors' labels for one view.
pub struct Placed {
    pub layout: Layout,
    /// The anchors in pixels (top-left origin, y down) and window depth.
    pub projected: Vec<ProjectedAnchor>,
    /// The silhouette hull the labels were placed around (pixels).
    pub hull: Vec<glam::Vec2>,
    pub width: u32,
    pub height: u32,
    /// Label text size, pixels.
    pub font_size: f32,
    /// Space between a label's text and its box, pixels (each side).
    pub padding: f32,
}

impl Annotations {
    /// The layout, or an error naming `port` when the annotations were not laid out.
    pub fn placed(&self, port: &str) -> Result<&Placed, NodeError> {
        self.placed.as_deref().ok_or_else(|| {
            NodeError::at_port(
                port,
                "these annotations are not laid out: pass them through AnnotationLayout first",
            )
        })
    }
}
