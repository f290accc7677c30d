//! The canvas's zoom: how far it zooms, *Frame all* (the whole graph in the canvas, however
//! big) and the level of detail that keeps a zoomed-out graph readable — below
//! [`LOD_TITLE_PX`] a node is drawn as a box in its output's colour with its id in a legible
//! size (at least [`LEGIBLE_TEXT_PX`] on screen, broken after `_` to fit) instead of text too
//! small to read or cut off by the node's edge; a box too small for that shows no text, and
//! its name on hover.

use egui::emath::TSTransform;
use egui::{Color32, Rect, Stroke, Ui};

/// Node titles are drawn at egui's body size (13 points at zoom 1).
pub const TITLE_FONT_PX: f32 = 13.0;
/// Titles smaller than this on screen: nodes are drawn as boxes with their id.
pub const LOD_TITLE_PX: f32 = 9.0;
/// The smallest text on a zoomed-out node (screen pixels).
pub const LEGIBLE_TEXT_PX: f32 = 11.0;
/// The largest id text in a box (screen pixels).
const BOX_TEXT_PX: f32 = 14.0;
/// How far the canvas zooms out and in (wheel and *Frame all*).
pub const MIN_SCALE: f32 = 0.05;
pub const MAX_SCALE: f32 = 2.0;

/// The canvas's snarl style: egui-snarl's, zooming out to [`MIN_SCALE`] (its own floor, 0.2,
/// would stop *Frame all* short of big graphs and pull the view back each frame).
pub fn snarl_style() -> egui_snarl::ui::SnarlStyle {
    let mut style = egui_snarl::ui::SnarlStyle::new();
    style.min_scale = Some(MIN_SCALE);
    style.max_scale = Some(MAX_SCALE);
    style
}

/// The view that fits `bounds` (graph space) into `rect` (screen), centred: all of it, at
/// most at zoom 1.
pub fn frame_all(rect: Rect, bounds: Rect) -> TSTransform {
    let bounds = bounds.expand(30.0);
    let fit = (rect.width() / bounds.width()).min(rect.height() / bounds.height());
    let scaling = fit.clamp(MIN_SCALE, 1.0);
    TSTransform {
        scaling,
        translation: rect.center().to_vec2() - bounds.center().to_vec2() * scaling,
    }
}

/// The view after a wheel `scroll` (points) at `at`: zoomed about `at`, so the graph under the
/// pointer stays put.
pub fn wheel_zoom(before: TSTransform, scroll: f32, at: egui::Pos2) -> TSTransform {
    let scaling = (before.scaling * (scroll * 0.002).exp()).clamp(MIN_SCALE, MAX_SCALE);
    let factor = scaling / before.scaling;
    TSTransform::from_translation(at.to_vec2())
        * TSTransform::from_scaling(factor)
        * TSTransform::from_translation(-at.to_vec2())
        * before
}

/// Whether nodes are drawn as boxes at this zoom.
pub fn boxes(scaling: f32) -> bool {
    TITLE_FONT_PX * scaling < LOD_TITLE_PX
}

/// Paints node `id` as a box over its drawn rectangle `rect` (graph space) in `color`, outlined
/// with `stroke`, and its id in it, as large as fits (from [`BOX_TEXT_PX`] down to
/// [`LEGIBLE_TEXT_PX`] on screen, broken after `_`). Returns the text's screen size, pixels, or
/// none when even the smallest legible size would not fit: then the box has no text (zoomed
/// out that far, text cut by the box or spilling over its neighbours is not legible; its name
/// shows on hover and zooming in brings it back).
pub fn paint_box(
    ui: &Ui,
    rect: Rect,
    id: &str,
    color: Color32,
    stroke: Stroke,
    scaling: f32,
) -> Option<f32> {
    let painter = ui.painter();
    let background = ui.visuals().window_fill;
    let fill = background.lerp_to_gamma(color, 0.6);
    painter.rect(rect, 4.0 / scaling, fill, stroke, egui::StrokeKind::Inside);
    // A little room at the sides; none above and below (a one-port node is a line high).
    let inner = rect.shrink2(egui::vec2(3.0 / scaling, 0.0));
    let [r, g, b, _] = fill.to_array();
    let luma = 0.299 * r as f32 + 0.587 * g as f32 + 0.114 * b as f32;
    let ink = if luma > 140.0 {
        Color32::BLACK
    } else {
        Color32::WHITE
    };
    let mut px = BOX_TEXT_PX;
    while px >= LEGIBLE_TEXT_PX {
        let font = egui::FontId::proportional(px / scaling);
        let text = break_lines(ui, id, &font, inner.width());
        let galley = painter.layout_no_wrap(text, font, ink);
        if galley.size().x <= inner.width() && galley.size().y <= inner.height() {
            let at = inner.center() - galley.size() / 2.0;
            painter.galley(at, galley, ink);
            return Some(px);
        }
        px -= 1.0;
    }
    None
}

/// `id` in lines no wider than `width` where it can be broken: after each `_`.
fn break_lines(ui: &Ui, id: &str, font: &egui::FontId, width: f32) -> String {
    let painter = ui.painter();
    let wide = |s: &str| {
        painter
            .layout_no_wrap(s.to_owned(), font.clone(), Color32::WHITE)
            .size()
            .x
    };
    let mut lines: Vec<String> = Vec::new();
    for part in id.split_inclusive('_') {
        match lines.last_mut() {
            Some(line) if wide(&format!("{line}{part}")) <= width => line.push_str(part),
            _ => lines.push(part.to_owned()),
        }
    }
    lines.join("\n")
}
