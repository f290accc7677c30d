//! The transfer-function editor: control points on an opacity curve over the data values, each
//! drawn in its colour above the resulting colour ramp (over a checkerboard, so opacity shows).
//!
//! Mouse: drag a point to move it (its value stays between its neighbours'), double-click on the
//! curve area to add a point, right-click a point to remove it, click a point to pick it for the
//! colour and number fields below the curve.

use egui::{Color32, Pos2, Rect, Sense, Stroke, Ui, Vec2};
use hatchery_data::transfer_function::{ControlPoint, TransferFunction1D};

/// Height of the curve area, points.
const HEIGHT: f32 = 140.0;
/// Radius of a control point's handle, points.
const HANDLE: f32 = 6.0;

/// What the editor remembers between frames (per node, in egui's memory).
#[derive(Clone, Copy, Default)]
struct Memory {
    selected: Option<usize>,
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
    fn handle(&self, p: &ControlPoint) -> Pos2 {
        Pos2::new(self.x(p.value), self.y(p.rgba[3]))
    }
}

/// The plotted value range: the points' range, widened to `context` (e.g. the volume's range).
pub fn plot_domain(points: &[ControlPoint], context: Option<[f32; 2]>) -> [f32; 2] {
    let mut lo = points.iter().map(|p| p.value).fold(f32::INFINITY, f32::min);
    let mut hi = points
        .iter()
        .map(|p| p.value)
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

/// Draws and edits `points` (strictly increasing values). Returns whether they changed.
pub fn tf_editor(
    ui: &mut Ui,
    id: egui::Id,
    points: &mut Vec<ControlPoint>,
    context: Option<[f32; 2]>,
) -> bool {
    let mut memory: Memory = ui.data(|d| d.get_temp(id).unwrap_or_default());
    let width = ui.available_width().max(120.0);
    let (rect, background) = ui.allocate_exact_size(Vec2::new(width, HEIGHT), Sense::click());
    background.widget_info(|| {
        egui::WidgetInfo::labeled(egui::WidgetType::Other, true, "transfer function curve")
    });
    let frame = Frame {
        rect,
        domain: plot_domain(points, context),
    };
    let painter = ui.painter_at(rect.expand(HANDLE));
    draw_ramp(&painter, &frame, points);

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
            let name = format!("transfer function point {}", i + 1);
            egui::WidgetInfo::labeled(egui::WidgetType::Other, true, name)
        });
        let response = response.on_hover_text(format!(
            "value {}, opacity {:.3}\ndrag to move, right-click to remove",
            points[i].value, points[i].rgba[3]
        ));
        if response.drag_started() || response.clicked() {
            memory.selected = Some(i);
        }
        if response.dragged()
            && let Some(pointer) = response.interact_pointer_pos()
        {
            // Keep values strictly increasing: a point stays between its neighbours.
            let span = frame.domain[1] - frame.domain[0];
            let gap = span * 1e-3;
            let lo = if i > 0 {
                points[i - 1].value + gap
            } else {
                f32::NEG_INFINITY
            };
            let hi = points
                .get(i + 1)
                .map_or(f32::INFINITY, |next| next.value - gap);
            let value = frame.value(pointer.x).clamp(lo, hi.max(lo));
            let alpha = frame.alpha(pointer.y);
            if value != points[i].value || alpha != points[i].rgba[3] {
                points[i].value = value;
                points[i].rgba[3] = alpha;
                changed = true;
            }
        }
        if response.secondary_clicked() && points.len() > 2 {
            remove = Some(i);
        }
        let [r, g, b, _] = points[i]
            .rgba
            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8);
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
        if points.iter().all(|p| p.value != value) {
            let mut rgba = interpolate(points, value);
            rgba[3] = frame.alpha(pointer.y);
            let at = points.partition_point(|p| p.value < value);
            points.insert(at, ControlPoint { value, rgba });
            memory.selected = Some(at);
            changed = true;
        }
    }
    background.on_hover_text("double-click to add a point");

    // Fields of the picked point.
    if let Some(i) = memory.selected.filter(|&i| i < points.len()) {
        ui.horizontal(|ui| {
            ui.label(format!("point {}", i + 1));
            let p = &mut points[i];
            let mut rgb = [p.rgba[0], p.rgba[1], p.rgba[2]];
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                p.rgba[..3].copy_from_slice(&rgb);
                changed = true;
            }
            ui.label("value");
            changed |= ui
                .add(egui::DragValue::new(&mut p.value).speed(0.5))
                .changed();
            ui.label("opacity");
            changed |= ui
                .add(
                    egui::DragValue::new(&mut p.rgba[3])
                        .range(0.0..=1.0)
                        .speed(0.005),
                )
                .changed();
        });
        // Typed values may break the order: sort, keeping the picked point picked.
        if !points.windows(2).all(|w| w[0].value < w[1].value) {
            let picked = points[i];
            points.sort_by(|a, b| a.value.total_cmp(&b.value));
            points.dedup_by(|b, a| a.value == b.value);
            memory.selected = points.iter().position(|p| *p == picked);
        }
    }
    ui.data_mut(|d| d.insert_temp(id, memory));
    changed
}

/// The colour ramp the points make, over a checkerboard, as vertical strips.
fn draw_ramp(painter: &egui::Painter, frame: &Frame, points: &[ControlPoint]) {
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
        let [r, g, b, a] = interpolate(points, value);
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
        TransferFunction1D::parse_points(points_text)
    } else {
        TransferFunction1D::preset(preset, range)
            .ok_or_else(|| format!("unknown preset `{preset}`"))
    }
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
