//! One frame of the editor: places the panels (menu bar, status line, inspector, viewport,
//! canvas: see [`crate::panels`]) in the window around the app's state ([`crate::app`]).

use crate::app::EditorApp;
use crate::panels::Panel as _;
use crate::panels::canvas::{self, Canvas};
use crate::panels::inspector::Inspector;
use crate::panels::menu::{self, MenuBar, StatusLine};
use crate::panels::viewport::Viewport;
use egui::Ui;

impl EditorApp {
    /// One frame of the whole editor.
    pub fn ui(&mut self, ui: &mut Ui) {
        self.guard_close(ui);
        menu::shortcuts(self, ui);
        // Custom shaders are re-read when their files change (a thread wakes us then).
        self.state.poll_watched_files();
        let watch = self
            .file_watch
            .get_or_insert_with(|| crate::file_watch::FileWatch::spawn(ui.ctx().clone()));
        watch.set(self.state.watched_stamps());
        if self.synced_revision != Some(self.state.revision()) {
            canvas::rebuild_snarl(self);
        }
        use crate::picture::Placement;
        let placement = self.picture.placement;
        if placement == Placement::FullWindow {
            egui::CentralPanel::default().show(ui, |ui| Viewport.show(self, ui));
        } else {
            egui::Panel::top("menu").show(ui, |ui| MenuBar.show(self, ui));
            egui::Panel::bottom("status").show(ui, |ui| StatusLine.show(self, ui));
            // The Inspector keeps its width when a node with a wide editor (the object table)
            // is selected: wide content scrolls sideways instead of pushing the picture and the
            // canvas over.
            // Panel widths are kept between runs (see crate::settings).
            let inspector = egui::Panel::right("inspector")
                .default_size(self.panel_width("inspector", 320.0))
                .show(ui, |ui| {
                    egui::ScrollArea::both()
                        .auto_shrink([false, false])
                        .show(ui, |ui| Inspector.show(self, ui));
                });
            self.panel_rects
                .insert("inspector", inspector.response.rect);
            if placement == Placement::Maximised {
                egui::CentralPanel::default().show(ui, |ui| Viewport.show(self, ui));
            } else {
                // The picture beside the canvas, in a panel the user can widen.
                let wide = (ui.max_rect().width() * 0.4).max(240.0);
                let picture = egui::Panel::right("viewport")
                    .resizable(true)
                    .default_size(self.panel_width("viewport", wide))
                    .show(ui, |ui| Viewport.show(self, ui));
                self.panel_rects.insert("viewport", picture.response.rect);
                egui::CentralPanel::default().show(ui, |ui| Canvas.show(self, ui));
            }
        }
        self.dropped_files(ui);
        self.apply_to_my_data();
        if let Some((purpose, path)) = self.picker.update(ui.ctx()) {
            self.picked(purpose, &path);
        }
        self.confirm_discard(ui);
        crate::frames::rename_window(ui.ctx(), &mut self.state);
        if self
            .export
            .show(ui.ctx(), self.state.doc(), &self.state.registry)
        {
            let graph = self.state.validate();
            let base = self.state.base_dir();
            self.export.start(graph, base.as_deref());
        }
        match self.export.poll() {
            Some(Ok(path)) => self.state.status = format!("exported {}", path.display()),
            Some(Err(e)) => self.state.status = format!("export failed: {e}"),
            None => {}
        }
        if self.layout.enabled() {
            for id in self.snarl_ids.keys() {
                if let Some(r) = self.node_screen_rect(id) {
                    self.layout.record(format!("node:{id}"), r);
                }
            }
            // A canvas point on no node (where a scripted right-click opens the palette).
            let canvas = self.canvas_rect.shrink(30.0);
            let empty = (0..40)
                .flat_map(|j| (0..40).map(move |i| (i, j)))
                .map(|(i, j)| canvas.lerp_inside(egui::vec2(i as f32 / 39.0, j as f32 / 39.0)))
                .find(|p| self.node_at(*p).is_none());
            if let Some(p) = empty {
                self.layout.record(
                    "canvas:empty".into(),
                    egui::Rect::from_center_size(p, egui::vec2(2.0, 2.0)),
                );
            }
            self.layout.flush(ui.ctx().pixels_per_point());
        }

        // A drag (of a slider, a node, ...) ends when the pointer is released.
        let busy = ui.input(|i| i.pointer.any_down()) || ui.ctx().egui_wants_keyboard_input();
        if !busy {
            self.state.end_group();
        }
        self.state.autosave();
        let title = self.state.title();
        if title != self.title {
            ui.ctx()
                .send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
    }
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        EditorApp::ui(self, ui);
    }

    fn on_exit(&mut self) {
        self.save_settings();
    }
}
