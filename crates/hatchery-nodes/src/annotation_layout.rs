//! `AnnotationLayout`: VolumeShop's annotation layout (the tutorial's §6.4) for one view — the
//! anchors projected with the camera, labels placed outside the convex hull of the visible
//! objects' footprint, crossings and overlaps resolved, the farthest labels left out first
//! (hatchery_annotation::layout does the placement; this node gathers its inputs).

use crate::annotations::{Annotations, Placed};
use crate::camera::Camera;
use crate::{Ctx, Value, export, label_font};
use glam::Vec2;
use hatchery_annotation::{
    Layout, LayoutParams, ProjectedAnchor, box_corners, convex_hull, layout, project_anchors,
    project_footprint,
};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::{Arc, Mutex};

/// Space between a label's text and its box, pixels of the designed figure (each side).
pub const LABEL_PADDING: f32 = 2.0;

/// A label's box for `text` at `font_size` pixels: the text's extent plus `padding` each side.
pub fn label_size(text: &str, font_size: f32, padding: f32) -> Vec2 {
    let [w, h] = label_font::measure(text, font_size);
    Vec2::new(w, h) + 2.0 * padding
}

/// View depth (world units in front of the eye) of window depth `z` at pixel centre `pixel`.
fn view_depth(camera: &Camera, pixel: Vec2, z: f32) -> f32 {
    let ndc = Vec2::new(
        pixel.x / camera.width as f32 * 2.0 - 1.0,
        1.0 - pixel.y / camera.height as f32 * 2.0,
    );
    let p = camera.view_proj().inverse().project_point3(ndc.extend(z));
    -(camera.view * p.extend(1.0)).z
}

/// Anchors behind the G-buffer's surface by more than `tolerance` (world units) are hidden.
fn hide_occluded(
    camera: &Camera,
    projected: &mut [ProjectedAnchor],
    depth: &export::Array,
    tolerance: f32,
) {
    let (h, w) = (depth.shape[0], depth.shape[1]);
    for a in projected.iter_mut().filter(|a| a.visible) {
        let (x, y) = (a.screen.x.floor(), a.screen.y.floor());
        if x < 0.0 || y < 0.0 || x as usize >= w || y as usize >= h {
            continue;
        }
        let surface = depth.data[(y as usize * w + x as usize) * 4];
        if surface >= 1.0 {
            continue; // nothing drawn there
        }
        let centre = Vec2::new(x + 0.5, y + 0.5);
        if view_depth(camera, centre, a.depth) > view_depth(camera, centre, surface) + tolerance {
            a.visible = false;
        }
    }
}

/// Pixel centres of a mask's boundary (value > 0.5 with a neighbour ≤ 0.5): enough for its hull.
fn mask_boundary(mask: &export::Array) -> Vec<Vec2> {
    let (h, w) = (mask.shape[0], mask.shape[1]);
    let inside = |x: usize, y: usize| mask.data[y * w + x] > 0.5;
    let mut points = Vec::new();
    for y in 0..h {
        for x in 0..w {
            if !inside(x, y) {
                continue;
            }
            let edge = x == 0
                || y == 0
                || x + 1 == w
                || y + 1 == h
                || !inside(x - 1, y)
                || !inside(x + 1, y)
                || !inside(x, y - 1)
                || !inside(x, y + 1);
            if edge {
                points.push(Vec2::new(x as f32 + 0.5, y as f32 + 0.5));
            }
        }
    }
    points
}

hatchery_graph::node_params! {
    /// Parameters of `AnnotationLayout`.
    pub struct AnnotationLayoutParams {
        /// label text size, pixels
        pub font_size: f32 = 13.0, range(6.0, 96.0), unit(pixels);
        /// distance of the labels from the hull, pixels
        pub margin: f32 = 10.0, range(0.0, 200.0), unit(pixels);
        /// iterations of the swap/shift loop before labels are left out
        pub max_iterations: u32 = 300, range(1, 10000);
        /// with a gbuffer: an anchor this far (world units) behind the surface still counts as
        /// visible
        pub depth_tolerance: f32 = 5.0, range(0.0, 1.0e6);
        /// start from the previous layout (labels move little between frames)
        pub coherent: bool = true;
    }
}

pub struct AnnotationLayoutNode;

impl Node<Value, Ctx> for AnnotationLayoutNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "AnnotationLayout",
            category: "Annotation",
            doc: "Annotation layout (VolumeShop, the tutorial's §6.4): anchors projected with the \
                  camera; the convex hull of the visible objects' footprint (their boxes, or the \
                  `footprint` mask's pixels) parameterised by arc length; each label placed \
                  outside the hull at the point nearest its anchor, then crossing leader lines \
                  swapped, labels swapped when both get closer, and overlapping ones shifted by \
                  δ (from scratch by 1.5× their overlap, so piles spread fast), until resolved or `max_iterations`; what stays unresolved is left out, \
                  lowest priority and farthest (screen depth) first. Leader opacity falls with \
                  the anchor's depth; anchors hidden behind the `gbuffer` surface get no label. \
                  Starts from this node's previous layout (temporal coherence) when the labels \
                  and frame size are unchanged.",
            inputs: vec![
                PortSpec::input("annotations", PortType::Annotations, "the anchors"),
                PortSpec::input("camera", PortType::Camera, "the view"),
                PortSpec::optional(
                    "gbuffer",
                    PortType::GBuffer,
                    "the rendered surface: anchors behind it are hidden",
                ),
                PortSpec::optional(
                    "footprint",
                    PortType::Mask,
                    "the visible objects' footprint (> 0.5), instead of their boxes",
                ),
            ],
            outputs: vec![PortSpec::output(
                "annotations",
                PortType::Annotations,
                "the anchors with their labels placed",
            )],
            params: AnnotationLayoutParams::specs(),
            frame_dependent: true,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = AnnotationLayoutParams::read(p)?;
        let annotations = inputs.require("annotations")?.annotations("annotations")?;
        let camera = inputs.require("camera")?.camera("camera")?.clone();
        let frame = Vec2::new(camera.width as f32, camera.height as f32);
        let view_proj = camera.view_proj();
        let mut projected = project_anchors(&annotations.anchors, view_proj, frame);
        if let Some(g) = inputs.get("gbuffer") {
            let g = g.gbuffer("gbuffer")?;
            let depth = export::to_array(&Value::GBuffer(g.clone()), &ctx.gpu)
                .map_err(|e| NodeError::at_port("gbuffer", e))?;
            if depth.shape[0] != camera.height as usize || depth.shape[1] != camera.width as usize {
                return Err(NodeError::at_port(
                    "gbuffer",
                    format!(
                        "{}×{} pixels, the camera's frame {}×{}",
                        depth.shape[1], depth.shape[0], camera.width, camera.height
                    ),
                ));
            }
            hide_occluded(&camera, &mut projected, &depth, params.depth_tolerance);
        }
        let hull_points = match inputs.get("footprint") {
            Some(m) => {
                let mask = export::to_array(m, &ctx.gpu)
                    .map_err(|e| NodeError::at_port("footprint", e))?;
                if mask.shape[0] != camera.height as usize || mask.shape[1] != camera.width as usize
                {
                    return Err(NodeError::at_port(
                        "footprint",
                        format!(
                            "{}×{} pixels, the camera's frame {}×{}",
                            mask.shape[1], mask.shape[0], camera.width, camera.height
                        ),
                    ));
                }
                convex_hull(&mask_boundary(&mask))
            }
            None => {
                // The visible objects' boxes (§6.4: the hull of what is shown).
                let mut points = Vec::new();
                for ((a, bounds), projected) in annotations
                    .anchors
                    .iter()
                    .zip(&annotations.bounds)
                    .zip(&projected)
                {
                    if !projected.visible {
                        continue;
                    }
                    match bounds {
                        Some([lo, hi]) => points.extend(box_corners(*lo, *hi)),
                        None => points.push(a.position),
                    }
                }
                convex_hull(&project_footprint(&points, view_proj, frame))
            }
        };
        let font_size = params.font_size;
        // The layout's own lengths in pixels scale with the render as its parameters do.
        let scale = ctx.pixel_scale() as f32;
        let padding = LABEL_PADDING * scale;
        let sizes: Vec<Vec2> = annotations
            .anchors
            .iter()
            .map(|a| label_size(&a.text, font_size, padding))
            .collect();
        let defaults = LayoutParams::default();
        let layout_params = LayoutParams {
            margin: params.margin,
            max_iterations: params.max_iterations.clamp(1, 10000),
            label_gap: defaults.label_gap * scale,
            delta: defaults.delta * scale,
            coherence_pull: defaults.coherence_pull * scale,
            ..defaults
        };
        // The previous layout of this node, for temporal coherence.
        let key = format!(
            "annotation_layout.previous/{}",
            ctx.current_node().unwrap_or("")
        );
        let memory = ctx
            .cached(&key, |_| {
                Ok(Mutex::new(None::<(Vec<String>, Vec2, Layout)>))
            })
            .map_err(|e| NodeError::new(e.to_string()))?;
        let mut memory = memory.lock().unwrap_or_else(|e| e.into_inner());
        // The same labels (texts, in order) in the same frame: start from the last layout.
        let texts: Vec<String> = annotations.anchors.iter().map(|a| a.text.clone()).collect();
        let previous = memory
            .as_ref()
            .filter(|(t, f, _)| params.coherent && *t == texts && *f == frame)
            .map(|(_, _, l)| l);
        let mut placed = layout(
            &projected,
            &sizes,
            &hull_points,
            frame,
            &layout_params,
            previous,
        );
        *memory = Some((texts, frame, placed.clone()));
        // A label the frame cuts is worse than none (a narrow frame around a wide hull).
        let mut cut = Vec::new();
        for label in placed
            .labels
            .iter_mut()
            .filter(|l| l.shown && !l.inside_frame)
        {
            label.shown = false;
            cut.push(annotations.anchors[label.anchor].text.clone());
        }
        if !cut.is_empty() {
            ctx.warn(format!(
                "no room in the frame for the labels {}: left out",
                cut.join(", ")
            ));
        }
        let hull = placed.path.vertices().to_vec();
        let mut out = Annotations::clone(annotations);
        out.placed = Some(Arc::new(Placed {
            layout: placed,
            projected,
            hull,
            width: camera.width,
            height: camera.height,
            font_size,
            padding,
        }));
        Ok(vec![Value::Annotations(Arc::new(out))])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(AnnotationLayoutNode);
}
