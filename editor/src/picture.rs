//! How the rendered picture is shown: where (beside the canvas, maximised over it, or filling the
//! whole window) and a zoom/pan of the picture itself — to inspect hatching at pixel level —
//! that never touches the graph's camera.

use egui::{Rect, Vec2, pos2, vec2};

/// Where the picture is shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Placement {
    /// In a resizable panel beside the canvas.
    #[default]
    Beside,
    /// Instead of the canvas (menu, Inspector and status line stay).
    Maximised,
    /// The whole window (`F11`; `Esc` or `F11` leaves).
    FullWindow,
}

/// Zoom and pan of the picture (not of the scene).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PictureView {
    pub placement: Placement,
    /// 1 = the whole picture fits; 2 = each picture pixel twice as big, ...
    pub zoom: f32,
    /// The picture point (0..1 in both axes) shown at the centre of the view.
    pub centre: Vec2,
}

impl Default for PictureView {
    fn default() -> Self {
        PictureView {
            placement: Placement::Beside,
            zoom: 1.0,
            centre: vec2(0.5, 0.5),
        }
    }
}

/// The largest picture zoom (a picture pixel 64 screen pixels wide at most).
const MAX_ZOOM: f32 = 64.0;

impl PictureView {
    /// The part of the picture (texture coordinates) shown.
    pub fn uv_rect(&self) -> Rect {
        let half = 0.5 / self.zoom;
        Rect::from_min_max(
            pos2(self.centre.x - half, self.centre.y - half),
            pos2(self.centre.x + half, self.centre.y + half),
        )
    }

    pub fn is_zoomed(&self) -> bool {
        self.zoom > 1.0
    }

    /// Back to the whole picture.
    pub fn fit(&mut self) {
        self.zoom = 1.0;
        self.centre = vec2(0.5, 0.5);
    }

    /// Zooms by `factor` keeping the picture point under `at` (screen) in place; `shown` is where
    /// the picture is drawn.
    pub fn zoom_at(&mut self, factor: f32, at: egui::Pos2, shown: Rect) {
        let old = self.uv_rect();
        let t = (at - shown.min) / shown.size();
        let under = vec2(
            old.min.x + t.x * old.width(),
            old.min.y + t.y * old.height(),
        );
        self.zoom = (self.zoom * factor).clamp(1.0, MAX_ZOOM);
        let half = 0.5 / self.zoom;
        // Keep `under` at the same screen fraction t.
        self.centre = under + vec2((0.5 - t.x) * 2.0 * half, (0.5 - t.y) * 2.0 * half);
        self.clamp();
    }

    /// Moves the picture with the pointer by `delta` screen points over `shown`.
    pub fn pan(&mut self, delta: Vec2, shown: Rect) {
        let uv = self.uv_rect();
        self.centre -= vec2(
            delta.x / shown.width() * uv.width(),
            delta.y / shown.height() * uv.height(),
        );
        self.clamp();
    }

    fn clamp(&mut self) {
        let half = 0.5 / self.zoom;
        self.centre.x = self.centre.x.clamp(half, 1.0 - half);
        self.centre.y = self.centre.y.clamp(half, 1.0 - half);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zoom_keeps_the_point_under_the_pointer() {
        let shown = Rect::from_min_size(pos2(100.0, 50.0), vec2(400.0, 300.0));
        let mut v = PictureView::default();
        let at = pos2(200.0, 125.0); // a quarter across, a quarter down
        v.zoom_at(4.0, at, shown);
        let uv = v.uv_rect();
        let t = (at - shown.min) / shown.size();
        let under = pos2(uv.min.x + t.x * uv.width(), uv.min.y + t.y * uv.height());
        assert!((under - pos2(0.25, 0.25)).length() < 1e-5, "{under:?}");
        assert_eq!(v.zoom, 4.0);
        // Panning never leaves the picture.
        v.pan(vec2(10_000.0, 0.0), shown);
        assert!(v.uv_rect().min.x >= 0.0 && v.uv_rect().max.x <= 1.0 + 1e-6);
        v.fit();
        assert_eq!(
            v.uv_rect(),
            Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0))
        );
    }
}
