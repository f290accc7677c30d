//! `SaveSvg`: a figure as vector graphics for illustrators' editors (Inkscape, Illustrator) —
//! the picture as an embedded PNG, lines traced from masks (marching squares and
//! Ramer–Douglas–Peucker, hatchery_annotation::trace_mask), leader lines and labels as text,
//! each group an Inkscape layer.

use crate::{Ctx, Value, export, label_font};
use glam::Vec2;
use hatchery_annotation::{
    Color, LabelStyle, Layer, PathData, PathStyle, Stroke, SvgDocument, signed_area, trace_mask,
};
use hatchery_graph::{
    NodeError, NodeInputs, NodeSchema, Params, PortSpec, PortType, executor::Node,
};
use std::path::PathBuf;

/// The line inputs (masks) and their parameters' suffix.
const LINES: [&str; 3] = ["lines1", "lines2", "lines3"];

fn color(c: [f32; 4]) -> Color {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    Color(byte(c[0]), byte(c[1]), byte(c[2]))
}

hatchery_graph::param_choice! {
    /// Traced masks as filled shapes or as stroked outlines.
    pub enum LinesAs { Shapes = "shapes", Outlines = "outlines" }
}

hatchery_graph::param_choice! {
    /// Whose world box to draw.
    pub enum Boxes { None = "none", Ghost = "ghost", Selection = "selection", Both = "both" }
}

hatchery_graph::node_params! {
    /// Parameters of `SaveSvg`; `color`/`shown`/`width` 1–3 belong to inputs `lines1`–`lines3`.
    pub struct SaveSvgParams {
        /// the SVG file to write
        pub path: PathBuf = "figure.svg";
        /// embed the `image` as a PNG layer under the lines
        pub embed_picture: bool = true;
        /// traced masks as filled shapes (the mask's exact extent, one path per input) or as
        /// stroked outlines (one path per contour)
        pub lines_as: LinesAs = LinesAs::Shapes;
        /// Douglas–Peucker tolerance of the traced lines, pixels
        pub simplify: f32 = 0.5, range(0.0, 10.0), unit(pixels);
        /// label text colour
        pub text_color: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// label halo colour
        pub halo_color: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
        /// label halo width, pixels (0: none)
        pub halo_width: f32 = 2.0, range(0.0, 20.0), unit(pixels);
        /// leader line colour
        pub leader_color: [f32; 4] = [0.2, 0.2, 0.2, 1.0];
        /// leader line width, pixels
        pub leader_width: f32 = 1.0, range(0.1, 20.0), unit(pixels);
        /// with `selection`: the arrow ghost → selection
        pub arrow: bool = true;
        /// with `selection`: the fan between their rectangles
        pub fan: bool = false;
        /// with `selection`: whose world box to draw
        pub boxes: Boxes = Boxes::None;
        /// colour of the arrow, fan and boxes
        pub convention_color: [f32; 4] = [0.8, 0.1, 0.1, 1.0];
        /// line width of the arrow, fan and boxes, pixels
        pub convention_width: f32 = 2.0, range(0.1, 32.0), unit(pixels);
        /// the arrow's bend per pixel of depth difference (as Arrow's)
        pub curvature: f32 = 0.5, range(0.0, 4.0);
        /// colour of the hatching `strokes`
        pub strokes_color: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// stroke colour of the lines traced from this input
        pub color1: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// these lines visible over the picture; off: in the hidden 'Covered lines' layer, for lines
        /// the picture draws under its surfaces (hidden edges under hatching), so that the SVG
        /// shows what the PNG does
        pub shown1: bool = true;
        /// stroke width of those lines, pixels
        pub width1: f32 = 1.5, range(0.1, 50.0), unit(pixels);
        /// stroke colour of the lines traced from this input
        pub color2: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// these lines visible over the picture; off: in the hidden 'Covered lines' layer, for lines
        /// the picture draws under its surfaces (hidden edges under hatching), so that the SVG
        /// shows what the PNG does
        pub shown2: bool = true;
        /// stroke width of those lines, pixels
        pub width2: f32 = 1.5, range(0.1, 50.0), unit(pixels);
        /// stroke colour of the lines traced from this input
        pub color3: [f32; 4] = [0.0, 0.0, 0.0, 1.0];
        /// these lines visible over the picture; off: in the hidden 'Covered lines' layer, for lines
        /// the picture draws under its surfaces (hidden edges under hatching), so that the SVG
        /// shows what the PNG does
        pub shown3: bool = true;
        /// stroke width of those lines, pixels
        pub width3: f32 = 1.5, range(0.1, 50.0), unit(pixels);
    }
}

impl SaveSvgParams {
    /// The stroke and whether it is shown of the lines traced from input `lines{k + 1}`.
    fn line(&self, k: usize) -> (Stroke, bool) {
        let (c, w, shown) = match k {
            0 => (self.color1, self.width1, self.shown1),
            1 => (self.color2, self.width2, self.shown2),
            _ => (self.color3, self.width3, self.shown3),
        };
        (Stroke::new(color(c), w), shown)
    }
}

pub struct SaveSvgNode;

impl Node<Value, Ctx> for SaveSvgNode {
    fn schema(&self) -> NodeSchema {
        NodeSchema {
            kind: "SaveSvg",
            category: "Output",
            doc: "Writes an SVG figure whose Inkscape layers are: the picture (the `image` as an \
                  embedded PNG), lines (each `lines` mask's region above 0.5, traced by \
                  marching squares and simplified, as a filled path in its own colour, or its \
                  outlines as strokes; a lines input with `shown` off goes to a hidden layer), \
                  hatching `strokes` as their tapered outlines in a layer of their own, leader lines, arrows, and labels as <text> (from laid-out `annotations`). Open it in \
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
                PortSpec::optional(
                    "strokes",
                    PortType::Strokes,
                    "hatching strokes (HatchStrokes): one open polyline each, round caps",
                ),
                PortSpec::optional(
                    "selection",
                    PortType::Annotations,
                    "ghost (anchor 0) and selection (anchor 1), e.g. SelectionRender's: arrow, \
                     fan and boxes as paths",
                ),
                PortSpec::optional(
                    "camera",
                    PortType::Camera,
                    "the view of the picture (for `selection`)",
                ),
            ],
            outputs: vec![],
            params: SaveSvgParams::specs(),
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
        let params = SaveSvgParams::read(p)?;
        let (width, height) = ctx.size();
        let mut doc = SvgDocument::new(width as f32, height as f32);
        if let Some(image) = inputs.get("image")
            && params.embed_picture
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
            let (stroke, shown) = params.line(i);
            let lines = trace_mask(&a.data, w, h, 0.5, params.simplify);
            let layer = if shown {
                Layer::Lines
            } else {
                Layer::CoveredLines
            };
            if params.lines_as == LinesAs::Outlines {
                for line in &lines {
                    let style = PathStyle {
                        fill: None,
                        stroke: Some(stroke),
                    };
                    doc.path(layer, line.into(), style);
                }
            } else {
                // One filled shape per input: outer contours and holes run in opposite
                // directions, so the non-zero rule leaves the holes open. The traced region is
                // the mask's extent (the 0.5 level between pixel centres), so the fill alone is
                // as wide as the picture's line; no stroke widens it.
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
                let style = PathStyle {
                    fill: Some((stroke.color, 1.0)),
                    stroke: None,
                };
                doc.path(layer, d, style);
            }
        }
        if let Some(s) = inputs.get("strokes") {
            let s = s.strokes("strokes")?;
            if s.frame != (width, height) {
                return Err(NodeError::at_port(
                    "strokes",
                    format!(
                        "traced in a {}×{} frame, the figure is {width}×{height}",
                        s.frame.0, s.frame.1
                    ),
                ));
            }
            let ink = color(params.strokes_color);
            for line in s
                .lines(&ctx.gpu)
                .map_err(|e| NodeError::at_port("strokes", e))?
            {
                let style = PathStyle {
                    fill: Some((ink, 1.0)),
                    stroke: None,
                };
                doc.path(
                    Layer::Strokes,
                    ribbon(&line.points, s.width, s.taper),
                    style,
                );
            }
        }
        if let Some(a) = inputs.get("annotations") {
            let a = a.annotations("annotations")?;
            let placed = a.placed("annotations")?;
            let halo = params.halo_width;
            let style = LabelStyle {
                font_family: label_font::FAMILY.to_owned(),
                font_size: label_font::svg_font_size(placed.font_size),
                fill: color(params.text_color),
                halo: (halo > 0.0).then(|| Stroke::new(color(params.halo_color), 2.0 * halo)),
            };
            let leader = Stroke::new(color(params.leader_color), params.leader_width);
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
                let at = label.rect.min + Vec2::new(placed.padding, placed.padding + ascent);
                doc.text(&a.anchors[label.anchor].text, at, &style);
            }
        }
        if let Some(selection) = inputs.get("selection") {
            let selection = selection.annotations("selection")?;
            let camera = inputs
                .get("camera")
                .ok_or_else(|| {
                    NodeError::at_port("camera", "`selection` needs the camera of the picture")
                })?
                .camera("camera")?;
            conventions(&mut doc, selection, camera, (width, height), &params)?;
        }
        let path = &params.path;
        hatchery_graph::atomic::write_atomically(path, |file| {
            let mut out = std::io::BufWriter::new(file);
            doc.write_to(&mut out)?;
            std::io::Write::flush(&mut out)
        })
        .map_err(|e| NodeError::new(format!("cannot write {}: {e}", path.display())))?;
        tracing::info!(path = %path.display(), "SVG written");
        Ok(vec![])
    }
}

/// A hatching stroke as the filled outline HatchStrokes draws (hatch_strokes.wgsl): `width`
/// wide in the middle, each end tapering to nothing over `taper` of its points; an SVG stroke
/// has one width, so the outline is drawn instead, offset along each point's normal.
fn ribbon(points: &[Vec2], width: f32, taper: f32) -> PathData {
    let n = points.len();
    let half = |k: usize| {
        let t = k as f32 / (n.max(2) - 1) as f32;
        let scale = if taper > 0.0 {
            (t.min(1.0 - t) / taper).clamp(0.0, 1.0)
        } else {
            1.0
        };
        0.5 * width * scale
    };
    let offset = |k: usize| {
        let along = points[(k + 1).min(n - 1)] - points[k.saturating_sub(1)];
        let normal = Vec2::new(-along.y, along.x).normalize_or_zero();
        normal * half(k)
    };
    let left = (0..n).map(|k| points[k] + offset(k));
    let right = (0..n).rev().map(|k| points[k] - offset(k));
    polygon(&left.chain(right).collect::<Vec<_>>())
}

/// A closed path through `points`.
fn polygon(points: &[Vec2]) -> PathData {
    let mut d = PathData::new();
    for (i, &q) in points.iter().enumerate() {
        d = if i == 0 { d.move_to(q) } else { d.line_to(q) };
    }
    d.close()
}

/// The rectangle (lo, hi) as corner points, in the winding opposite to `hull`'s (so that the
/// non-zero rule leaves it out of a fill together with the hull).
fn rect_points((lo, hi): (Vec2, Vec2), hull: &[Vec2]) -> Vec<Vec2> {
    let mut r = vec![lo, Vec2::new(hi.x, lo.y), hi, Vec2::new(lo.x, hi.y)];
    if (signed_area(&r) > 0.0) == (signed_area(hull) > 0.0) {
        r.reverse();
    }
    r
}

/// VolumeShop's visual conventions (§6.3) as paths in the arrows layer, the same geometry the
/// Arrow, Fan and BoundingBox nodes draw.
fn conventions(
    doc: &mut SvgDocument,
    selection: &crate::annotations::Annotations,
    camera: &crate::camera::Camera,
    frame: (u32, u32),
    p: &SaveSvgParams,
) -> Result<(), NodeError> {
    use crate::visual_conventions::{arrow_shape, box_edges, fan_shape};
    let at_port = |e: NodeError| NodeError::at_port("selection", e.message);
    let color = color(p.convention_color);
    let width = p.convention_width;
    let stroke = Stroke::new(color, width);
    let stroked = PathStyle {
        fill: None,
        stroke: Some(stroke),
    };
    if p.fan
        && let Some(fan) = fan_shape(selection, camera, frame).map_err(at_port)?
    {
        let mut fill = polygon(&fan.hull);
        for rect in fan.rects {
            fill.0.extend(polygon(&rect_points(rect, &fan.hull)).0);
        }
        let fill_style = PathStyle {
            fill: Some((color, 0.15)),
            stroke: None,
        };
        doc.path(Layer::Arrows, fill, fill_style);
        for rect in fan.rects {
            doc.path(
                Layer::Arrows,
                polygon(&rect_points(rect, &fan.hull)),
                stroked,
            );
        }
        for [a, b] in fan.bridges {
            doc.path(
                Layer::Arrows,
                PathData::new().move_to(a).line_to(b),
                stroked,
            );
        }
    }
    let which: &[usize] = match p.boxes {
        Boxes::Ghost => &[0],
        Boxes::Selection => &[1],
        Boxes::Both => &[0, 1],
        Boxes::None => &[],
    };
    for [a, b] in box_edges(selection, camera, frame, which).map_err(at_port)? {
        doc.path(
            Layer::Arrows,
            PathData::new().move_to(a).line_to(b),
            stroked,
        );
    }
    if p.arrow
        && let Some((shaft, head)) =
            arrow_shape(selection, camera, frame, width, p.curvature).map_err(at_port)?
    {
        let mut d = PathData::new();
        for (i, &q) in shaft.iter().enumerate() {
            d = if i == 0 { d.move_to(q) } else { d.line_to(q) };
        }
        doc.path(Layer::Arrows, d, stroked);
        doc.path(
            Layer::Arrows,
            polygon(&head),
            PathStyle {
                fill: Some((color, 1.0)),
                stroke: None,
            },
        );
    }
    Ok(())
}

/// This module's node kinds, shader programs and uniform blocks (see [`crate::kinds`]).
pub fn declare(k: &mut crate::kinds::Kinds) {
    k.node(SaveSvgNode);
}
