//! `AnnotationOverlay`: laid-out labels, leader lines and anchor dots drawn over a picture.

use crate::overlay::Canvas;
use crate::overlay::MAX_HALO;
use crate::overlay::pixels;
use crate::annotations::Annotations;
use crate::label_font;
use crate::{Ctx, Value};
use glam::Vec2;
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::sync::Arc;

hatchery_graph::node_params! {
    /// Parameters of `AnnotationOverlay`.
    pub struct AnnotationOverlayParams {
        /// label text colour
        pub text_color: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// colour of the halo around the text (alpha 0: none)
        pub halo_color: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
        /// halo width around the glyphs, pixels
        pub halo_width: f32 = 2.0, range(0.0, MAX_HALO as f64), unit(pixels);
        /// leader line and anchor dot colour (alpha times the label's opacity)
        pub leader_color: [f32; 4] = [0.2, 0.2, 0.2, 1.0];
        /// leader line width, pixels
        pub leader_width: f32 = 1.0, range(0.0, 16.0), unit(pixels);
        /// radius of the dot at the anchor, pixels (0: none)
        pub dot_radius: f32 = 2.5, range(0.0, 32.0), unit(pixels);
    }
}

pub struct AnnotationOverlayNode;

impl Node<Value, Ctx> for AnnotationOverlayNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "AnnotationOverlay",
            category: "Annotation",
            doc: "Draws laid-out annotations over an image (VolumeShop §6.4): for every shown \
                  label its leader line from the anchor to the label's attachment point and a \
                  dot at the anchor, both at the label's depth opacity, then its text (at the \
                  layout's font size) over a halo. Anti-aliased on the GPU; pixels, top-left \
                  origin, y down.",
            inputs: vec![
                PortSpec::input("image", PortType::Image, "the picture to annotate"),
                PortSpec::input(
                    "annotations",
                    PortType::Annotations,
                    "annotations laid out by AnnotationLayout for this image's size",
                ),
            ],
            outputs: vec![PortSpec::output(
                "image",
                PortType::Image,
                "the picture with the labels",
            )],
            params: AnnotationOverlayParams::specs(),
            frame_dependent: false,
            sink: false,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let params = AnnotationOverlayParams::read(p)?;
        let image = inputs.require("image")?.image("image")?.clone();
        let annotations: Arc<Annotations> = inputs
            .require("annotations")?
            .annotations("annotations")?
            .clone();
        let placed = annotations.placed("annotations")?;
        let (width, height) = (image.texture.width(), image.texture.height());
        if (placed.width, placed.height) != (width, height) {
            return Err(NodeError::at_port(
                "annotations",
                format!(
                    "laid out for {}×{} pixels, the image is {width}×{height}",
                    placed.width, placed.height
                ),
            ));
        }
        let (halo_width, leader_width, dot_radius) = (
            pixels("halo_width", params.halo_width)?,
            pixels("leader_width", params.leader_width)?,
            pixels("dot_radius", params.dot_radius)?,
        );
        let leader_color = params.leader_color;
        let with_opacity = |o: f32| {
            let mut c = leader_color;
            c[3] *= o.clamp(0.0, 1.0);
            c
        };
        let mut canvas = Canvas::new(width, height);
        let shown: Vec<_> = placed.layout.labels.iter().filter(|l| l.shown).collect();
        // Leaders and dots first, so no leader runs over another label's text.
        for label in &shown {
            let [anchor, attachment] = label.leader;
            canvas.line(
                anchor,
                attachment,
                leader_width,
                with_opacity(label.opacity),
            );
            canvas.disc(anchor, dot_radius, with_opacity(label.opacity));
        }
        let ascent = label_font::ascent(placed.font_size);
        for label in &shown {
            let anchor = annotations.anchors.get(label.anchor).ok_or_else(|| {
                NodeError::at_port(
                    "annotations",
                    format!(
                        "a label refers to anchor {}, there are {}",
                        label.anchor,
                        annotations.anchors.len()
                    ),
                )
            })?;
            let origin = label.rect.min + Vec2::new(placed.padding, placed.padding + ascent);
            canvas.text(
                &anchor.text,
                placed.font_size,
                origin,
                params.text_color,
                params.halo_color,
                halo_width,
            );
        }
        Ok(vec![canvas.draw_over(ctx, &image, "image")?])
    }
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(AnnotationOverlayNode);
}
