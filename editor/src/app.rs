//! The egui application: menu bar, snarl canvas (a view rebuilt from the document), inspector,
//! viewport and status line.

use crate::files::{FileKind, FilePicker, Purpose};
use crate::preview::{Preview, Shown};
use crate::render_worker::{NodeTime, Port};
use crate::selection::{CanvasSelection, SelectionChange};
use crate::state::EditorState;
use egui::{Color32, Id, Key, Modifiers, Pos2, Ui};
use egui_snarl::ui::{AnyPins, PinInfo, SnarlPin, SnarlViewer, SnarlWidget};
use egui_snarl::{InPin, NodeId, OutPin, Snarl};
use hatchery_graph::{EditorPos, ParamKind, ParamSpec, ParamValue, PortType};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// One colour per port type (also the legend).
pub fn port_color(ty: PortType) -> Color32 {
    match ty {
        PortType::Volume => Color32::from_rgb(230, 160, 60),
        PortType::Labels => Color32::from_rgb(200, 110, 40),
        PortType::Mesh => Color32::from_rgb(90, 180, 90),
        PortType::Camera => Color32::from_rgb(80, 150, 230),
        PortType::Light => Color32::from_rgb(240, 220, 90),
        PortType::GBuffer => Color32::from_rgb(150, 100, 220),
        PortType::Image => Color32::from_rgb(230, 90, 120),
        PortType::Mask => Color32::from_rgb(180, 180, 180),
        PortType::TransferFunction => Color32::from_rgb(60, 200, 200),
        PortType::StyleSet => Color32::from_rgb(220, 120, 220),
        PortType::ObjectStyles => Color32::from_rgb(140, 200, 120),
        PortType::Importance => Color32::from_rgb(250, 130, 60),
        PortType::Annotations => Color32::from_rgb(120, 120, 240),
        PortType::Strokes => Color32::from_rgb(90, 90, 90),
    }
}

fn pos(p: Pos2) -> EditorPos {
    EditorPos { x: p.x, y: p.y }
}

pub struct EditorApp {
    pub state: EditorState,
    pub preview: Preview,
    /// Render the viewport (tests that only edit turn it off).
    pub preview_enabled: bool,
    /// Where the viewport image was drawn last frame (screen points; tests drag in it).
    pub viewport_rect: egui::Rect,
    /// Folder listed in the Presets menu.
    pub presets_dir: PathBuf,
    /// The path field of the File menu.
    pub file_field: String,
    snarl: Snarl<String>,
    snarl_ids: BTreeMap<String, NodeId>,
    /// Where the canvas put each node at the last rebuild or move (nodes without a stored
    /// position get a grid place, written to the document only when moved).
    pub(crate) placed: BTreeMap<String, Pos2>,
    synced_revision: Option<u64>,
    /// Selection by the mouse (see [`crate::selection`]).
    pub(crate) selecting: CanvasSelection,
    /// A frame being dragged by its title bar (see [`crate::frames`]).
    pub(crate) frame_drag: Option<crate::frames::FrameDrag>,
    /// *File → Export image…*.
    pub export: crate::export_dialog::ExportDialog,
    /// Where the picture is shown and its own zoom/pan.
    pub picture: crate::picture::PictureView,
    /// The canvas's screen rectangle last frame.
    pub canvas_rect: egui::Rect,
    /// Screen positions for scripted checks (off unless asked for).
    layout: crate::layout_dump::LayoutDump,
    /// The add-node palette, while open (see [`crate::add_menu`]).
    pub add_menu: Option<crate::add_menu::Palette>,
    clipboard: String,
    /// Why the last wire drop was refused, where and when (shown as a tooltip for a while).
    pub refusal: Option<Refusal>,
    style_thumbnails: crate::style_picker::Thumbnails,
    /// The file dialog (path parameters, Open…, Save as…).
    pub picker: FilePicker,
    title: String,
    offer_recovery: bool,
    /// Fit every node into the canvas on the next frame.
    pub frame_all: bool,
    /// The picture shown is being replaced by a render in progress (drawn dimmed).
    pub picture_stale: bool,
    /// The Data panel's input rows last frame (screen points): drop targets.
    pub data_rows: Vec<(String, egui::Rect)>,
    /// The Presets menu's presets (read when it first opens) and their thumbnails.
    gallery: Option<Vec<crate::gallery::PresetInfo>>,
    thumbnails: crate::gallery::Thumbnails,
    /// Where preset thumbnails are cached (see [`crate::gallery`]).
    pub thumbnail_dir: PathBuf,
    /// *Apply to my data…*: once this preset is open, ask for a file for this input (name, type).
    apply_after_open: Option<(PathBuf, String, String)>,
    /// Wakes the UI when a custom shader's file changes.
    file_watch: Option<crate::file_watch::FileWatch>,
    /// Frame once more when every node has been drawn (their sizes are known then).
    frame_all_again: bool,
    /// The canvas's graph → screen transform of the last frame.
    pub canvas_transform: egui::emath::TSTransform,
    /// An action that would discard unsaved changes, waiting for the user's answer.
    pending: Option<Pending>,
    /// The user agreed to close the window with unsaved changes.
    quitting: bool,
}

/// A refused wire: the reason, shown next to the pointer until `until` (egui time, seconds).
#[derive(Clone, Debug)]
pub struct Refusal {
    pub reason: String,
    pub at: Pos2,
    pub until: f64,
}

/// Node titles are drawn at egui's body size (13 points at zoom 1).
const TITLE_FONT_PX: f32 = 13.0;
/// The smallest title height *Frame all* zooms out to.
pub const LEGIBLE_TITLE_PX: f32 = 11.0;

/// The widest an error or warning line makes a node's body (points at zoom 1); the body sits
/// between the input and output pins.
const NODE_MESSAGE_WIDTH: f32 = 120.0;

/// How long a refusal tooltip stays up, seconds.
const REFUSAL_SECONDS: f64 = 4.0;

/// Actions that replace the document and so ask first when it has unsaved changes.
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    Open(PathBuf),
    New,
    /// Closing the window.
    Quit,
}

const SNARL_ID: &str = "hatchery-snarl";

impl Default for EditorApp {
    fn default() -> Self {
        Self::new(EditorState::new())
    }
}

impl EditorApp {
    pub fn new(state: EditorState) -> Self {
        let presets_dir = ["graphs", concat!(env!("CARGO_MANIFEST_DIR"), "/../graphs")]
            .iter()
            .map(PathBuf::from)
            .find(|p| p.is_dir())
            .unwrap_or_else(|| PathBuf::from("graphs"));
        let offer_recovery = state.has_recovery();
        EditorApp {
            file_field: state
                .path()
                .map_or(String::new(), |p| p.display().to_string()),
            state,
            preview: Preview::default(),
            preview_enabled: true,
            viewport_rect: egui::Rect::NOTHING,
            presets_dir,
            snarl: Snarl::new(),
            snarl_ids: BTreeMap::new(),
            placed: BTreeMap::new(),
            synced_revision: None,
            selecting: CanvasSelection::default(),
            frame_drag: None,
            layout: crate::layout_dump::LayoutDump::from_env(),
            export: Default::default(),
            picture: Default::default(),
            canvas_rect: egui::Rect::NOTHING,
            add_menu: None,
            clipboard: String::new(),
            refusal: None,
            style_thumbnails: Default::default(),
            picker: FilePicker::default(),
            title: String::new(),
            offer_recovery,
            pending: None,
            quitting: false,
            frame_all: true,
            picture_stale: false,
            data_rows: Vec::new(),
            gallery: None,
            thumbnails: Default::default(),
            thumbnail_dir: crate::gallery::cache_dir(),
            apply_after_open: None,
            file_watch: None,
            frame_all_again: false,
            canvas_transform: egui::emath::TSTransform::IDENTITY,
        }
    }

    /// An editor inside eframe: previews render on the window's wgpu device when that is a good
    /// idea (see [`crate::preview::share_device_by_default`]).
    pub fn with_creation_context(state: EditorState, cc: &eframe::CreationContext<'_>) -> Self {
        let mut app = Self::new(state);
        if let Some(rs) = &cc.wgpu_render_state {
            let share = crate::preview::share_device_by_default(&rs.adapter.get_info());
            app.preview.set_render_state(rs.clone(), share);
        }
        app
    }

    /// Opens a file (a bad file leaves the current graph and reports why in the status line).
    pub fn open(&mut self, path: &Path) {
        match self.state.open(path) {
            Ok(()) => {
                self.file_field = path.display().to_string();
                self.preview.chosen = None;
                // The previous graph's picture is not this one's: nothing until it renders.
                self.preview.viewport = None;
                self.offer_recovery = self.state.has_recovery();
            }
            Err(e) => self.state.status = e,
        }
    }

    /// Opens a file or starts a new graph, asking first if that would discard unsaved changes.
    pub fn request(&mut self, action: Pending) {
        if self.state.is_dirty() {
            self.pending = Some(action);
        } else {
            self.perform(action);
        }
    }

    /// The action waiting for confirmation, if any.
    pub fn pending(&self) -> Option<&Pending> {
        self.pending.as_ref()
    }

    fn perform(&mut self, action: Pending) {
        match action {
            Pending::Open(path) => self.open(&path),
            Pending::Quit => self.quitting = true,
            Pending::New => {
                let scratch = self.state.scratch_dir.clone();
                self.state = EditorState::new();
                self.state.scratch_dir = scratch;
                self.file_field.clear();
                self.preview.chosen = None;
                self.offer_recovery = false;
            }
        }
    }

    fn confirm_discard(&mut self, ui: &mut Ui) {
        let Some(action) = self.pending.clone() else {
            return;
        };
        egui::Window::new("Unsaved changes")
            .collapsible(false)
            .resizable(false)
            .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
            .show(ui.ctx(), |ui| {
                ui.label("The graph has unsaved changes.");
                ui.horizontal(|ui| {
                    // Save needs a file to save to; an untitled graph is saved with File → Save as….
                    let can_save = self.state.path().is_some();
                    let save = ui
                        .add_enabled(can_save, egui::Button::new("Save"))
                        .on_disabled_hover_text("untitled: use File → Save as… first");
                    if save.clicked() {
                        match self.state.save() {
                            Ok(()) => {
                                self.pending = None;
                                self.perform(action.clone());
                            }
                            Err(e) => self.state.status = e,
                        }
                    }
                    if ui.button("Discard changes").clicked() {
                        self.pending = None;
                        // Discarded on purpose: no autosave should offer them back.
                        self.state.discard_recovery();
                        self.perform(action.clone());
                    }
                    if ui.button("Cancel").clicked() {
                        self.pending = None;
                    }
                });
            });
    }

    /// The snarl node showing graph node `id`, if any.
    pub fn snarl_node(&self, id: &str) -> Option<NodeId> {
        self.snarl_ids.get(id).copied()
    }

    /// Lays the graph out in columns by rank, with the drawn node sizes (one undo step), and
    /// frames it.
    pub fn arrange(&mut self) {
        // What the canvas shows: the groups as nodes, or the inside of the group entered.
        let shown =
            crate::groups::shown_doc(self.state.doc(), &self.state.registry, self.state.level());
        let positions = crate::arrange::layered_layout(&shown, &self.selecting.sizes());
        self.state.move_nodes(&positions);
        self.frame_all = true;
    }

    /// Where node `id` was drawn last frame (screen points), if it was.
    pub fn node_screen_rect(&self, id: &str) -> Option<egui::Rect> {
        self.selecting.node_rect(self.canvas_transform, id)
    }

    /// The topmost node drawn at a screen position last frame.
    pub fn node_at(&self, at: Pos2) -> Option<&str> {
        self.selecting.node_at(self.canvas_transform, at)
    }

    /// Rebuilds the canvas from the document (Snarl is only a view of it) at the current level
    /// (see [`crate::groups`]).
    fn rebuild_snarl(&mut self) {
        let mut snarl = Snarl::new();
        let mut ids = BTreeMap::new();
        let mut placed = BTreeMap::new();
        let doc = self.state.doc();
        for (i, (id, at)) in crate::groups::shown_nodes(doc, self.state.level())
            .into_iter()
            .enumerate()
        {
            let at = at.map_or_else(
                || Pos2::new(240.0 * (i % 5) as f32, 160.0 * (i / 5) as f32),
                |p| Pos2::new(p.x, p.y),
            );
            placed.insert(id.clone(), at);
            ids.insert(id.clone(), snarl.insert_node(at, id));
        }
        for ((from, o), (to, i)) in
            crate::groups::shown_wires(doc, &self.state.registry, self.state.level())
        {
            if let (Some(&from), Some(&to)) = (ids.get(&from), ids.get(&to)) {
                snarl.connect(
                    egui_snarl::OutPinId {
                        node: from,
                        output: o,
                    },
                    egui_snarl::InPinId { node: to, input: i },
                );
            }
        }
        self.snarl = snarl;
        self.snarl_ids = ids;
        self.placed = placed;
        self.synced_revision = Some(self.state.revision());
    }

    /// One frame of the whole editor.
    pub fn ui(&mut self, ui: &mut Ui) {
        self.guard_close(ui);
        self.shortcuts(ui);
        // Custom shaders are re-read when their files change (a thread wakes us then).
        self.state.poll_watched_files();
        let watch = self
            .file_watch
            .get_or_insert_with(|| crate::file_watch::FileWatch::spawn(ui.ctx().clone()));
        watch.set(self.state.watched_files());
        if self.synced_revision != Some(self.state.revision()) {
            self.rebuild_snarl();
        }
        use crate::picture::Placement;
        let placement = self.picture.placement;
        if placement == Placement::FullWindow {
            egui::CentralPanel::default().show(ui, |ui| self.viewport(ui));
        } else {
            egui::Panel::top("menu").show(ui, |ui| self.menu_bar(ui));
            egui::Panel::bottom("status").show(ui, |ui| self.status_line(ui));
            // The Inspector keeps its width when a node with a wide editor (the object table)
            // is selected: wide content scrolls sideways instead of pushing the picture and the
            // canvas over.
            egui::Panel::right("inspector")
                .default_size(320.0)
                .show(ui, |ui| {
                    egui::ScrollArea::both()
                        .auto_shrink([false, false])
                        .show(ui, |ui| self.inspector(ui));
                });
            if placement == Placement::Maximised {
                egui::CentralPanel::default().show(ui, |ui| self.viewport(ui));
            } else {
                // The picture beside the canvas, in a panel the user can widen.
                let wide = (ui.max_rect().width() * 0.4).max(240.0);
                egui::Panel::right("viewport")
                    .resizable(true)
                    .default_size(wide)
                    .show(ui, |ui| self.viewport(ui));
                egui::CentralPanel::default().show(ui, |ui| self.canvas(ui));
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

    /// Closing the window with unsaved changes asks first (the autosave covers crashes only).
    fn guard_close(&mut self, ui: &Ui) {
        if self.quitting {
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        if ui.input(|i| i.viewport().close_requested()) && self.state.is_dirty() {
            ui.ctx()
                .send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.pending = Some(Pending::Quit);
        }
    }

    fn shortcuts(&mut self, ui: &mut Ui) {
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
            self.request(Pending::Quit);
        }
        if redo {
            self.state.redo();
        } else if undo {
            self.state.undo();
        }
        if save {
            let _ = self.state.save();
        }
        if !typing && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::F)) {
            self.frame_all = true;
        }
        let level = self.state.level().map(str::to_owned);
        crate::groups::shortcuts(&mut self.state, ui, typing);
        if self.state.level() != level.as_deref() {
            self.frame_all = true;
        }
        if !typing && ui.input_mut(|i| i.consume_key(Modifiers::COMMAND, Key::J)) {
            self.frame_selection();
        }
        // F11: the picture fills the window (again: back); Esc leaves that too.
        use crate::picture::Placement;
        if ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::F11)) {
            self.picture.placement = if self.picture.placement == Placement::FullWindow {
                Placement::Beside
            } else {
                Placement::FullWindow
            };
        }
        // Esc clears the selection unless a popup, menu or text field takes it.
        // (The add-node palette takes Esc itself: egui drops the keyboard focus on Esc before
        // this runs, so `typing` no longer says the palette's field had it.)
        let popup = egui::Popup::is_any_open(ui.ctx()) || self.add_menu.is_some();
        if !typing && !popup && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Escape)) {
            if self.picture.placement == Placement::FullWindow {
                self.picture.placement = Placement::Beside;
            } else {
                self.state.clear_selection();
            }
        }
        if !typing && ui.input_mut(|i| i.consume_key(Modifiers::NONE, Key::Delete)) {
            let ids: Vec<String> = self.state.selection.iter().cloned().collect();
            let _ = self.state.remove_nodes(&ids);
        }
    }

    fn menu_bar(&mut self, ui: &mut Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("New").clicked() {
                    self.request(Pending::New);
                    ui.close();
                }
                if ui.button("Open…").clicked() {
                    let folder = self
                        .state
                        .base_dir()
                        .or_else(|| Some(self.presets_dir.clone()));
                    self.picker
                        .open(Purpose::OpenGraph, Some(FileKind::Graph), folder);
                    ui.close();
                }
                if ui.button("Export image…").clicked() {
                    self.export.open = true;
                    if self.export.port.is_none() {
                        self.export.port = self.preview.chosen.clone().or_else(|| {
                            let doc = self.state.doc();
                            let saver = doc.nodes.iter().find(|n| n.kind == "SaveImage")?;
                            let edge = doc.edges.iter().find(|e| e.to.0 == saver.id)?;
                            Some(edge.from.clone())
                        });
                    }
                    ui.close();
                }
                if ui.button("Save as…").clicked() {
                    self.picker.open(
                        Purpose::SaveGraphAs,
                        Some(FileKind::Graph),
                        self.state.base_dir(),
                    );
                    ui.close();
                }
                ui.separator();
                ui.label("Path:");
                ui.text_edit_singleline(&mut self.file_field);
                ui.horizontal(|ui| {
                    if ui.button("Open").clicked() {
                        let path = PathBuf::from(self.file_field.trim());
                        self.request(Pending::Open(path));
                        ui.close();
                    }
                    if ui.button("Save").clicked() {
                        let _ = self.state.save();
                        ui.close();
                    }
                    if ui.button("Save as").clicked() {
                        let path = PathBuf::from(self.file_field.trim());
                        let _ = self.state.save_as(&path);
                        ui.close();
                    }
                });
            });
            ui.menu_button("Presets", |ui| {
                let dir = self.presets_dir.clone();
                let presets = self
                    .gallery
                    .get_or_insert_with(|| crate::gallery::list(&dir, &self.thumbnail_dir))
                    .clone();
                match crate::gallery::menu(ui, &presets, &mut self.thumbnails) {
                    Some(crate::gallery::Choice::Open(p)) => self.request(Pending::Open(p)),
                    Some(crate::gallery::Choice::Apply(p, input, kind)) => {
                        self.apply_after_open = Some((p.clone(), input, kind));
                        self.request(Pending::Open(p));
                    }
                    None => {}
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui
                    .add_enabled(self.state.can_undo(), egui::Button::new("Undo (Ctrl+Z)"))
                    .clicked()
                {
                    self.state.undo();
                }
                if ui
                    .add_enabled(
                        self.state.can_redo(),
                        egui::Button::new("Redo (Ctrl+Shift+Z)"),
                    )
                    .clicked()
                {
                    self.state.redo();
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Frame all (F)").clicked() {
                    self.frame_all = true;
                    ui.close();
                }
                if ui
                    .button("Arrange")
                    .on_hover_text("lay the graph out in columns by topological rank")
                    .clicked()
                {
                    self.arrange();
                    ui.close();
                }
            });
            ui.menu_button("Legend", |ui| {
                for ty in PortType::ALL {
                    ui.colored_label(port_color(ty), format!("● {ty}"));
                }
            });
            ui.label(self.state.title());
        });
    }

    fn status_line(&mut self, ui: &mut Ui) {
        ui.horizontal(|ui| {
            if self.offer_recovery {
                ui.colored_label(Color32::YELLOW, "An autosave of this graph exists.");
                if ui.button("Restore").clicked() {
                    let _ = self.state.restore_recovery();
                    self.offer_recovery = false;
                }
                if ui.button("Discard").clicked() {
                    self.state.discard_recovery();
                    self.offer_recovery = false;
                }
            }
            for e in self.state.graph_errors() {
                ui.colored_label(Color32::LIGHT_RED, e);
            }
            ui.label(&self.state.status);
        });
    }

    fn canvas(&mut self, ui: &mut Ui) {
        if crate::groups::level_bar(&self.state, ui) {
            self.state.exit_group();
            self.frame_all = true;
        }
        let widget = SnarlWidget::new().id(Id::new(SNARL_ID));
        let failed = self.preview.failed_node.clone();
        let frame_into =
            std::mem::take(&mut self.frame_all).then(|| ui.available_rect_before_wrap());
        // Node sizes as drawn last frame, for framing (before this frame's are recorded).
        let node_sizes = self.selecting.sizes();
        if frame_into.is_some() && node_sizes.len() < self.snarl_ids.len() {
            // Not all nodes drawn yet (the first frame): frame again once they are.
            self.frame_all_again = true;
        } else if frame_into.is_none() && std::mem::take(&mut self.frame_all_again) {
            self.frame_all = true;
        }
        let mut thumbnails: BTreeMap<Port, Result<(egui::TextureId, egui::Vec2), String>> = self
            .preview
            .thumbnails
            .iter()
            .map(|(port, shown)| (port.clone(), Ok((shown.id(), thumbnail_size(shown)))))
            .collect();
        for (port, e) in &self.preview.thumbnail_errors {
            thumbnails.insert(port.clone(), Err(e.clone()));
        }
        self.selecting.begin_frame();
        let mut frame_request = false;
        // The wheel over the canvas (not over a popup or the palette) zooms it.
        let pointer = ui.input(|i| i.pointer.latest_pos());
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        let wheel_zoom = pointer
            .filter(|&at| {
                scroll != 0.0
                    && !ui.input(|i| i.modifiers.shift || i.modifiers.command)
                    && ui.available_rect_before_wrap().contains(at)
                    && self.add_menu.is_none()
                    && ui
                        .ctx()
                        .layer_id_at(at)
                        .is_none_or(|l| l.order == egui::Order::Background)
            })
            .map(|at| (scroll, at));
        let mut viewer = Viewer {
            frame_into,
            node_sizes,
            transform: self.canvas_transform,
            selecting: &mut self.selecting,
            state: &mut self.state,
            add_menu: &mut self.add_menu,
            clipboard: &mut self.clipboard,
            preview: &mut self.preview.chosen,
            pins: &mut self.preview.pins,
            thumbnails,
            times: self.preview.show_times.then_some(&self.preview.times),
            refused: None,
            warnings: self.preview.warnings.clone(),
            failed,
            frame_request: &mut frame_request,
            wheel_zoom,
        };

        // Dragging a node's title moves the node instead of selecting its text.
        ui.style_mut().interaction.selectable_labels = false;
        // Snarl sees no modifiers, so its own (Shift-click) selection never starts: the editor
        // owns selection (see crate::selection).
        let modifiers = ui.input(|i| i.modifiers);
        ui.ctx().input_mut(|i| i.modifiers = Modifiers::NONE);
        let canvas_rect = ui.available_rect_before_wrap();
        self.canvas_rect = canvas_rect;
        widget.show(&mut self.snarl, &mut viewer, ui);
        ui.ctx().input_mut(|i| i.modifiers = modifiers);
        self.canvas_transform = viewer.transform;
        let refused = viewer.refused.take();
        if frame_request {
            self.frame_selection();
        }
        let free = ui
            .input(|i| i.pointer.interact_pos())
            .is_some_and(|p| ui.ctx().layer_id_at(p).is_none_or(|l| l == ui.layer_id()));
        let over_canvas = ui
            .input(|i| i.pointer.interact_pos())
            .is_some_and(|p| free && canvas_rect.contains(p));
        let dragging_frame = self.drag_frames(ui.ctx(), over_canvas);
        let change = if dragging_frame {
            None
        } else {
            self.selecting.update(
                ui.ctx(),
                canvas_rect,
                free,
                self.canvas_transform,
                modifiers,
            )
        };
        match change {
            Some(SelectionChange::Click { node, mode }) => self.state.select_click(&node, mode),
            Some(SelectionChange::ClickEmpty) if modifiers.is_none() => {
                self.state.clear_selection()
            }
            Some(SelectionChange::Box { nodes, add }) => self.state.select_box(&nodes, add),
            _ => {}
        }
        if let Some(reason) = refused {
            let now = ui.input(|i| i.time);
            let at = ui
                .input(|i| i.pointer.latest_pos())
                .unwrap_or_else(|| ui.max_rect().center());
            self.refusal = Some(Refusal {
                reason,
                at,
                until: now + REFUSAL_SECONDS,
            });
        }
        self.refusal_tooltip(ui);
        let clipboard = self.clipboard.clone();
        for (name, r) in
            crate::add_menu::show(ui.ctx(), &mut self.add_menu, &mut self.state, &clipboard)
        {
            self.layout.record(name, r);
        }
        let changed_by_viewer = self.synced_revision != Some(self.state.revision());

        // Node moves: written back to the document (one undo step per drag).
        if !changed_by_viewer {
            let moved: Vec<(String, Pos2)> = self
                .snarl
                .nodes_pos()
                .filter_map(|(p, id)| {
                    let old = *self.placed.get(id)?;
                    (old.distance(p) > 0.25).then(|| (id.clone(), p))
                })
                .collect();
            // Dragging one selected node carries the rest of the selection along.
            let mut moved = moved;
            if let [(dragged, to)] = moved.clone().as_slice()
                && self.state.selection.contains(dragged)
                && let Some(&from) = self.placed.get(dragged)
            {
                let delta = *to - from;
                for other in &self.state.selection {
                    if other == dragged {
                        continue;
                    }
                    let (Some(&n), Some(&at)) = (self.snarl_ids.get(other), self.placed.get(other))
                    else {
                        continue;
                    };
                    if let Some(info) = self.snarl.get_node_info_mut(n) {
                        info.pos = at + delta;
                        moved.push((other.clone(), at + delta));
                    }
                }
            }
            for (id, p) in moved {
                self.state.move_node(&id, pos(p));
                self.placed.insert(id, p);
            }
            // The canvas already shows these positions: no rebuild needed.
            self.synced_revision = Some(self.state.revision());
        }
    }

    fn inspector(&mut self, ui: &mut Ui) {
        self.data_rows = crate::data_panel::show(&mut self.state, ui, &mut self.picker);
        for (name, rect) in &self.data_rows {
            self.layout.record(format!("input:{name}"), *rect);
        }
        ui.separator();
        ui.heading("Inspector");
        let Some(id) = self.state.inspected().map(str::to_owned) else {
            ui.label("Click a node to edit its parameters.");
            return;
        };
        if crate::groups::inspector(&mut self.state, ui, &id) {
            self.frame_all |= self.state.level().is_some();
            return;
        }
        if self.state.selection.len() > 1 {
            ui.weak(format!(
                "{} nodes selected; showing the last clicked",
                self.state.selection.len()
            ));
        }
        let Some(node) = self.state.doc().nodes.iter().find(|n| n.id == id).cloned() else {
            return;
        };
        ui.label(format!("{} ({})", node.id, node.kind));
        if let Some(e) = self.state.node_error(&id) {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        let doc = self.state.doc();
        let Some(schema) =
            hatchery_graph::node_schema(&self.state.registry, doc, &node).map(|s| (*s).clone())
        else {
            ui.label("unknown kind: no parameters to show");
            return;
        };
        ui.label(schema.doc).on_hover_text(schema.category);
        // Editors for the parameters that are more than a number.
        match node.kind.as_str() {
            "TransferFunction1D" => self.transfer_function_section(ui, &id, &node),
            "StyleTransferFunction" => self.style_function_section(ui, &id, &node),
            "StyleSet" => self.styles_section(ui, &id, &node),
            "ObjectStyles" => self.object_styles_section(ui, &id, &node),
            _ => {}
        }
        egui::Grid::new("params").num_columns(3).show(ui, |ui| {
            for spec in &schema.params {
                let current = node
                    .params
                    .get(spec.name)
                    .and_then(|raw| spec.convert(raw).ok())
                    .unwrap_or_else(|| spec.default.clone());
                ui.label(spec.name).on_hover_text(spec.doc);
                let resolved = self
                    .preview
                    .resolved
                    .get(&id)
                    .and_then(|r| r.get(spec.name))
                    .cloned();
                let widget = ui.scope(|ui| {
                    if spec.relative {
                        crate::relative_value::widget(ui, spec, &current, resolved.as_deref())
                    } else {
                        (param_widget(ui, spec, &current), egui::Rect::NOTHING)
                    }
                });
                // Where its value is typed (a relative value's row also has a form menu).
                let (value, field) = widget.inner;
                let rect = if field.is_positive() {
                    field
                } else {
                    widget.response.rect
                };
                self.layout.record(format!("param:{}", spec.name), rect);
                let widget = egui::InnerResponse::new(value, widget.response);
                if let Some(value) = widget.inner {
                    let dragging =
                        ui.input(|i| i.pointer.any_down()) || ui.ctx().egui_wants_keyboard_input();
                    let _ = self.state.set_param(&id, spec.name, value, dragging);
                }
                // A third column: the file dialog button of path parameters.
                if spec.kind == ParamKind::Path
                    && ui
                        .button("📂")
                        .on_hover_text(format!("choose {} with the file dialog", spec.name))
                        .clicked()
                {
                    self.choose_path(&node, spec.name, &current);
                }
                ui.end_row();
            }
        });
        // Values of parameters the node's file no longer declares (a renamed shader uniform):
        // kept, unused, until removed here.
        let stale: Vec<String> = node
            .params
            .keys()
            .filter(|k| schema.param(k).is_none())
            .cloned()
            .collect();
        if !stale.is_empty() {
            ui.separator();
            ui.label("Not declared by the shader any more (kept, unused):");
            for name in stale {
                ui.horizontal(|ui| {
                    ui.label(&name);
                    if ui.button("✕ Remove").clicked() {
                        let node_id = id.clone();
                        let _ = self.state.apply(None, |d, _| {
                            if let Some(n) = d.nodes.iter_mut().find(|n| n.id == node_id) {
                                n.params.remove(&name);
                            }
                            Ok(())
                        });
                    }
                });
            }
        }
    }

    /// Opens the file dialog for a path parameter, in the folder of its current file.
    fn choose_path(&mut self, node: &hatchery_graph::NodeDoc, param: &str, current: &ParamValue) {
        let base = self.state.base_dir();
        let folder = match current {
            ParamValue::Path(p) if !p.is_empty() => {
                let p = PathBuf::from(p);
                let p = match &base {
                    Some(b) if p.is_relative() => b.join(p),
                    _ => p,
                };
                p.parent().map(Path::to_path_buf)
            }
            _ => None,
        }
        .filter(|folder| folder.is_dir())
        .or(base);
        let kind = match node.kind.as_str() {
            "VolumeFile" => Some(FileKind::Volume),
            "MeshFile" => Some(FileKind::Mesh),
            "CustomShader" => Some(FileKind::Shader),
            _ => None,
        };
        let purpose = Purpose::Param {
            node: node.id.clone(),
            param: param.to_owned(),
        };
        self.picker.open(purpose, kind, folder);
    }

    /// The text of a point list as a curve editor draws it: as written when every value is a
    /// number; with values relative to the data (`range(30/255): …`) as the last render
    /// resolved them (`None` before it ran). Editing the curve then writes numbers.
    fn resolved_text(&self, node: &str, param: &str, written: String) -> Option<String> {
        let relative = written.split(';').any(|e| {
            e.split_once(':')
                .is_some_and(|(v, _)| !v.trim().is_empty() && v.trim().parse::<f32>().is_err())
        });
        if !relative {
            return Some(written);
        }
        self.preview.resolved.get(node)?.get(param).cloned()
    }

    /// *Apply to my data…*: the preset is open, ask for the file of its main input; forget the
    /// request if opening it was cancelled.
    fn apply_to_my_data(&mut self) {
        let Some((path, input, kind)) = self.apply_after_open.clone() else {
            return;
        };
        if self.state.path() == Some(path.as_path()) {
            self.apply_after_open = None;
            let file_kind = match kind.as_str() {
                "volume" | "labels" => Some(FileKind::Volume),
                "mesh" => Some(FileKind::Mesh),
                _ => None,
            };
            self.picker
                .open(Purpose::Input { name: input }, file_kind, None);
        } else if self.pending.is_none() {
            self.apply_after_open = None;
        }
    }

    /// The user picked `path` in the file dialog.
    fn picked(&mut self, purpose: Purpose, path: &Path) {
        match purpose {
            Purpose::Param { node, param } => {
                let stored = crate::files::path_for_graph(self.state.base_dir().as_deref(), path);
                let _ = self
                    .state
                    .set_param(&node, &param, ParamValue::Path(stored), false);
            }
            Purpose::Input { name } => {
                if let Err(e) = crate::data_panel::set_input(&mut self.state, &name, path) {
                    self.state.status = e;
                }
            }
            Purpose::OpenGraph => self.request(Pending::Open(path.to_path_buf())),
            Purpose::SaveGraphAs => {
                if self.state.save_as(path).is_ok() {
                    self.file_field = path.display().to_string();
                }
            }
        }
    }

    /// Files dropped on the window: a graph opens; a volume or mesh becomes a source node
    /// reading it, where it was dropped.
    fn dropped_files(&mut self, ui: &Ui) {
        let hovering = ui.input(|i| !i.raw.hovered_files.is_empty());
        if hovering {
            egui::Area::new(Id::new("drop-hint"))
                .order(egui::Order::Tooltip)
                .anchor(egui::Align2::CENTER_CENTER, egui::Vec2::ZERO)
                .interactable(false)
                .show(ui.ctx(), |ui| {
                    egui::Frame::popup(ui.style()).show(ui, |ui| {
                        ui.label(
                            "Drop a graph (.ron) to open it, or a volume (.nii, .nii.gz, .vti) or \
                             mesh (.obj, .ply, .stl) to add a node reading it",
                        );
                    });
                });
        }
        let dropped = ui.input(|i| i.raw.dropped_files.clone());
        if dropped.is_empty() {
            return;
        }
        let at = ui
            .input(|i| i.pointer.latest_pos())
            .unwrap_or_else(|| ui.max_rect().center());
        let graph_at = self.canvas_transform.inverse() * at;
        // Dropped on an input of the Data panel: that input reads the file.
        if let Some((name, _)) = self.data_rows.iter().find(|(_, r)| r.contains(at)).cloned() {
            for file in &dropped {
                if let Err(e) = crate::data_panel::set_input(&mut self.state, &name, file.path()) {
                    self.state.status = e;
                }
            }
            return;
        }
        for (n, file) in dropped.iter().enumerate() {
            let path = file.path().to_path_buf();
            let kind = FileKind::of(&path);
            match kind.and_then(|k| Some((k.node_kind()?, k.path_param()))) {
                Some((node_kind, param)) => {
                    let place = graph_at + egui::vec2(0.0, 140.0 * n as f32);
                    let stored =
                        crate::files::path_for_graph(self.state.base_dir().as_deref(), &path);
                    let params = [(param, ParamValue::Path(stored))];
                    if let Ok(id) = self.state.add_node_with(node_kind, pos(place), &params) {
                        self.state.status = format!("added {id} reading {}", path.display());
                    }
                }
                None if kind == Some(FileKind::Graph) => {
                    self.request(Pending::Open(path));
                }
                None => {
                    self.state.status = format!(
                        "{}: not a graph, volume, mesh or shader file (.ron; .nii, .nii.gz, .vti, \
                         …; .obj, .ply, .stl; .wgsl)",
                        path.display()
                    );
                }
            }
        }
    }

    /// The curve editor of a `TransferFunction1D` node. Editing a preset turns it into `custom`
    /// points (the preset's points over the range it spans now), so the look does not jump.
    fn transfer_function_section(&mut self, ui: &mut Ui, id: &str, node: &hatchery_graph::NodeDoc) {
        let value = |name: &str| node_param(&self.state, node, name);
        let text = |v: Option<ParamValue>| match v {
            Some(ParamValue::Text(t) | ParamValue::Choice(t)) => t,
            _ => String::new(),
        };
        let float = |v: Option<ParamValue>| match v {
            Some(ParamValue::Float(x)) => x as f32,
            _ => 0.0,
        };
        let preset = text(value("preset"));
        let range = self
            .preview
            .tf_domains
            .get(id)
            .copied()
            .unwrap_or([float(value("range_min")), float(value("range_max"))]);
        ui.label("Transfer function").on_hover_text(
            "drag a point to move it, double-click to add one, right-click a point to remove it",
        );
        let Some(written) = self.resolved_text(id, "points", text(value("points"))) else {
            ui.weak("the points are relative to the data: they show once the graph has run");
            return;
        };
        let mut points = match crate::curve_editor::node_points(&preset, &written, range) {
            Ok(points) => points,
            Err(e) => {
                ui.colored_label(Color32::LIGHT_RED, format!("cannot draw the curve: {e}"));
                return;
            }
        };
        let context = self.preview.tf_domains.get(id).copied();
        if crate::curve_editor::transfer_function_editor(
            ui,
            Id::new(("tf editor", id)),
            &mut points,
            context,
        ) {
            let values = [
                ("preset", ParamValue::Choice("custom".into())),
                (
                    "points",
                    ParamValue::Text(hatchery_data::transfer_function::format_points(&points)),
                ),
            ];
            let _ = self.state.set_params(id, &values, "transfer function edit");
        }
        ui.separator();
    }

    /// The curve editor of a `StyleTransferFunction` node's `nodes` (per-label rows stay text),
    /// its points named and coloured after the connected `StyleSet`.
    fn style_function_section(&mut self, ui: &mut Ui, id: &str, node: &hatchery_graph::NodeDoc) {
        let Some(ParamValue::Text(text)) = node_param(&self.state, node, "nodes") else {
            return;
        };
        ui.label("Style transfer function").on_hover_text(
            "drag a point to move it, double-click to add one, right-click a point to remove it; \
             click a point to pick its style",
        );
        let Some(text) = self.resolved_text(id, "nodes", text) else {
            ui.weak("the nodes are relative to the data: they show once the graph has run");
            return;
        };
        let mut nodes = match hatchery_data::style::StyleTransferFunction::parse(&text) {
            Ok(nodes) => nodes,
            Err(e) => {
                ui.colored_label(Color32::LIGHT_RED, format!("cannot draw the curve: {e}"));
                return;
            }
        };
        let doc = self.state.doc();
        let styles = doc
            .edges
            .iter()
            .find(|e| e.to.0 == id && e.to.1 == "styles")
            .and_then(|e| doc.nodes.iter().find(|n| n.id == e.from.0))
            .and_then(|set| match node_param(&self.state, set, "styles") {
                Some(ParamValue::Text(styles)) => Some(crate::style_picker::style_looks(&styles)),
                _ => None,
            })
            .unwrap_or_default();
        let context = self.preview.tf_domains.get(id).copied();
        let editor_id = Id::new(("style tf editor", id));
        if crate::curve_editor::style_curve_editor(ui, editor_id, &mut nodes, context, &styles) {
            let text = hatchery_data::style::StyleTransferFunction::format(&nodes);
            let _ = self.state.set_params(
                id,
                &[("nodes", ParamValue::Text(text))],
                "style function edit",
            );
        }
        ui.separator();
    }

    /// The object table of an `ObjectStyles` node, its objects named after the connected labels.
    fn object_styles_section(&mut self, ui: &mut Ui, id: &str, node: &hatchery_graph::NodeDoc) {
        let Some(ParamValue::Text(text)) = node_param(&self.state, node, "objects") else {
            return;
        };
        ui.label("Objects");
        let doc = self.state.doc();
        let names: Vec<(u16, String)> = doc
            .edges
            .iter()
            .find(|e| e.to.0 == id && e.to.1 == "labels")
            .and_then(|e| self.preview.object_names.get(&e.from.0))
            .cloned()
            .unwrap_or_default();
        // Rows may name their objects: the table shows them by id (an edit writes ids).
        let by_id: std::collections::BTreeMap<u16, String> = names.iter().cloned().collect();
        let text = match hatchery_nodes::object_styles::named_rows(&text, &by_id) {
            Ok(text) => text,
            Err(e) => {
                ui.weak(format!("{e} (the table shows once the graph has run)"));
                return;
            }
        };
        let mut rows = match hatchery_nodes::object_styles::parse_rows(&text) {
            Ok(rows) => rows,
            Err(e) => {
                ui.colored_label(Color32::LIGHT_RED, format!("cannot show the table: {e}"));
                return;
            }
        };
        if crate::object_table::object_table(ui, id, &mut rows, &names) {
            let text = hatchery_nodes::object_styles::format_rows(&rows);
            let _ = self.state.set_params(
                id,
                &[("objects", ParamValue::Text(text))],
                "object table edit",
            );
        }
        ui.separator();
    }

    /// The lit-sphere style picker of a `StyleSet` node.
    fn styles_section(&mut self, ui: &mut Ui, id: &str, node: &hatchery_graph::NodeDoc) {
        let Some(ParamValue::Text(styles)) = node_param(&self.state, node, "styles") else {
            return;
        };
        ui.label("Styles");
        if let Some(new) =
            crate::style_picker::style_picker(ui, &mut self.style_thumbnails, &styles)
        {
            let _ = self
                .state
                .set_params(id, &[("styles", ParamValue::Text(new))], "styles edit");
        }
        ui.separator();
    }

    /// The reason of a refused wire, next to where it was dropped, for a few seconds.
    fn refusal_tooltip(&mut self, ui: &Ui) {
        let Some(refusal) = &self.refusal else {
            return;
        };
        let now = ui.input(|i| i.time);
        if now > refusal.until {
            self.refusal = None;
            return;
        }
        egui::Area::new(Id::new("wire-refusal"))
            .order(egui::Order::Tooltip)
            .fixed_pos(refusal.at + egui::vec2(12.0, 12.0))
            .interactable(false)
            .show(ui.ctx(), |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.colored_label(Color32::LIGHT_RED, format!("⛔ {}", refusal.reason));
                });
            });
        ui.ctx()
            .request_repaint_after(std::time::Duration::from_secs_f64(refusal.until - now));
    }

    /// Dragging in the viewport orbits the graph's Camera node (azimuth, elevation), dragging
    /// with the right or middle button (or with Shift) pans its target, the wheel zooms
    /// (distance); one drag or one burst of scrolling is one undo step. A camera that frames
    /// its data (issue 25) keeps framing: the pan moves `pan_x`/`pan_y` (fractions of the
    /// frame) and the wheel scales `fill`, so the view survives a change of data.
    fn orbit_camera(&mut self, ui: &Ui, response: &egui::Response) {
        let Some(camera) = viewport_camera(self.state.doc()) else {
            return;
        };
        let current = |state: &EditorState, name: &str| camera_param(state, &camera, name);
        let framing = camera_choice(&self.state, &camera, "framing").as_deref() != Some("fixed")
            && self.state.doc().edges.iter().any(|e| e.to.0 == camera);
        let panning = response.dragged_by(egui::PointerButton::Secondary)
            || response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Primary)
                && ui.input(|i| i.modifiers.shift));
        let delta = response.drag_delta();
        if panning && delta != egui::Vec2::ZERO {
            let values = if framing {
                // The scene follows the pointer: the target moves the other way, in frame sizes.
                let across = response.rect.size().min_elem().max(1.0) as f64;
                let pan = |name: &str, by: f64| {
                    ParamValue::Float((current(&self.state, name) + by).clamp(-10.0, 10.0))
                };
                vec![
                    ("pan_x", pan("pan_x", -delta.x as f64 / across)),
                    ("pan_y", pan("pan_y", delta.y as f64 / across)),
                ]
            } else {
                let target = pan_target(&self.state, &camera, delta, response.rect.size());
                vec![("target", ParamValue::Vec3(target))]
            };
            let _ = self.state.set_params(&camera, &values, "viewport pan");
        } else if !panning && response.dragged() && delta != egui::Vec2::ZERO {
            orbit_by(&mut self.state, &camera, delta);
        }
        if response.drag_stopped() {
            self.state.end_group();
        }
        let scroll = ui.input(|i| i.smooth_scroll_delta.y);
        if response.hovered() && scroll != 0.0 {
            let zoom = (scroll as f64 * 0.002).exp();
            let value = if framing {
                (
                    "fill",
                    (current(&self.state, "fill") * zoom).clamp(0.05, 20.0),
                )
            } else {
                (
                    "distance",
                    (current(&self.state, "distance") / zoom).max(1e-3),
                )
            };
            let values = [(value.0, ParamValue::Float(value.1))];
            let _ = self.state.set_params(&camera, &values, "viewport zoom");
        }
    }

    fn viewport(&mut self, ui: &mut Ui) {
        use crate::picture::Placement;
        let target = self.preview.target(self.state.doc());
        ui.horizontal(|ui| {
            ui.heading("Viewport");
            let placement = &mut self.picture.placement;
            let maximised = *placement == Placement::Maximised;
            if ui
                .selectable_label(maximised, "⛶ Maximise")
                .on_hover_text("the picture instead of the canvas")
                .clicked()
            {
                *placement = if maximised {
                    Placement::Beside
                } else {
                    Placement::Maximised
                };
            }
            if ui
                .selectable_label(*placement == Placement::FullWindow, "Full window (F11)")
                .on_hover_text("the picture fills the window; Esc or F11 leaves")
                .clicked()
            {
                *placement = if *placement == Placement::FullWindow {
                    Placement::Beside
                } else {
                    Placement::FullWindow
                };
            }
            if self.picture.is_zoomed() {
                ui.label(format!("picture {:.1}×", self.picture.zoom));
                if ui.button("Fit").clicked() {
                    self.picture.fit();
                }
            }
        });
        ui.label(match &target {
            Some((n, p)) => format!("showing {n}.{p}"),
            None => "nothing to show".into(),
        })
        .on_hover_text(
            "drag: orbit the camera; right/middle/Shift-drag: pan it; wheel: its distance. \
             Alt+wheel / Alt+drag: zoom / move the picture itself (the camera stays)",
        );
        if self.preview.chosen.is_some() && ui.button("Show the SaveImage input").clicked() {
            self.preview.chosen = None;
        }
        ui.horizontal(|ui| {
            ui.checkbox(&mut self.preview.show_times, "Node times")
                .on_hover_text("Show each node's last CPU and GPU time on the canvas");
            if self.preview.is_busy() {
                // No spinner: it would repaint the UI all the time the frame renders.
                ui.label("rendering…");
            } else if let Some((elapsed, adapter)) = &self.preview.last_render {
                ui.label(format!("{:.1} ms", elapsed.as_secs_f64() * 1e3))
                    .on_hover_text(format!(
                        "wall time of the last render on the render thread, on {adapter}"
                    ));
            }
        });
        // The picture fills the space left (its size follows the panel).
        let size = ui.available_size().max(egui::vec2(64.0, 48.0));
        if self.preview_enabled {
            let ppp = ui.ctx().pixels_per_point();
            let (w, h) = ((size.x * ppp) as u32, (size.y * ppp) as u32);
            self.preview.update(ui.ctx(), &mut self.state, w, h);
        }
        if let Some(e) = &self.preview.error {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        let sense = egui::Sense::drag();
        let response = match &self.preview.viewport {
            Some(shown) => {
                let mut image = egui::Image::new((shown.id(), size)).uv(self.picture.uv_rect());
                if self.picture.is_zoomed() {
                    // Pixels as squares when inspecting hatching up close.
                    image = image.texture_options(egui::TextureOptions::NEAREST);
                }
                ui.add(image.sense(sense))
            }
            None => ui.allocate_response(size, sense),
        };
        self.viewport_rect = response.rect;
        // While a newer picture renders, the one shown is dimmed and says so on itself (a small
        // label beside the checkbox went unnoticed during 8–18 s CPU renders).
        self.picture_stale = self.preview.is_busy();
        if self.picture_stale {
            let painter = ui.painter_at(response.rect);
            painter.rect_filled(response.rect, 0.0, Color32::from_black_alpha(120));
            painter.text(
                response.rect.center(),
                egui::Align2::CENTER_CENTER,
                "rendering…",
                egui::FontId::proportional(22.0),
                Color32::WHITE,
            );
        }
        // Alt: the picture's own zoom and pan; otherwise the camera.
        if ui.input(|i| i.modifiers.alt) {
            if response.dragged() {
                self.picture.pan(response.drag_delta(), response.rect);
            }
            if let Some(at) = response.hover_pos() {
                let scroll = ui.input(|i| i.smooth_scroll_delta.y + i.smooth_scroll_delta.x);
                if scroll != 0.0 {
                    self.picture
                        .zoom_at((scroll * 0.004).exp(), at, response.rect);
                }
            }
        } else {
            self.orbit_camera(ui, &response);
        }
    }
}

/// A thumbnail's size on the canvas (points): its pixels, at most the thumbnail bound.
fn thumbnail_size(shown: &Shown) -> egui::Vec2 {
    let [w, h] = shown.size();
    egui::vec2(w as f32, h as f32)
}

/// The Camera target after panning by `delta` screen points in a viewport of `size` points:
/// the scene follows the pointer (at the target's depth; the field of view spans the shorter
/// side).
fn pan_target(state: &EditorState, camera: &str, delta: egui::Vec2, size: egui::Vec2) -> [f64; 3] {
    let get = |name: &str| camera_param(state, camera, name) as f32;
    let up_z = camera_choice(state, camera, "up").as_deref() == Some("z");
    let orbit = hatchery_nodes::camera::Camera::orbit(
        glam::Vec3::ZERO,
        get("azimuth"),
        get("elevation"),
        get("distance"),
        get("fov"),
        false,
        0.1,
        10.0,
        up_z,
        1,
        1,
    );
    // Rows of the view matrix are the camera's right and up axes in world space.
    let right = orbit.view.row(0).truncate();
    let up = orbit.view.row(1).truncate();
    let world_per_point =
        2.0 * get("distance") * (get("fov").to_radians() / 2.0).tan() / size.min_elem().max(1.0);
    let shift = (-right * delta.x + up * delta.y) * world_per_point;
    let target = camera_target(state, camera);
    [0, 1, 2].map(|i| target[i] + shift[i] as f64)
}

impl eframe::App for EditorApp {
    fn ui(&mut self, ui: &mut Ui, _frame: &mut eframe::Frame) {
        EditorApp::ui(self, ui);
    }
}

/// A widget for one parameter; returns the new value when the user changed it.
pub(crate) fn param_widget(
    ui: &mut Ui,
    spec: &ParamSpec,
    current: &ParamValue,
) -> Option<ParamValue> {
    let hover = format!("{} ({})", spec.doc, spec.kind.describe());
    match (&spec.kind, current) {
        (ParamKind::Float { min, max }, ParamValue::Float(x)) => {
            let mut v = *x;
            // Angles: a fine drag (about a degree a point) instead of a 720° slider in a few
            // points, which jumped hundreds of degrees for a short drag.
            let angle = spec.doc.contains("degrees");
            let r = if angle {
                ui.add(
                    egui::DragValue::new(&mut v)
                        .range(*min..=*max)
                        .speed(0.5)
                        .suffix("°"),
                )
            } else if (max - min).is_finite() && max - min <= 1.0e4 {
                ui.add(egui::Slider::new(&mut v, *min..=*max))
            } else {
                ui.add(egui::DragValue::new(&mut v).range(*min..=*max).speed(0.01))
            };
            r.on_hover_text(hover)
                .changed()
                .then_some(ParamValue::Float(v.clamp(*min, *max)))
        }
        (ParamKind::Int { min, max }, ParamValue::Int(x)) => {
            let mut v = *x;
            let r = ui.add(egui::DragValue::new(&mut v).range(*min..=*max));
            r.on_hover_text(hover)
                .changed()
                .then_some(ParamValue::Int(v))
        }
        (ParamKind::Bool, ParamValue::Bool(b)) => {
            let mut v = *b;
            let r = ui.checkbox(&mut v, "");
            r.on_hover_text(hover)
                .changed()
                .then_some(ParamValue::Bool(v))
        }
        (ParamKind::Choice(names), ParamValue::Choice(c)) => {
            let mut chosen = None;
            egui::ComboBox::from_id_salt(spec.name)
                .selected_text(c.as_str())
                .show_ui(ui, |ui| {
                    for name in names.iter() {
                        if ui.selectable_label(c == name, *name).clicked() && c != name {
                            chosen = Some(ParamValue::Choice((*name).to_owned()));
                        }
                    }
                })
                .response
                .on_hover_text(hover);
            chosen
        }
        (ParamKind::Color, ParamValue::Color(c)) => {
            let mut v = c.map(|x| x as f32);
            let r = ui.color_edit_button_rgba_unmultiplied(&mut v);
            r.on_hover_text(hover)
                .changed()
                .then(|| ParamValue::Color(v.map(|x| (x as f64).clamp(0.0, 1.0))))
        }
        (ParamKind::Vec3, ParamValue::Vec3(v)) => {
            let mut v = *v;
            let changed = ui
                .horizontal(|ui| {
                    let mut changed = false;
                    for x in &mut v {
                        changed |= ui.add(egui::DragValue::new(x).speed(0.01)).changed();
                    }
                    changed
                })
                .inner;
            changed.then_some(ParamValue::Vec3(v))
        }
        (ParamKind::Path, ParamValue::Path(s)) | (ParamKind::Text, ParamValue::Text(s)) => {
            let mut v = s.clone();
            let r = ui.text_edit_singleline(&mut v).on_hover_text(hover);
            r.changed().then_some(match spec.kind {
                ParamKind::Path => ParamValue::Path(v),
                _ => ParamValue::Text(v),
            })
        }
        _ => {
            ui.label(current.to_string());
            None
        }
    }
}

/// The snarl viewer: every change goes through the editor state (and so `edit`).
struct Viewer<'a> {
    /// "Frame all" requested: the canvas rectangle (screen space) to fit the nodes into.
    frame_into: Option<egui::Rect>,
    /// Node sizes as drawn last frame (graph units).
    node_sizes: BTreeMap<String, [f32; 2]>,
    transform: egui::emath::TSTransform,
    /// Where nodes are drawn (for selection by the mouse).
    selecting: &'a mut CanvasSelection,
    state: &'a mut EditorState,
    add_menu: &'a mut Option<crate::add_menu::Palette>,
    clipboard: &'a mut String,
    preview: &'a mut Option<(String, String)>,
    /// Ports shown as thumbnails on their nodes (clicking an output's name toggles it).
    pins: &'a mut BTreeSet<Port>,
    /// Pictures (or why there is none) of the pinned ports.
    thumbnails: BTreeMap<Port, Result<(egui::TextureId, egui::Vec2), String>>,
    /// Per-node times, when the user asked for them.
    times: Option<&'a BTreeMap<String, NodeTime>>,
    /// Why a wire drop was refused this frame.
    refused: Option<String>,
    /// Warnings of the last render, by node.
    warnings: BTreeMap<String, String>,
    failed: Option<(String, String)>,
    /// *Frame selection* was chosen in a node menu (done after the canvas is drawn).
    frame_request: &'a mut bool,
    /// The mouse wheel over the canvas this frame (points, pointer): it zooms about the
    /// pointer instead of scrolling (Shift+wheel still scrolls).
    wheel_zoom: Option<(f32, Pos2)>,
}

impl Viewer<'_> {
    fn schema(&self, id: &str) -> Option<hatchery_graph::NodeSchema> {
        let doc = self.state.doc();
        let n = doc.nodes.iter().find(|n| n.id == id)?;
        hatchery_graph::node_schema(&self.state.registry, doc, n).map(|s| (*s).clone())
    }

    /// The ports shown on canvas node `id` (a group's are its members' exposed ports).
    fn ports(&self, id: &str, output: bool) -> Vec<hatchery_graph::organise::PortInfo> {
        crate::groups::view_ports(self.state.doc(), &self.state.registry, id, output)
    }

    fn error(&self, id: &str) -> Option<String> {
        let mut text = self
            .state
            .node_error(id)
            .map(str::to_owned)
            .or_else(|| crate::groups::member_errors(self.state, id));
        if let Some((n, m)) = &self.failed
            && n == id
        {
            text = Some(match text {
                Some(t) => format!("{t}\n{m}"),
                None => m.clone(),
            });
        }
        text
    }

    fn pin(ty: Option<PortType>) -> PinInfo {
        match ty {
            Some(ty) => PinInfo::circle()
                .with_fill(port_color(ty))
                .with_wire_color(port_color(ty)),
            // A reroute that carries nothing yet takes any type.
            None => PinInfo::circle().with_fill(Color32::GRAY),
        }
    }

    /// Inside a group, a mark on a member's port wired to a node outside it.
    fn outside_mark(&self, ui: &mut Ui, p: &hatchery_graph::organise::PortInfo, output: bool) {
        let (doc, level) = (self.state.doc(), self.state.level());
        if let Some(note) = crate::groups::outside_note(doc, level, p, output) {
            ui.label(if output { "➡" } else { "⬅" }).on_hover_text(note);
        }
    }

    fn is_reroute(&self, id: &str) -> bool {
        hatchery_graph::reroute::is_reroute(self.state.doc(), id)
    }
}

impl SnarlViewer<String> for Viewer<'_> {
    fn title(&mut self, node: &String) -> String {
        match self.state.doc().nodes.iter().find(|n| &n.id == node) {
            Some(n) => format!("{} ({})", n.id, n.kind),
            None if self.state.doc().group(node).is_some() => format!("{node} (Group)"),
            None => node.clone(),
        }
    }

    fn inputs(&mut self, node: &String) -> usize {
        self.ports(node, false).len()
    }

    fn outputs(&mut self, node: &String) -> usize {
        self.ports(node, true).len()
    }

    fn show_input(
        &mut self,
        pin: &InPin,
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) -> impl SnarlPin + 'static {
        let node = snarl.get_node(pin.id.node).cloned().unwrap_or_default();
        let port = self.ports(&node, false).get(pin.id.input).cloned();
        match &port {
            Some(p) => {
                let required = if p.required { "" } else { " (optional)" };
                let ty = p.ty.map_or("any type".into(), |t| t.to_string());
                ui.label(crate::groups::port_label(&node, p))
                    .on_hover_text(format!("{}: {ty}{required}\n{}", p.port, p.doc));
                self.outside_mark(ui, p, false);
            }
            None => {
                ui.label("?");
            }
        }
        Self::pin(port.and_then(|p| p.ty))
    }

    fn show_output(
        &mut self,
        pin: &OutPin,
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) -> impl SnarlPin + 'static {
        let node = snarl.get_node(pin.id.node).cloned().unwrap_or_default();
        let port = self.ports(&node, true).get(pin.id.output).cloned();
        match &port {
            // Thumbnails are for a node's own outputs (not a group's or a reroute's).
            Some(p) if p.node == node && p.ty.is_some() && !self.is_reroute(&node) => {
                let key = (node, p.port.clone());
                let pinned = self.pins.contains(&key);
                let text = if pinned {
                    egui::RichText::new(format!("{} 👁", p.port)).strong()
                } else {
                    egui::RichText::new(&p.port)
                };
                let response = ui
                    .add(egui::Label::new(text).sense(egui::Sense::click()))
                    .on_hover_text(format!(
                        "{}: {}\n{}\nClick to {} its thumbnail on the node",
                        p.port,
                        p.ty.map_or(String::new(), |t| t.to_string()),
                        p.doc,
                        if pinned { "hide" } else { "show" }
                    ));
                if response.clicked() && !self.pins.remove(&key) {
                    self.pins.insert(key);
                }
                self.outside_mark(ui, p, true);
            }
            Some(p) => {
                let ty = p.ty.map_or("any type".into(), |t| t.to_string());
                ui.label(crate::groups::port_label(&node, p))
                    .on_hover_text(format!("{}: {ty}\n{}", p.port, p.doc));
            }
            None => {
                ui.label("?");
            }
        }
        Self::pin(port.and_then(|p| p.ty))
    }

    fn has_body(&mut self, node: &String) -> bool {
        self.error(node).is_some() || self.warnings.contains_key(node)
    }

    fn has_footer(&mut self, node: &String) -> bool {
        self.pins.iter().any(|(n, _)| n == node) || self.times.is_some_and(|t| t.contains_key(node))
    }

    fn show_body(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        // At most NODE_MESSAGE_WIDTH wide, cut with "…" (the whole text on hover): a long
        // message used to stretch a new node past the canvas edge.
        let message = |ui: &mut Ui, color: Color32, text: String, whole: &str| {
            let label = egui::Label::new(egui::RichText::new(text).color(color)).truncate();
            ui.add_sized(egui::vec2(NODE_MESSAGE_WIDTH, 0.0), label)
                .on_hover_text(whole);
        };
        if let Some(e) = self.error(&id) {
            let first = e.lines().next().unwrap_or_default().to_owned();
            message(ui, Color32::LIGHT_RED, format!("⚠ {first}"), &e);
        }
        if let Some(w) = self.warnings.get(&id).cloned() {
            message(ui, Color32::YELLOW, format!("⚠ {w}"), &w);
        }
    }

    /// Below the pins: the node's times (on request) and its pinned thumbnails.
    fn show_footer(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        if let Some(time) = self.times.and_then(|t| t.get(&id)) {
            ui.label(egui::RichText::new(format_time(time)).monospace().small())
                .on_hover_text(
                    "CPU: encoding the node's GPU work or doing its CPU work; GPU: its \
                     submissions between timestamps (where the adapter has them). On a \
                     software driver both are CPU time.",
                );
        }
        let pinned: Vec<Port> = self
            .pins
            .iter()
            .filter(|(n, _)| *n == id)
            .cloned()
            .collect();
        for port in pinned {
            match self.thumbnails.get(&port) {
                Some(Ok((texture, size))) => {
                    let name = format!("{}.{}", port.0, port.1);
                    ui.add(egui::Image::new((*texture, *size)).alt_text(&name))
                        .on_hover_text(name);
                }
                Some(Err(e)) => {
                    ui.colored_label(Color32::LIGHT_RED, format!("{}: no picture", port.1))
                        .on_hover_text(e);
                }
                None => {
                    ui.label(format!("{}: rendering…", port.1));
                }
            }
        }
    }

    fn connect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<String>) {
        let (Some(f), Some(t)) = (
            snarl.get_node(from.id.node).cloned(),
            snarl.get_node(to.id.node).cloned(),
        ) else {
            return;
        };
        let (Some(op), Some(ip)) = (
            self.ports(&f, true).get(from.id.output).cloned(),
            self.ports(&t, false).get(to.id.input).cloned(),
        ) else {
            self.state.status = "cannot connect nodes of unknown kinds".into();
            return;
        };
        match self
            .state
            .connect((&op.node, &op.port), (&ip.node, &ip.port))
        {
            Ok(_) => {
                snarl.drop_inputs(to.id);
                snarl.connect(from.id, to.id);
                self.state.status = format!(
                    // ASCII: the editor's default font has no arrow glyph (it drew a box).
                    "connected {}.{} -> {}.{}",
                    op.node, op.port, ip.node, ip.port
                );
            }
            Err(reason) => self.refused = Some(reason),
        }
    }

    fn disconnect(&mut self, from: &OutPin, to: &InPin, snarl: &mut Snarl<String>) {
        let (Some(f), Some(t)) = (
            snarl.get_node(from.id.node).cloned(),
            snarl.get_node(to.id.node).cloned(),
        ) else {
            return;
        };
        let (Some(op), Some(ip)) = (
            self.ports(&f, true).get(from.id.output).cloned(),
            self.ports(&t, false).get(to.id.input).cloned(),
        ) else {
            return;
        };
        if self
            .state
            .disconnect((&op.node, &op.port), (&ip.node, &ip.port))
        {
            snarl.disconnect(from.id, to.id);
        }
    }

    fn drop_inputs(&mut self, pin: &InPin, snarl: &mut Snarl<String>) {
        for remote in pin.remotes.clone() {
            let from = snarl.out_pin(remote);
            self.disconnect(&from, pin, snarl);
        }
    }

    fn drop_outputs(&mut self, pin: &OutPin, snarl: &mut Snarl<String>) {
        for remote in pin.remotes.clone() {
            let to = snarl.in_pin(remote);
            self.disconnect(pin, &to, snarl);
        }
    }

    fn has_graph_menu(&mut self, _pos: Pos2, _snarl: &mut Snarl<String>) -> bool {
        true
    }

    fn show_graph_menu(&mut self, at: Pos2, ui: &mut Ui, _snarl: &mut Snarl<String>) {
        // Snarl's menu only opens the palette, which takes typing (see crate::add_menu).
        let screen = ui.cursor().min;
        *self.add_menu = Some(crate::add_menu::Palette::new(ui.ctx(), screen, at, None));
        ui.close();
    }

    fn has_dropped_wire_menu(&mut self, _src: AnyPins, _snarl: &mut Snarl<String>) -> bool {
        true
    }

    fn show_dropped_wire_menu(
        &mut self,
        at: Pos2,
        ui: &mut Ui,
        src: AnyPins,
        snarl: &mut Snarl<String>,
    ) {
        // The dragged pins' node and port names, and their type.
        // The dragged pins' real node and port names (a member's, for a group), and types.
        let (ends, output): (Vec<(String, String, Option<PortType>)>, bool) = match src {
            AnyPins::Out(pins) => (
                pins.iter()
                    .filter_map(|p| {
                        let id = snarl.get_node(p.node)?.clone();
                        let port = self.ports(&id, true).get(p.output)?.clone();
                        Some((port.node, port.port, port.ty))
                    })
                    .collect(),
                true,
            ),
            AnyPins::In(pins) => (
                pins.iter()
                    .filter_map(|p| {
                        let id = snarl.get_node(p.node)?.clone();
                        let port = self.ports(&id, false).get(p.input)?.clone();
                        Some((port.node, port.port, port.ty))
                    })
                    .collect(),
                false,
            ),
        };
        if ends.is_empty() {
            ui.close();
            return;
        }
        let wire = crate::add_menu::DroppedWire {
            ty: ends.first().and_then(|e| e.2),
            ends: ends.into_iter().map(|(id, port, _)| (id, port)).collect(),
            output,
        };
        let screen = ui.cursor().min;
        *self.add_menu = Some(crate::add_menu::Palette::new(
            ui.ctx(),
            screen,
            at,
            Some(wire),
        ));
        ui.close();
    }

    fn current_transform(
        &mut self,
        to_global: &mut egui::emath::TSTransform,
        snarl: &mut Snarl<String>,
    ) {
        // The canvas holds still while a box selection is dragged (the drag would pan it).
        if let Some(held) = self.selecting.box_transform {
            *to_global = held;
        }
        // The wheel zooms about the pointer: undo the scroll the canvas took (from last
        // frame's transform) and scale about the point under the pointer instead, so the graph
        // stays where it is under the mouse (a few notches used to scroll it off-screen).
        if let Some((scroll, at)) = self.wheel_zoom.take() {
            let before = self.transform;
            let factor = (scroll * 0.002).exp();
            let scaling = (before.scaling * factor).clamp(0.2, 2.0);
            let factor = scaling / before.scaling;
            *to_global = egui::emath::TSTransform::from_translation(at.to_vec2())
                * egui::emath::TSTransform::from_scaling(factor)
                * egui::emath::TSTransform::from_translation(-at.to_vec2())
                * before;
        }
        self.transform = *to_global;
        let Some(rect) = self.frame_into.take() else {
            return;
        };
        // Node positions are top-left corners; sizes as drawn (or typical, before drawing).
        let mut bounds = egui::Rect::NOTHING;
        for (p, id) in snarl.nodes_pos() {
            let [w, h] = self
                .node_sizes
                .get(id)
                .copied()
                .unwrap_or(crate::arrange::DEFAULT_SIZE);
            bounds = bounds.union(egui::Rect::from_min_size(p, egui::vec2(w, h)));
        }
        bounds = bounds.union(crate::frames::bounds(self.state.doc(), self.state.level()));
        if !bounds.is_positive() {
            return;
        }
        let bounds = bounds.expand(30.0);
        let fit = (rect.width() / bounds.width()).min(rect.height() / bounds.height());
        // Never so small that titles fall below LEGIBLE_TITLE_PX: scroll instead.
        let legible = LEGIBLE_TITLE_PX / TITLE_FONT_PX;
        let scaling = fit.clamp(legible, 1.0);
        let translation = if scaling <= fit {
            rect.center().to_vec2() - bounds.center().to_vec2() * scaling
        } else {
            // Too big to fit legibly: show its top-left part (where the sources are).
            rect.min.to_vec2() - bounds.min.to_vec2() * scaling
        };
        *to_global = egui::emath::TSTransform {
            scaling,
            translation,
        };
        self.transform = *to_global;
    }

    fn has_node_menu(&mut self, _node: &String) -> bool {
        true
    }

    fn draw_background(
        &mut self,
        background: Option<&egui_snarl::ui::BackgroundPattern>,
        viewport: &egui::Rect,
        snarl_style: &egui_snarl::ui::SnarlStyle,
        style: &egui::Style,
        painter: &egui::Painter,
        _snarl: &Snarl<String>,
    ) {
        if let Some(background) = background {
            background.draw(viewport, snarl_style, style, painter);
        }
        // Frames lie between the grid and the nodes.
        crate::frames::paint(painter, self.state.doc(), self.state.level());
    }

    fn node_frame(
        &mut self,
        default: egui::Frame,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        snarl: &Snarl<String>,
    ) -> egui::Frame {
        let Some(id) = snarl.get_node(node) else {
            return default;
        };
        if !self.state.selection.contains(id) {
            return default;
        }
        let mut stroke = crate::selection::selected_stroke();
        if self.state.inspected() == Some(id.as_str()) {
            stroke.color = crate::selection::active_color();
        }
        default.stroke(stroke)
    }

    fn final_node_rect(
        &mut self,
        node: NodeId,
        rect: egui::Rect,
        _ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        if let Some(id) = snarl.get_node(node) {
            self.selecting.node_drawn(id, rect);
        }
    }

    fn show_node_menu(
        &mut self,
        node: NodeId,
        _inputs: &[InPin],
        _outputs: &[OutPin],
        ui: &mut Ui,
        snarl: &mut Snarl<String>,
    ) {
        let Some(id) = snarl.get_node(node).cloned() else {
            return;
        };
        let selected: BTreeSet<String> = if self.state.selection.contains(&id) {
            self.state.selection.clone()
        } else {
            BTreeSet::from([id.clone()])
        };
        let ids: Vec<&str> = selected.iter().map(String::as_str).collect();
        crate::groups::node_menu(self.state, ui, &id, &selected);
        if ui.button("Frame selection").clicked() {
            *self.frame_request = true;
            ui.close();
        }
        if let Some(schema) = self.schema(&id) {
            for out in &schema.outputs {
                if ui.button(format!("Preview {}", out.name)).clicked() {
                    *self.preview = Some((id.clone(), out.name.to_owned()));
                    ui.close();
                }
            }
        }
        if ui.button("Duplicate").clicked() {
            let _ = self.state.duplicate(&ids);
            ui.close();
        }
        if ui.button("Copy").clicked() {
            *self.clipboard = self.state.copy(&ids);
            ui.ctx().copy_text(self.clipboard.clone());
            ui.close();
        }
        if ui.button("Delete").clicked() {
            let owned: Vec<String> = selected.into_iter().collect();
            let _ = self.state.remove_nodes(&owned);
            ui.close();
        }
    }
}

/// "12.3 ms cpu · 4.5 ms gpu", "cached" when the last pass reused the node's outputs, or the
/// node whose fused pass it ran in (that node shows the pass's time).
fn format_time(time: &NodeTime) -> String {
    if time.cached {
        return "⏱ cached".into();
    }
    if let Some(carrier) = &time.fused_into {
        return format!("⏱ in {carrier}'s pass");
    }
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    match time.gpu {
        Some(gpu) => format!("⏱ {:.1} ms cpu · {:.1} ms gpu", ms(time.cpu), ms(gpu)),
        None => format!("⏱ {:.1} ms cpu", ms(time.cpu)),
    }
}

/// The Camera node the viewport drives: the first one by id.
fn viewport_camera(doc: &hatchery_graph::GraphDocument) -> Option<String> {
    let mut cameras: Vec<&str> = doc
        .nodes
        .iter()
        .filter(|n| n.kind == "Camera")
        .map(|n| n.id.as_str())
        .collect();
    cameras.sort();
    cameras.first().map(|id| id.to_string())
}

/// A node's parameter as the graph will use it: the file's value, else the schema's default.
fn node_param(
    state: &EditorState,
    node: &hatchery_graph::NodeDoc,
    name: &str,
) -> Option<ParamValue> {
    let schema = hatchery_graph::node_schema(&state.registry, state.doc(), node)?;
    let spec = schema.param(name)?;
    match node.params.get(name) {
        Some(raw) => spec.convert(raw).ok(),
        None => Some(spec.default.clone()),
    }
}

/// A Camera parameter as the graph will use it.
fn camera_value(state: &EditorState, camera: &str, name: &str) -> Option<ParamValue> {
    let node = state.doc().nodes.iter().find(|n| n.id == camera)?;
    node_param(state, node, name)
}

/// Turns the camera by a viewport drag of `delta` points (0.4° a point; one undo group).
fn orbit_by(state: &mut EditorState, camera: &str, delta: egui::Vec2) {
    // Rounded to 1/1000 degree, so the file says `elevation: 9.0`, not 8.999999999999995.
    let round = |x: f64| (x * 1000.0).round() / 1000.0;
    let azimuth = round(
        (camera_param(state, camera, "azimuth") - delta.x as f64 * 0.4 + 180.0).rem_euclid(360.0)
            - 180.0,
    );
    let elevation =
        round((camera_param(state, camera, "elevation") + delta.y as f64 * 0.4).clamp(-89.0, 89.0));
    let values = [
        ("azimuth", ParamValue::Float(azimuth)),
        ("elevation", ParamValue::Float(elevation)),
    ];
    let _ = state.set_params(camera, &values, "viewport orbit");
}

fn camera_param(state: &EditorState, camera: &str, name: &str) -> f64 {
    match camera_value(state, camera, name) {
        Some(ParamValue::Float(x)) => x,
        _ => 0.0,
    }
}

fn camera_choice(state: &EditorState, camera: &str, name: &str) -> Option<String> {
    match camera_value(state, camera, name) {
        Some(ParamValue::Choice(c)) => Some(c),
        _ => None,
    }
}

fn camera_target(state: &EditorState, camera: &str) -> [f64; 3] {
    match camera_value(state, camera, "target") {
        Some(ParamValue::Vec3(v)) => v,
        _ => [0.0; 3],
    }
}
