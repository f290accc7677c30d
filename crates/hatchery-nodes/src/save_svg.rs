//! `SaveSvg`: a figure as vector graphics for illustrators' editors (Inkscape, Illustrator) —
//! the picture as an embedded PNG, lines traced from masks (marching squares and
//! Ramer–Douglas–Peucker, hatchery_annotation::trace_mask), leader lines and labels as text,
//! each group an Inkscape layer.

use crate::annotation_layout::LABEL_PADDING;
use crate::{Ctx, Value, export, label_font};
use glam::Vec2;
use hatchery_annotation::{
    Color, LabelStyle, Layer, PathData, PathStyle, Stroke, SvgDocument, trace_mask,
};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, ParamSpec, Params, PortSpec, PortType, executor::Node,
};

/// The line inputs (masks) and their parameters' suffix.
const LINES: [&str; 3] = ["lines1", "lines2", "lines3"];

fn color(c: [f32; 4]) -> Color {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Color(byte(c[0]), byte(c[1]), byte(c[2]))
}

pub struct SaveSvgNode;

impl Node<Value, Ctx> for SaveSvgNode {
    fn schema(&self) -> NodeSchema {
        let mut params = vec![
            ParamSpec::path("path", "figure.svg", "the SVG file to write"),
            ParamSpec::bool(
                "embed_picture",
                true,
                "embed the `image` as a PNG layer under the lines",
            ),
            ParamSpec::choice(
                "lines_as",
                "shapes",
                &["shapes", "outlines"],
                "traced masks as filled shapes (the mask's exact extent, one path per input) or \
                 as stroked outlines (one path per contour)",
            ),
            ParamSpec::float(
                "simplify",
                0.5,
                0.0,
                10.0,
                "Douglas–Peucker tolerance of the traced lines, pixels",
            ),
            ParamSpec::color("text_color", [0.0, 0.0, 0.0, 1.0], "label text colour"),
            ParamSpec::color("halo_color", [1.0, 1.0, 1.0, 1.0], "label halo colour"),
            ParamSpec::float(
                "halo_width",
                2.0,
                0.0,
                20.0,
                "label halo width, pixels (0: none)",
            ),
            ParamSpec::color("leader_color", [0.2, 0.2, 0.2, 1.0], "leader line colour"),
            ParamSpec::float("leader_width", 1.0, 0.1, 20.0, "leader line width, pixels"),
        ];
        for (color_name, width_name) in [
            ("color1", "width1"),
            ("color2", "width2"),
            ("color3", "width3"),
        ] {
            params.push(ParamSpec::color(
                color_name,
                [0.0, 0.0, 0.0, 1.0],
                "stroke colour of the lines traced from this input",
            ));
            params.push(ParamSpec::float(
                width_name,
                1.5,
                0.1,
                50.0,
                "stroke width of those lines, pixels",
            ));
        }
        NodeSchema {
            kind: "SaveSvg",
            category: "Output",
            doc: "Writes an SVG figure whose Inkscape layers are: the picture (the `image` as an \
                  embedded PNG), lines (each `lines` mask's region above 0.5, traced by \
                  marching squares and simplified, as a filled path in its own colour, or its \
                  outlines as strokes), leader \
                  lines, arrows, and labels as <text> (from laid-out `annotations`). Open it in \
                  Inkscape or Illustrator to edit lines and text. `hatchery render -o x.svg` \
                  replaces the path. Relative paths are relative to the graph file's folder.",
            inputs: vec![
                PortSpec::optional("image", PortType::Image, "the picture"),
                PortSpec::optional(
                    "annotations",
                    PortType::Annotations,
                    "labels placed by AnnotationLayout",
                ),
                PortSpec::optional("lines1", PortType::Mask, "a line or silhouette mask"),
                PortSpec::optional("lines2", PortType::Mask, "another, with its own stroke"),
                PortSpec::optional("lines3", PortType::Mask, "a third"),
            ],
            outputs: vec![],
            params,
            frame_dependent: true,
            sink: true,
        }
    }

    fn execute(
        &self,
        ctx: &mut Ctx,
        inputs: &NodeInputs<Value>,
        p: &Params,
    ) -> Result<Vec<Value>, NodeError> {
        let (width, height) = ctx.size();
        let mut doc = SvgDocument::new(width as f32, height as f32);
        if let Some(image) = inputs.get("image")
            && p.bool("embed_picture")
        {
            let image = image.image("image")?;
            let pixels = ctx
                .gpu
                .read_texture(&image.texture)
                .map_err(|e| NodeError::at_port("image", e.to_string()))?;
            let mut png = Vec::new();
            export::image_to_rgba8(&pixels)
                .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
                .map_err(|e| NodeError::at_port("image", e.to_string()))?;
            doc.picture_png(&png);
        }
        for (i, port) in LINES.iter().enumerate() {
            let Some(mask) = inputs.get(port) else {
                continue;
            };
            let a = export::to_array(mask, &ctx.gpu).map_err(|e| NodeError::at_port(port, e))?;
            let (h, w) = (a.shape[0], a.shape[1]);
            let stroke = Stroke::new(
                color(p.color(&format!("color{}", i + 1))),
                p.f32(&format!("width{}", i + 1)),
            );
            let lines = trace_mask(&a.data, w, h, 0.5, p.f32("simplify"));
            if p.choice("lines_as") == "outlines" {
                for line in &lines {
                    doc.polyline(line, stroke);
                }
            } else {
                // One filled shape per input: outer contours and holes run in opposite
                // directions, so the non-zero rule leaves the holes open; the thin stroke of the
                // same colour keeps hairlines visible.
                let mut d = PathData::new();
                for line in &lines {
                    let Some((first, rest)) = line.points.split_first() else {
                        continue;
                    };
                    d = d.move_to(*first);
                    for q in rest {
                        d = d.line_to(*q);
                    }
                    d = d.close();
                }
                doc.path(
                    Layer::Lines,
                    d,
                    PathStyle {
                        fill: Some((stroke.color, 1.0)),
                        stroke: Some(Stroke {
                            width: stroke.width.min(1.0),
                            ..stroke
                        }),
                    },
                );
            }
        }
        if let Some(a) = inputs.get("annotations") {
            let a = a.annotations("annotations")?;
            let placed = a.placed("annotations")?;
            let halo = p.f32("halo_width");
            let style = LabelStyle {
                font_family: label_font::FAMILY.to_owned(),
                font_size: placed.font_size,
                fill: color(p.color("text_color")),
                halo: (halo > 0.0).then(|| Stroke::new(color(p.color("halo_color")), 2.0 * halo)),
            };
            let leader = Stroke::new(color(p.color("leader_color")), p.f32("leader_width"));
            let ascent = label_font::ascent(placed.font_size);
            for label in placed.layout.shown() {
                doc.leader(
                    label.leader[0],
                    label.leader[1],
                    Stroke {
                        opacity: leader.opacity * label.opacity,
                        ..leader
                    },
                );
                let at = label.rect.min + Vec2::new(LABEL_PADDING, LABEL_PADDING + ascent);
                doc.text(&a.anchors[label.anchor].text, at, &style);
            }
        }
        let path = p.path("path");
        let file = std::fs::File::create(&path)
            .map_err(|e| NodeError::new(format!("cannot write {}: {e}", path.display())))?;
        doc.write_to(std::io::BufWriter::new(file))
            .map_err(|e| NodeError::new(format!("cannot write {}: {e}", path.display())))?;
        tracing::info!(path = %path.display(), "SVG written");
        Ok(vec![])
    }
}
