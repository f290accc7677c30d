//! Curve editors for transfer functions: control points on an opacity curve over the data values,
//! each drawn in its colour above the ramp they make (over a checkerboard, so opacity shows).
//! One widget serves the colour transfer function (points carry colours) and the style transfer
//! function (points carry lit-sphere style numbers).
//!
//! Mouse: drag a point to move it (its value stays between its neighbours'), double-click on the
//! curve area to add a point, right-click a point to remove it, click a point to pick it for the
//! fields below the curve.

use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2};
use hatchery_data::style::StyleNode;
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};

/// A control point of a curve: a data value, an opacity, and what else it carries.
pub trait CurvePoint: Clone + PartialEq {
    fn value(&self) -> f32;
    fn value_mut(&mut self) -> &mut f32;
    fn opacity_mut(&mut self) -> &mut f32;
    fn opacity(&self) -> f32;
    /// The point inserted at `value` between the existing ones.
    fn inserted(points: &[Self], value: f32, opacity: f32) -> Self;
    /// What the transfer function gives at `value` (straight colour, opacity).
    fn ramp(points: &[Self], value: f32, look: &dyn Fn(&Self) -> [f32; 3]) -> [f32; 4];
}

/// Height of the curve area, points.
const HEIGHT: f32 = 140.0;
/// Radius of a control point's handle, points.
const HANDLE: f32 = 6.0;

/// What the editor remembers between frames (per node, in egui's memory).
#[derive(Clone, Copy, Default)]
struct Memory {
    selected: Option<usize>,
    /// Handle position minus the pointer's, while a point is dragged.
    grab: Vec2,
}

/// Maps data values to x and opacity to y inside `rect`.
struct Frame {
    rect: Rect,
    domain: [f32; 2],
}

impl Frame {
    fn x(&self, value: f32) -> f32 {
        let t = (value - self.domain[0]) / (self.domain[1] - self.domain[0]);
        self.rect.left() + t * self.rect.width()
    }
    fn y(&self, alpha: f32) -> f32 {
        self.rect.bottom() - alpha.clamp(0.0, 1.0) * self.rect.height()
    }
    fn value(&self, x: f32) -> f32 {
        let t = (x - self.rect.left()) / self.rect.width();
        self.domain[0] + t * (self.domain[1] - self.domain[0])
    }
    fn alpha(&self, y: f32) -> f32 {
        ((self.rect.bottom() - y) / self.rect.height()).clamp(0.0, 1.0)
    }
    fn handle(&self, p: &impl CurvePoint) -> Pos2 {
        Pos2::new(self.x(p.value()), self.y(p.opacity()))
    }
}

/// The plotted value range: the points' range, widened to `context` (e.g. the volume's range).
pub fn plot_domain(points: &[impl CurvePoint], context: Option<[f32; 2]>) -> [f32; 2] {
    let mut lo = points
        .iter()
        .map(|p| p.value())
        .fold(f32::INFINITY, f32::min);
    let mut hi = points
        .iter()
        .map(|p| p.value())
        .fold(f32::NEG_INFINITY, f32::max);
    if let Some([a, b]) = context.filter(|[a, b]| a.is_finite() && b.is_finite()) {
        lo = lo.min(a);
        hi = hi.max(b);
    }
    if !lo.is_finite() || !hi.is_finite() {
        return [0.0, 1.0];
    }
    if hi <= lo {
        hi = lo + 1.0;
    }
    [lo, hi]
}

/// The colour at `value` by linear interpolation between the points (the node's rule).
fn interpolate(points: &[ControlPoint], value: f32) -> [f32; 4] {
    match points.iter().position(|p| p.value >= value) {
        None => points.last().map_or([0.0; 4], |p| p.rgba),
        Some(0) => points[0].rgba,
        Some(i) => {
            let (a, b) = (&points[i - 1], &points[i]);
            let t = ((value - a.value) / (b.value - a.value)).clamp(0.0, 1.0);
            [0, 1, 2, 3].map(|c| a.rgba[c] + t * (b.rgba[c] - a.rgba[c]))
        }
    }
}

/// Draws and edits `points` (strictly increasing values); `name` labels the widgets ("transfer
/// function"), `look` gives a point's colour, `fields` draws the picked point's own fields.
/// Returns whether the points changed.
pub fn curve_editor<P: CurvePoint>(
    ui: &mut Ui,
    id: egui::Id,
    name: &str,
    points: &mut Vec<P>,
    context: Option<[f32; 2]>,
    look: &dyn Fn(&P) -> [f32; 3],
    fields: &mut dyn FnMut(&mut Ui, &mut P) -> bool,
) -> bool {
    let mut memory: Memory = ui.data(|d| d.get_temp(id).unwrap_or_default());
    let width = ui.available_width().max(120.0);
    let (rect, background) = ui.allocate_exact_size(Vec2::new(width, HEIGHT), Sense::click());
    background.widget_info(|| {
        egui::WidgetInfo::labeled(egui::WidgetType::Other, true, format!("{name} curve"))
    });
    let frame = Frame {
        rect,
        domain: plot_domain(points, context),
    };
    let painter = ui.painter_at(rect.expand(HANDLE));
    draw_ramp(&painter, &frame, &|v| P::ramp(points, v, look));

    // The opacity curve.
    let line: Vec<Pos2> = points.iter().map(|p| frame.handle(p)).collect();
    painter.add(egui::Shape::line(line, Stroke::new(1.5, Color32::BLACK)));

    let mut changed = false;
    let mut remove = None;
    for i in 0..points.len() {
        let at = frame.handle(&points[i]);
        let handle = Rect::from_center_size(at, Vec2::splat(HANDLE * 2.5));
        let response = ui.interact(handle, id.with(("point", i)), Sense::click_and_drag());
        response.widget_info(|| {
            let label = format!("{name} point {}", i + 1);
            egui::WidgetInfo::labeled(egui::WidgetType::Other, true, label)
        });
        let response = response.on_hover_text(format!(
            "value {}, opacity {:.3}\ndrag to move, right-click to remove",
            points[i].value(),
            points[i].opacity()
        ));
        if response.drag_started() || response.clicked() {
            memory.selected = Some(i);
        }
        if response.drag_started() {
            // Where on the handle it was grabbed: the point keeps that offset from the pointer
            // (grabbing off its centre does not make it jump).
            let origin = ui.input(|i| i.pointer.press_origin()).unwrap_or(at);
            memory.grab = at - origin;
        }
        if response.dragged()
            && let Some(pointer) = response.interact_pointer_pos().map(|p| p + memory.grab)
        {
            // Keep values strictly increasing: a point stays between its neighbours.
            let span = frame.domain[1] - frame.domain[0];
            let gap = span * 1e-3;
            let lo = if i > 0 {
                points[i - 1].value() + gap
            } else {
                f32::NEG_INFINITY
            };
            let hi = points
                .get(i + 1)
                .map_or(f32::INFINITY, |next| next.value() - gap);
            let value = frame.value(pointer.x).clamp(lo, hi.max(lo));
            let alpha = frame.alpha(pointer.y);
            if value != points[i].value() || alpha != points[i].opacity() {
                *points[i].value_mut() = value;
                *points[i].opacity_mut() = alpha;
                changed = true;
            }
        }
        if response.secondary_clicked() && points.len() > 2 {
            remove = Some(i);
        }
        let [r, g, b] = look(&points[i]).map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
        let outline = if memory.selected == Some(i) {
            Stroke::new(2.5, Color32::YELLOW)
        } else {
            Stroke::new(1.5, Color32::WHITE)
        };
        painter.circle(at, HANDLE, Color32::from_rgb(r, g, b), outline);
    }
    if let Some(i) = remove {
        points.remove(i);
        memory.selected = None;
        changed = true;
    }
    if background.double_clicked()
        && let Some(pointer) = background.interact_pointer_pos()
    {
        let value = frame.value(pointer.x);
        if points.iter().all(|p| p.value() != value) {
            let new = P::inserted(points, value, frame.alpha(pointer.y));
            let at = points.partition_point(|p| p.value() < value);
            points.insert(at, new);
            memory.selected = Some(at);
            changed = true;
        }
    }
    background.on_hover_text("double-click to add a point");

    // Fields of the picked point.
    if let Some(i) = memory.selected.filter(|&i| i < points.len()) {
        // Wrapped, so the fields never widen the panel (which would move the curve mid-drag).
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("point {}", i + 1));
            let p = &mut points[i];
            changed |= fields(ui, p);
            ui.label("value");
            changed |= ui
                .add(egui::DragValue::new(p.value_mut()).speed(0.5))
                .changed();
            ui.label("opacity");
            changed |= ui
                .add(
                    egui::DragValue::new(p.opacity_mut())
                        .range(0.0..=1.0)
                        .speed(0.005),
                )
                .changed();
        });
        // Typed values may break the order: sort, keeping the picked point picked.
        if !points.windows(2).all(|w| w[0].value() < w[1].value()) {
            let picked = points[i].clone();
            points.sort_by(|a, b| a.value().total_cmp(&b.value()));
            points.dedup_by(|b, a| a.value() == b.value());
            memory.selected = points.iter().position(|p| *p == picked);
        }
    }
    ui.data_mut(|d| d.insert_temp(id, memory));
    changed
}

/// The ramp `at` gives (straight colour, opacity per value), over a checkerboard, as strips.
fn draw_ramp(painter: &egui::Painter, frame: &Frame, at: &dyn Fn(f32) -> [f32; 4]) {
    let rect = frame.rect;
    let cell = 8.0;
    let (cols, rows) = (
        (rect.width() / cell).ceil() as i32,
        (rect.height() / cell).ceil() as i32,
    );
    for j in 0..rows {
        for i in 0..cols {
            let grey = if (i + j) % 2 == 0 { 230 } else { 190 };
            let min = rect.min + Vec2::new(i as f32 * cell, j as f32 * cell);
            let square = Rect::from_min_size(min, Vec2::splat(cell)).intersect(rect);
            painter.rect_filled(square, 0.0, Color32::from_gray(grey));
        }
    }
    let strips = (rect.width() / 2.0).ceil() as usize;
    for s in 0..strips {
        let x0 = rect.left() + s as f32 * 2.0;
        let value = frame.value(x0 + 1.0);
        let [r, g, b, a] = at(value);
        let color = Color32::from_rgba_unmultiplied(
            (r.clamp(0.0, 1.0) * 255.0) as u8,
            (g.clamp(0.0, 1.0) * 255.0) as u8,
            (b.clamp(0.0, 1.0) * 255.0) as u8,
            (a.clamp(0.0, 1.0) * 255.0) as u8,
        );
        let strip = Rect::from_min_max(
            Pos2::new(x0, rect.top()),
            Pos2::new((x0 + 2.0).min(rect.right()), rect.bottom()),
        );
        painter.rect_filled(strip, 0.0, color);
    }
    painter.rect_stroke(
        rect,
        0.0,
        Stroke::new(1.0, Color32::DARK_GRAY),
        egui::StrokeKind::Inside,
    );
}

/// The points a `TransferFunction1D` node uses: its `points` when the preset is `custom`, else
/// the preset's points over `range` (the connected volume's value range when known).
pub fn node_points(
    preset: &str,
    points_text: &str,
    range: [f32; 2],
) -> Result<Vec<ControlPoint>, String> {
    if preset == "custom" {
        TransferFunction1D::parse_points(points_text).map_err(|e| e.to_string())
    } else {
        TransferFunction1D::preset(preset, range)
            .ok_or_else(|| format!("unknown preset `{preset}`"))
    }
}

impl CurvePoint for ControlPoint {
    fn value(&self) -> f32 {
        self.value
    }
    fn value_mut(&mut self) -> &mut f32 {
        &mut self.value
    }
    fn opacity(&self) -> f32 {
        self.rgba[3]
    }
    fn opacity_mut(&mut self) -> &mut f32 {
        &mut self.rgba[3]
    }
    fn inserted(points: &[Self], value: f32, opacity: f32) -> Self {
        let mut rgba = interpolate(points, value);
        rgba[3] = opacity;
        ControlPoint { value, rgba }
    }
    fn ramp(points: &[Self], value: f32, _look: &dyn Fn(&Self) -> [f32; 3]) -> [f32; 4] {
        interpolate(points, value)
    }
}

/// The colour transfer function's editor: points carry colours (picked below the curve).
pub fn transfer_function_editor(
    ui: &mut Ui,
    id: egui::Id,
    points: &mut Vec<ControlPoint>,
    context: Option<[f32; 2]>,
) -> bool {
    let look = |p: &ControlPoint| [p.rgba[0], p.rgba[1], p.rgba[2]];
    let mut colour = |ui: &mut Ui, p: &mut ControlPoint| {
        // A copy: the colour button rounds through HSV every frame.
        let mut rgb = [p.rgba[0], p.rgba[1], p.rgba[2]];
        let changed = ui.color_edit_button_rgb(&mut rgb).changed();
        if changed {
            p.rgba[..3].copy_from_slice(&rgb);
        }
        changed
    };
    curve_editor(
        ui,
        id,
        "transfer function",
        points,
        context,
        &look,
        &mut colour,
    )
}

impl CurvePoint for StyleNode {
    fn value(&self) -> f32 {
        self.value
    }
    fn value_mut(&mut self) -> &mut f32 {
        &mut self.value
    }
    fn opacity(&self) -> f32 {
        self.opacity
    }
    fn opacity_mut(&mut self) -> &mut f32 {
        &mut self.opacity
    }
    /// The style of the nearest node at or below `value` (else the first).
    fn inserted(points: &[Self], value: f32, opacity: f32) -> Self {
        let below = points.iter().rev().find(|p| p.value <= value);
        StyleNode {
            value,
            style: below.or(points.first()).map_or(0, |p| p.style),
            opacity,
        }
    }
    /// Styles blend between nodes (§4.1): the ramp mixes the styles' colours the same way.
    fn ramp(points: &[Self], value: f32, look: &dyn Fn(&Self) -> [f32; 3]) -> [f32; 4] {
        let mix = |a: &Self, b: &Self, t: f32| {
            let (ca, cb) = (look(a), look(b));
            let c = [0, 1, 2].map(|i| ca[i] + t * (cb[i] - ca[i]));
            [c[0], c[1], c[2], a.opacity + t * (b.opacity - a.opacity)]
        };
        match points.iter().position(|p| p.value >= value) {
            None => points.last().map_or([0.0; 4], |p| mix(p, p, 0.0)),
            Some(0) => mix(&points[0], &points[0], 0.0),
            Some(i) => {
                let (a, b) = (&points[i - 1], &points[i]);
                mix(
                    a,
                    b,
                    ((value - a.value) / (b.value - a.value)).clamp(0.0, 1.0),
                )
            }
        }
    }
}

/// The style transfer function's editor: points carry style numbers, named and coloured after
/// the connected `StyleSet` (`styles`: name and representative colour of each style).
pub fn style_curve_editor(
    ui: &mut Ui,
    id: egui::Id,
    nodes: &mut Vec<StyleNode>,
    context: Option<[f32; 2]>,
    styles: &[(String, [f32; 3])],
) -> bool {
    let look = |p: &StyleNode| styles.get(p.style).map_or([0.5; 3], |s| s.1);
    let mut pick_style = |ui: &mut Ui, p: &mut StyleNode| {
        let name = |j: usize| match styles.get(j) {
            Some((name, _)) => format!("{j}: {name}"),
            None => format!("{j}"),
        };
        let mut changed = false;
        egui::ComboBox::from_id_salt(("style of point", id))
            .selected_text(name(p.style))
            .show_ui(ui, |ui| {
                for j in 0..styles.len().max(p.style + 1) {
                    if ui.selectable_label(p.style == j, name(j)).clicked() && p.style != j {
                        p.style = j;
                        changed = true;
                    }
                }
            });
        changed
    };
    curve_editor(
        ui,
        id,
        "style transfer function",
        nodes,
        context,
        &look,
        &mut pick_style,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(value: f32, a: f32) -> ControlPoint {
        ControlPoint {
            value,
            rgba: [value / 255.0, 0.5, 0.5, a],
        }
    }

    #[test]
    fn the_plot_covers_the_points_and_the_context_range() {
        assert_eq!(
            plot_domain(&[p(10.0, 0.0), p(20.0, 1.0)], None),
            [10.0, 20.0]
        );
        assert_eq!(
            plot_domain(&[p(10.0, 0.0), p(20.0, 1.0)], Some([0.0, 255.0])),
            [0.0, 255.0]
        );
        assert_eq!(plot_domain(&[p(5.0, 0.0)], None), [5.0, 6.0]);
    }

    #[test]
    fn interpolation_is_linear_between_points_and_clamped_outside() {
        let points = [p(0.0, 0.0), p(100.0, 1.0)];
        let mid = interpolate(&points, 50.0);
        assert!((mid[3] - 0.5).abs() < 1e-6);
        assert_eq!(interpolate(&points, -5.0), points[0].rgba);
        assert_eq!(interpolate(&points, 500.0), points[1].rgba);
    }
}
