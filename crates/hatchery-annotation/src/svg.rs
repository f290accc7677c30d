//! Vector export: an SVG document with Inkscape layers for the picture, traced lines, leader
//! lines, arrows (and other generic paths) and labels.
//!
//! Written with quick-xml's `Writer` (already in hatchery's dependency tree through
//! hatchery-data): `BytesText::new` escapes text and `push_attribute` escapes attribute values
//! (`&`, `<`, `>`, quotes), so label texts are safe as given. The `svg` crate would be a new
//! dependency for the handful of elements written here, and its attribute escaping is not
//! documented.

use crate::geometry::Rect;
use crate::layout::Layout;
use crate::trace::Polyline;
use base64::Engine;
use glam::Vec2;
use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};
use std::io::{self, Write};

/// The document's layers, in drawing order (bottom first). Each is written as
/// `<g id="…" inkscape:groupmode="layer" inkscape:label="…">`, also when empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Layer {
    /// The raster picture (`id="picture"`).
    Picture,
    /// Traced lines the picture draws under its surfaces, e.g. hidden edges under hatching
    /// (`id="covered-lines"`): hidden (`display:none`), so that the figure stays the picture,
    /// and there for an illustrator to show or restyle.
    CoveredLines,
    /// Hatching strokes, one open path each (`id="strokes"`): a layer of their own, so that an
    /// illustrator can hide or restyle the hatching apart from the outlines.
    Strokes,
    /// Traced lines: silhouettes, contours, ridges (`id="lines"`).
    Lines,
    /// Leader (connecting) lines from anchors to labels (`id="leaders"`).
    Leaders,
    /// Arrows, fans, boxes and other generic paths (`id="arrows"`).
    Arrows,
    /// Label texts (`id="labels"`).
    Labels,
}

impl Layer {
    /// All layers in drawing order.
    pub const ALL: [Layer; 7] = [
        Layer::Picture,
        Layer::CoveredLines,
        Layer::Strokes,
        Layer::Lines,
        Layer::Leaders,
        Layer::Arrows,
        Layer::Labels,
    ];

    /// The group's `id`.
    pub fn id(self) -> &'static str {
        match self {
            Layer::Picture => "picture",
            Layer::CoveredLines => "covered-lines",
            Layer::Strokes => "strokes",
            Layer::Lines => "lines",
            Layer::Leaders => "leaders",
            Layer::Arrows => "arrows",
            Layer::Labels => "labels",
        }
    }

    /// The layer name Inkscape shows (`inkscape:label`).
    pub fn label(self) -> &'static str {
        match self {
            Layer::Picture => "Picture",
            Layer::CoveredLines => "Covered lines (hidden)",
            Layer::Strokes => "Hatching",
            Layer::Lines => "Lines",
            Layer::Leaders => "Leader lines",
            Layer::Arrows => "Arrows",
            Layer::Labels => "Labels",
        }
    }
}

/// An sRGB colour, 8 bits per channel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Color(pub u8, pub u8, pub u8);

impl Color {
    /// Black.
    pub const BLACK: Color = Color(0, 0, 0);
    /// White.
    pub const WHITE: Color = Color(255, 255, 255);

    fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// A stroke: colour, width in px, opacity in [0, 1]. Round caps and joins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stroke {
    /// Stroke colour.
    pub color: Color,
    /// Width, px.
    pub width: f32,
    /// Opacity in [0, 1].
    pub opacity: f32,
}

impl Stroke {
    /// An opaque stroke.
    pub fn new(color: Color, width: f32) -> Self {
        Self {
            color,
            width,
            opacity: 1.0,
        }
    }
}

/// Paint of a generic path: an optional fill (colour, opacity) and an optional stroke.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathStyle {
    /// Fill colour and opacity; `None` writes `fill="none"`.
    pub fill: Option<(Color, f32)>,
    /// Stroke; `None` writes no stroke.
    pub stroke: Option<Stroke>,
}

/// Text style of labels.
#[derive(Clone, Debug, PartialEq)]
pub struct LabelStyle {
    /// CSS font family list, e.g. `"DejaVu Sans, Arial, sans-serif"`.
    pub font_family: String,
    /// Font size, px.
    pub font_size: f32,
    /// Text colour.
    pub fill: Color,
    /// Optional halo: a stroke painted under the glyphs (`paint-order="stroke"`), e.g. white and
    /// 3 px wide, to keep labels readable over the picture.
    pub halo: Option<Stroke>,
}

impl Default for LabelStyle {
    fn default() -> Self {
        Self {
            font_family: "DejaVu Sans, Arial, Helvetica, sans-serif".into(),
            font_size: 14.0,
            fill: Color::BLACK,
            halo: Some(Stroke::new(Color::WHITE, 3.0)),
        }
    }
}

/// Fraction of the font size between a label box's bottom and the text baseline (descenders).
pub const DESCENT: f32 = 0.25;
/// Label box height per font size, for [`estimate_label_size`].
pub const LINE_HEIGHT: f32 = 1.25;
/// Mean advance per character per font size, for [`estimate_label_size`] (sans-serif).
pub const MEAN_ADVANCE: f32 = 0.6;

/// A rough label box (w × h px) for `text` at `font_size` px without font metrics:
/// `(MEAN_ADVANCE · font_size · chars, LINE_HEIGHT · font_size)`. The drawing side should measure
/// real text where it can; this is for tests and previews.
pub fn estimate_label_size(text: &str, font_size: f32) -> Vec2 {
    Vec2::new(
        MEAN_ADVANCE * font_size * text.chars().count() as f32,
        LINE_HEIGHT * font_size,
    )
}

/// Where the text of a label box starts: its left edge, on the baseline `DESCENT · font_size`
/// above the box bottom, px. The SVG `<text>` of a label is written at this point
/// (`text-anchor` start).
pub fn label_baseline(rect: &Rect, font_size: f32) -> Vec2 {
    Vec2::new(rect.min.x, rect.max.y - DESCENT * font_size)
}

/// One path command, coordinates in px.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PathCommand {
    /// Start a sub-path.
    MoveTo(Vec2),
    /// Straight line.
    LineTo(Vec2),
    /// Quadratic Bézier (control, end).
    QuadTo(Vec2, Vec2),
    /// Cubic Bézier (control 1, control 2, end).
    CubicTo(Vec2, Vec2, Vec2),
    /// Close the sub-path.
    Close,
}

/// Path geometry, written as an SVG `d` attribute with absolute commands.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathData(pub Vec<PathCommand>);

impl PathData {
    /// An empty path.
    pub fn new() -> Self {
        Self::default()
    }
    /// Appends a move.
    pub fn move_to(mut self, p: Vec2) -> Self {
        self.0.push(PathCommand::MoveTo(p));
        self
    }
    /// Appends a line.
    pub fn line_to(mut self, p: Vec2) -> Self {
        self.0.push(PathCommand::LineTo(p));
        self
    }
    /// Appends a quadratic Bézier.
    pub fn quad_to(mut self, c: Vec2, p: Vec2) -> Self {
        self.0.push(PathCommand::QuadTo(c, p));
        self
    }
    /// Appends a cubic Bézier.
    pub fn cubic_to(mut self, c1: Vec2, c2: Vec2, p: Vec2) -> Self {
        self.0.push(PathCommand::CubicTo(c1, c2, p));
        self
    }
    /// Closes the current sub-path.
    pub fn close(mut self) -> Self {
        self.0.push(PathCommand::Close);
        self
    }

    /// The `d` attribute text.
    pub fn to_svg(&self) -> String {
        let mut d = String::new();
        let pt = |p: Vec2| format!("{},{}", num(p.x), num(p.y));
        for c in &self.0 {
            if !d.is_empty() {
                d.push(' ');
            }
            match *c {
                PathCommand::MoveTo(p) => d += &format!("M{}", pt(p)),
                PathCommand::LineTo(p) => d += &format!("L{}", pt(p)),
                PathCommand::QuadTo(c, p) => d += &format!("Q{} {}", pt(c), pt(p)),
                PathCommand::CubicTo(a, b, p) => d += &format!("C{} {} {}", pt(a), pt(b), pt(p)),
                PathCommand::Close => d.push('Z'),
            }
        }
        d
    }
}

impl From<&Polyline> for PathData {
    fn from(line: &Polyline) -> Self {
        let mut d = PathData::new();
        for (k, &p) in line.points.iter().enumerate() {
            d = if k == 0 { d.move_to(p) } else { d.line_to(p) };
        }
        if line.closed && line.points.len() > 1 {
            d = d.close();
        }
        d
    }
}

/// A number with at most 3 decimals, without trailing zeros.
fn num(v: f32) -> String {
    let s = format!("{:.3}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

#[derive(Clone, Debug, PartialEq)]
enum Item {
    Path {
        d: PathData,
        style: PathStyle,
    },
    Text {
        text: String,
        at: Vec2,
        style: LabelStyle,
    },
}

/// An SVG document under construction: `width × height` px (also the `viewBox`), its layers
/// ([`Layer`]) filled by the builder methods, written by [`SvgDocument::write_to`].
#[derive(Clone, Debug, PartialEq)]
pub struct SvgDocument {
    width: f32,
    height: f32,
    picture: Option<Vec<u8>>,
    items: [Vec<Item>; Layer::ALL.len()],
}

impl SvgDocument {
    /// An empty document of `width × height` px.
    pub fn new(width: f32, height: f32) -> Self {
        Self {
            width,
            height,
            picture: None,
            items: Default::default(),
        }
    }

    /// Embeds `png` (the bytes of a PNG file) in the picture layer, stretched over the whole
    /// document, as `<image href="data:image/png;base64,…">`. Replaces an earlier picture.
    pub fn picture_png(&mut self, png: &[u8]) -> &mut Self {
        self.picture = Some(png.to_vec());
        self
    }

    /// Adds a generic path to `layer` (a path in [`Layer::Picture`] is drawn above the image).
    pub fn path(&mut self, layer: Layer, d: PathData, style: PathStyle) -> &mut Self {
        self.items[layer as usize].push(Item::Path { d, style });
        self
    }

    /// Adds a polyline (e.g. from [`trace_mask`](crate::trace_mask)) to the lines layer, unfilled.
    pub fn polyline(&mut self, line: &Polyline, stroke: Stroke) -> &mut Self {
        self.path(
            Layer::Lines,
            line.into(),
            PathStyle {
                fill: None,
                stroke: Some(stroke),
            },
        )
    }

    /// Adds a leader line from `from` to `to` to the leaders layer.
    pub fn leader(&mut self, from: Vec2, to: Vec2, stroke: Stroke) -> &mut Self {
        self.path(
            Layer::Leaders,
            PathData::new().move_to(from).line_to(to),
            PathStyle {
                fill: None,
                stroke: Some(stroke),
            },
        )
    }

    /// Adds a text to the labels layer, its baseline starting at `at` px.
    pub fn text(&mut self, text: &str, at: Vec2, style: &LabelStyle) -> &mut Self {
        self.items[Layer::Labels as usize].push(Item::Text {
            text: text.to_owned(),
            at,
            style: style.clone(),
        });
        self
    }

    /// Adds the shown labels of `layout`: for each, its leader line (`leader` with its opacity
    /// multiplied by the label's [`opacity`](crate::PlacedLabel::opacity)) and its text
    /// `texts[label.anchor]` at [`label_baseline`]. `texts` holds one text per anchor (panics when
    /// shorter).
    pub fn annotations<S: AsRef<str>>(
        &mut self,
        layout: &Layout,
        texts: &[S],
        style: &LabelStyle,
        leader: Stroke,
    ) -> &mut Self {
        for label in layout.shown() {
            let stroke = Stroke {
                opacity: leader.opacity * label.opacity,
                ..leader
            };
            self.leader(label.leader[0], label.leader[1], stroke);
            self.text(
                texts[label.anchor].as_ref(),
                label_baseline(&label.rect, style.font_size),
                style,
            );
        }
        self
    }

    /// Writes the document as UTF-8 SVG.
    pub fn write_to<W: Write>(&self, out: W) -> io::Result<()> {
        let mut w = Writer::new_with_indent(out, b' ', 1);
        w.write_event(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)))?;
        let (width, height) = (num(self.width), num(self.height));
        let view_box = format!("0 0 {width} {height}");
        let mut svg = BytesStart::new("svg");
        svg.push_attribute(("xmlns", "http://www.w3.org/2000/svg"));
        svg.push_attribute((
            "xmlns:inkscape",
            "http://www.inkscape.org/namespaces/inkscape",
        ));
        svg.push_attribute(("version", "1.1"));
        svg.push_attribute(("width", width.as_str()));
        svg.push_attribute(("height", height.as_str()));
        svg.push_attribute(("viewBox", view_box.as_str()));
        w.write_event(Event::Start(svg))?;
        for layer in Layer::ALL {
            let mut g = BytesStart::new("g");
            g.push_attribute(("id", layer.id()));
            g.push_attribute(("inkscape:groupmode", "layer"));
            g.push_attribute(("inkscape:label", layer.label()));
            if layer == Layer::CoveredLines {
                g.push_attribute(("style", "display:none"));
            }
            w.write_event(Event::Start(g))?;
            if layer == Layer::Picture
                && let Some(png) = &self.picture
            {
                let href = format!(
                    "data:image/png;base64,{}",
                    base64::engine::general_purpose::STANDARD.encode(png)
                );
                let mut image = BytesStart::new("image");
                image.push_attribute(("x", "0"));
                image.push_attribute(("y", "0"));
                image.push_attribute(("width", width.as_str()));
                image.push_attribute(("height", height.as_str()));
                image.push_attribute(("preserveAspectRatio", "none"));
                image.push_attribute(("href", href.as_str()));
                w.write_event(Event::Empty(image))?;
            }
            for item in &self.items[layer as usize] {
                write_item(&mut w, item)?;
            }
            w.write_event(Event::End(BytesEnd::new("g")))?;
        }
        w.write_event(Event::End(BytesEnd::new("svg")))?;
        w.into_inner().write_all(b"\n")
    }

    /// The document as an SVG string.
    pub fn to_svg_string(&self) -> String {
        let mut bytes = Vec::new();
        self.write_to(&mut bytes)
            .expect("writing to a Vec does not fail");
        String::from_utf8(bytes).expect("the writer emits UTF-8")
    }
}

fn push_stroke(e: &mut BytesStart, stroke: &Stroke) {
    e.push_attribute(("stroke", stroke.color.hex().as_str()));
    e.push_attribute(("stroke-width", num(stroke.width).as_str()));
    if stroke.opacity < 1.0 {
        e.push_attribute(("stroke-opacity", num(stroke.opacity.max(0.0)).as_str()));
    }
    e.push_attribute(("stroke-linecap", "round"));
    e.push_attribute(("stroke-linejoin", "round"));
}

fn write_item<W: Write>(w: &mut Writer<W>, item: &Item) -> io::Result<()> {
    match item {
        Item::Path { d, style } => {
            let mut e = BytesStart::new("path");
            e.push_attribute(("d", d.to_svg().as_str()));
            match style.fill {
                Some((color, opacity)) => {
                    e.push_attribute(("fill", color.hex().as_str()));
                    if opacity < 1.0 {
                        e.push_attribute(("fill-opacity", num(opacity.max(0.0)).as_str()));
                    }
                }
                None => e.push_attribute(("fill", "none")),
            }
            if let Some(stroke) = &style.stroke {
                push_stroke(&mut e, stroke);
            }
            w.write_event(Event::Empty(e))
        }
        Item::Text { text, at, style } => {
            let mut e = BytesStart::new("text");
            e.push_attribute(("x", num(at.x).as_str()));
            e.push_attribute(("y", num(at.y).as_str()));
            e.push_attribute(("font-family", style.font_family.as_str()));
            e.push_attribute(("font-size", num(style.font_size).as_str()));
            e.push_attribute(("fill", style.fill.hex().as_str()));
            if let Some(halo) = &style.halo {
                push_stroke(&mut e, halo);
                e.push_attribute(("paint-order", "stroke"));
            }
            w.write_event(Event::Start(e))?;
            w.write_event(Event::Text(BytesText::new(text)))?;
            w.write_event(Event::End(BytesEnd::new("text")))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_escaping() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.125), "2.125");
        let mut doc = SvgDocument::new(10.0, 10.0);
        doc.text("a < b & \"c\"", Vec2::ZERO, &LabelStyle::default());
        let s = doc.to_svg_string();
        assert!(s.contains("a &lt; b &amp;"), "{s}");
    }
}
