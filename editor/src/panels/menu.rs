//! The menu bar (File, Presets, Edit, View, Legend), the status line and the keyboard shortcuts.

use super::Panel;
use crate::app::{EditorApp, Pending, port_color};
use crate::files::{FileKind, Purpose};
use egui::{Color32, Key, Modifiers, Ui};
use hatchery_graph::PortType;
use std::path::PathBuf;

/// The menu bar at the top of the window.
pub struct MenuBar;

impl Panel for MenuBar {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("New").clicked() {
                    app.request(Pending::New);
                    ui.close();
                }
                if ui.button("Open…").clicked() {
                    let folder = app
                        .state
                        .base_dir()
                        .or_else(|| Some(app.presets_dir.clone()));
                    app.picker
                        .open(Purpose::OpenGraph, Some(FileKind::Graph), folder);
                    ui.close();
                }
                if ui.button("Export image…").clicked() {
                    app.export.open = true;
                    app.export.screen = app.preview.viewport.as_ref().map(|v| v.size());
                    if app.export.port.is_none() {
                        app.export.port = app.preview.chosen.clone().or_else(|| {
                            let doc = app.state.doc();
                            let saver = doc.nodes.iter().find(|n| n.kind == "SaveImage")?;
                            let edge = doc.edges.iter().find(|e| e.to.0 == saver.id)?;
                            Some(edge.from.clone())
                        });
                    }
                    ui.close();
                }
                if ui.button("Save as…").clicked() {
                    app.picker.open(
                        Purpose::SaveGraphAs,
                        Some(FileKind::Graph),
                        app.state.base_dir(),
                    );
                    ui.close();
                }
                ui.separator();
                ui.label("Path:");
                ui.text_edit_singleline(&mut app.file_field);
                ui.horizontal(|ui| {
                    if ui.button("Open").clicked() {
                        let path = PathBuf::from(app.file_field.trim());
                        app.request(Pending::Open(path));
                        ui.close();
                    }
                    if ui.button("Save").clicked() {
                        let _ = app.state.save();
                        ui.close();
                    }
                    if ui.button("Save as").clicked() {
                        let path = PathBuf::from(app.file_field.trim());
                        let _ = app.state.save_as(&path);
                        ui.close();
                    }
                });
            });
            ui.menu_button("Presets", |ui| {
                let dir = app.presets_dir.clone();
                let presets = app
                    .gallery
                    .get_or_insert_with(|| crate::gallery::list(&dir, &app.thumbnail_dir))
                    .clone();
                match crate::gallery::menu(ui, &presets, &mut app.thumbnails) {
                    Some(crate::gallery::Choice::Open(p)) => app.request(Pending::Open(p)),
                    Some(crate::gallery::Choice::Apply(p, input, kind)) => {
                        app.apply_after_open = Some((p.clone(), input, kind));
                        app.request(Pending::Open(p));
                    }
                    None => {}
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui
                    .add_enabled(app.state.can_undo(), egui::Button::new("Undo (Ctrl+Z)"))
                    .clicked()
                {
                    app.state.undo();
                }
                if ui
                    .add_enabled(
                        app.state.can_redo(),
                        egui::Button::new("Redo (Ctrl+Shift+Z)"),
                    )
                    .clicked()
                {
                    app.state.redo();
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Frame all (F)").clicked() {
                    app.frame_all = true;
                    ui.close();
                }
                if ui
                    .button("Arrange")
                    .on_hover_text("lay the graph out in columns by topological rank")
                    .clicked()
                {
                    app.arrange();
                    ui.close();
                }
            });
            ui.menu_button("Legend", |ui| {
                for ty in PortType::ALL {
                    ui.colored_label(port_color(ty), format!("● {ty}"));
                }
            });
            ui.label(app.state.title());
        });
    }
}

/// The status line at the bottom: the autosave offer, graph errors and the last message.
pub struct StatusLine;

impl Panel for StatusLine {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui) {
        ui.horizontal(|ui| {
            if app.offer_recovery {
                ui.colored_label(Color32::YELLOW, "An autosave of this graph exists.");
                if ui.button("Restore").clicked() {
                    let _ = app.state.restore_recovery();
                    app.offer_recovery = false;
                }
                if ui.button("Discard").clicked() {
                    app.state.discard_recovery();
                    app.offer_recovery = false;
                }
            }
            for e in app.state.graph_errors() {
                ui.colored_label(Color32::LIGHT_RED, e);
            }
            ui.label(&app.state.status);
        });
    }
}

/// The keyboard shortcuts, read before any panel is drawn.
pub(crate) fn shortcuts(app: &mut EditorApp, ui: &mut Ui) {
    let typing = ui.ctx().egui_wants_keyboard_input();
    let (redo, undo, save, quit) = ui.input_mut(|i| {
        let redo = i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z)
            || i.consume_key(Modifiers::COMMAND, Key::Y);
        let undo = i.consume_key(Modifiers::COMMAND, Key::Z);
        let save = i.consume_key(Modifiers::COMMAND, Key::S);
        let quit = i.consume_key(Modifiers::COMMAND, Key::Q);
        (redo, undo, save, quit)
    });
    // Ctrl+Q closes the window, asking first about unsaved changes (as its close button).
    if quit {
        app.request(Pending::Quit);
    }
    if redo {
        app.state.redo();
    } else if undo {
        app.state.undo();
    }
    if save {
        let _ = app.state.save();
    }
    if !typing && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::F)) {
        app.frame_all = true;
    }
    // Entering or leaving a group shows the view it had (see crate::settings::CanvasViews).
    crate::groups::shortcuts(&mut app.state, ui, typing);
    if !typing && ui.input_mut(|i| i.consume_key(Modifiers::COMMAND, Key::J)) {
        app.frame_selection();
    }
    // F11: the picture fills the window (again: back); Esc leaves that too.
    use crate::picture::Placement;
    if ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::F11)) {
        app.picture.placement = if app.picture.placement == Placement::FullWindow {
            Placement::Beside
        } else {
            Placement::FullWindow
        };
    }
    // Esc clears the selection unless a popup, menu or text field takes it.
    // (The add-node palette takes Esc itself: egui drops the keyboard focus on Esc before
    // this runs, so `typing` no longer says the palette's field had it.)
    let popup = egui::Popup::is_any_open(ui.ctx()) || app.add_menu.is_some();
    if !typing && !popup && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Escape)) {
        if app.picture.placement == Placement::FullWindow {
            app.picture.placement = Placement::Beside;
        } else {
            app.state.clear_selection();
        }
    }
    if !typing && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Delete)) {
        let ids: Vec<String> = app.state.selection.iter().cloned().collect();
        let _ = app.state.remove_nodes(&ids);
    }
}
