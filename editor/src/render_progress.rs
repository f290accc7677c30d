//! Render feedback on the picture itself while a newer one renders: the shown picture dimmed,
//! "rendering…" with the node running, the steps done of those planned and the time so far,
//! and a bar (8–18 s CPU-driver renders of volumes went unnoticed with a small grey label).

use egui::{Color32, Rect};
use hatchery_nodes::progress::PassProgress;
use std::time::Duration;

/// The lines drawn for `progress` (testable without a window): the heading, and what runs —
/// with the running node's duration the last time it ran (GPU work included) as the estimate of
/// how long it takes (the node runs again after an edit: a ray cast of seconds on a CPU driver).
pub fn caption(progress: Option<&(Duration, PassProgress)>) -> (String, Option<String>) {
    let Some((busy, pass)) = progress else {
        return ("rendering…".into(), None);
    };
    let heading = format!("rendering… {:.1} s", busy.as_secs_f64());
    let detail = pass.current.as_ref().map(|(node, since)| {
        let step = pass.done + 1;
        let estimate = pass
            .estimate
            .filter(|t| *t >= Duration::from_millis(100))
            .map_or(String::new(), |t| {
                format!(" of about {:.1} s", t.as_secs_f64())
            });
        format!(
            "{node} (step {step} of {}, {:.1} s{estimate})",
            pass.planned.len().max(step),
            since.elapsed().as_secs_f64()
        )
    });
    (heading, detail)
}

/// Dims `rect` and draws the caption and a bar of the steps done (the render thread asks for
/// a repaint when a node starts or ends; no timer, which would repaint the UI all the time).
pub fn draw(ui: &egui::Ui, rect: Rect, progress: Option<(Duration, PassProgress)>) {
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 0.0, Color32::from_black_alpha(120));
    let (heading, detail) = caption(progress.as_ref());
    painter.text(
        rect.center(),
        egui::Align2::CENTER_BOTTOM,
        heading,
        egui::FontId::proportional(22.0),
        Color32::WHITE,
    );
    if let Some(detail) = detail {
        painter.text(
            rect.center() + egui::vec2(0.0, 6.0),
            egui::Align2::CENTER_TOP,
            detail,
            egui::FontId::proportional(15.0),
            Color32::WHITE,
        );
    }
    if let Some((_, pass)) = &progress
        && !pass.planned.is_empty()
    {
        let width = (rect.width() * 0.5).min(320.0);
        let bar = Rect::from_center_size(
            rect.center() + egui::vec2(0.0, 40.0),
            egui::vec2(width, 6.0),
        );
        painter.rect_filled(bar, 3.0, Color32::from_white_alpha(60));
        let done = pass.done as f32 / pass.planned.len() as f32;
        let filled = Rect::from_min_size(bar.min, egui::vec2(width * done.min(1.0), 6.0));
        painter.rect_filled(filled, 3.0, Color32::WHITE);
    }
}
