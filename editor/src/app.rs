//! The egui application's state, [`EditorApp`], and what belongs to no panel (files dropped or
//! picked, the unsaved-changes dialog, export, the window title). One frame of it, placing the
//! panels, is [`crate::shell`].

use crate::files::{FileKind, FilePicker, Purpose};
use crate::preview::Preview;
use crate::selection::CanvasSelection;
use crate::state::EditorState;
use egui::{Color32, Id, Pos2, Ui};
use egui_snarl::{NodeId, Snarl};
use hatchery_graph::{EditorPos, ParamValue, PortType};
use std::collections::BTreeMap;
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
        PortType::VectorField => Color32::from_rgb(210, 170, 120),
    }
}

pub(crate) fn pos(p: Pos2) -> EditorPos {
    EditorPos { x: p.x, y: p.y }
}

pub struct EditorApp {
    pub state: EditorState,
    /// The paint tool's last dab in this drag (world position, radius), to space the next.
    pub last_dab: Option<(glam::Vec3, f32)>,
    pub preview: Preview,
    /// Render the viewport (tests that only edit turn it off).
    pub preview_enabled: bool,
    /// Where the viewport image was drawn last frame (screen points; tests drag in it).
    pub viewport_rect: egui::Rect,
    /// Folder listed in the Presets menu.
    pub presets_dir: PathBuf,
    /// The path field of the File menu.
    pub file_field: String,
    pub(crate) snarl: Snarl<String>,
    pub(crate) snarl_ids: BTreeMap<String, NodeId>,
    /// Where the canvas put each node at the last rebuild or move (nodes without a stored
    /// position get a grid place, written to the document only when moved).
    pub(crate) placed: BTreeMap<String, Pos2>,
    pub(crate) synced_revision: Option<u64>,
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
    pub(crate) layout: crate::layout_dump::LayoutDump,
    /// The add-node palette, while open (see [`crate::add_menu`]).
    pub add_menu: Option<crate::add_menu::Palette>,
    pub(crate) clipboard: String,
    /// Why the last wire drop was refused, where and when (shown as a tooltip for a while).
    pub refusal: Option<Refusal>,
    pub(crate) style_thumbnails: crate::style_picker::Thumbnails,
    /// The file dialog (path parameters, Open…, Save as…).
    pub picker: FilePicker,
    pub(crate) title: String,
    pub(crate) offer_recovery: bool,
    /// Fit every node into the canvas on the next frame.
    pub frame_all: bool,
    /// The picture shown is being replaced by a render in progress (drawn dimmed).
    pub picture_stale: bool,
    /// The Data panel's input rows last frame (screen points): drop targets.
    pub data_rows: Vec<(String, egui::Rect)>,
    /// The Presets menu's presets (read when it first opens) and their thumbnails.
    pub(crate) gallery: Option<Vec<crate::gallery::PresetInfo>>,
    pub(crate) thumbnails: crate::gallery::Thumbnails,
    /// Where preset thumbnails are cached (see [`crate::gallery`]).
    pub thumbnail_dir: PathBuf,
    /// *Apply to my data…*: once this preset is open, ask for a file for this input (name, type).
    pub(crate) apply_after_open: Option<(PathBuf, String, String)>,
    /// Wakes the UI when a custom shader's file changes.
    pub(crate) file_watch: Option<crate::file_watch::FileWatch>,
    /// Frame once more when every node has been drawn (their sizes are known then).
    pub(crate) frame_all_again: bool,
    /// The canvas's graph → screen transform of the last frame.
    pub canvas_transform: egui::emath::TSTransform,
    /// A kept view to show on the next frame (another graph or level is shown).
    pub(crate) restore_view: Option<egui::emath::TSTransform>,
    /// The views of graphs and groups, the panel widths (see [`crate::settings`]).
    pub settings: crate::settings::Settings,
    /// Where the settings are written when the window closes (none: not kept, as in tests
    /// that do not ask for it).
    pub settings_file: Option<PathBuf>,
    pub(crate) canvas_views: crate::settings::CanvasViews,
    /// The panels' outer rectangles last frame by egui id (`inspector`, `viewport`).
    pub panel_rects: BTreeMap<&'static str, egui::Rect>,
    /// Nodes drawn as boxes (zoomed out, see [`crate::panels::canvas_zoom`]) last frame: the
    /// screen height of their id's text, pixels (0: the box is too small for legible text).
    pub lod_text_px: BTreeMap<String, f32>,
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

/// Actions that replace the document and so ask first when it has unsaved changes.
#[derive(Clone, Debug, PartialEq)]
pub enum Pending {
    Open(PathBuf),
    New,
    /// Closing the window.
    Quit,
}

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
            last_dab: None,
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
            restore_view: None,
            settings: Default::default(),
            settings_file: None,
            canvas_views: Default::default(),
            panel_rects: BTreeMap::new(),
            lod_text_px: BTreeMap::new(),
        }
    }

    /// Keeps views and panel widths in `path` (read now, written when the window closes).
    pub fn with_settings_file(mut self, path: PathBuf) -> Self {
        self.settings = crate::settings::Settings::load(&path);
        self.settings_file = Some(path);
        self
    }

    /// Writes the settings file (if there is one) with the view shown and the panel widths.
    pub fn save_settings(&mut self) {
        self.canvas_views
            .remember(&mut self.settings, self.canvas_transform);
        for (id, r) in &self.panel_rects {
            self.settings.panels.insert((*id).to_owned(), r.width());
        }
        if let Some(path) = &self.settings_file
            && let Err(e) = self.settings.save(path)
        {
            self.state.status = format!("could not keep the settings in {}: {e}", path.display());
        }
    }

    /// The width a panel had when the settings were written, else `default`.
    pub(crate) fn panel_width(&self, id: &str, default: f32) -> f32 {
        self.settings.panels.get(id).copied().unwrap_or(default)
    }

    /// An editor inside eframe: previews render on the window's wgpu device when that is a good
    /// idea (see [`crate::preview::share_device_by_default`]).
    pub fn with_creation_context(state: EditorState, cc: &eframe::CreationContext<'_>) -> Self {
        let mut app = Self::new(state);
        crate::fonts::install_math_fallback(&cc.egui_ctx);
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

    pub(crate) fn perform(&mut self, action: Pending) {
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

    pub(crate) fn confirm_discard(&mut self, ui: &mut Ui) {
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

    /// Closing the window with unsaved changes asks first (the autosave covers crashes only).
    pub(crate) fn guard_close(&mut self, ui: &Ui) {
        if self.quitting {
            self.save_settings();
            ui.ctx().send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        if ui.input(|i| i.viewport().close_requested()) {
            self.save_settings();
        }
        if ui.input(|i| i.viewport().close_requested()) && self.state.is_dirty() {
            ui.ctx()
                .send_viewport_cmd(egui::ViewportCommand::CancelClose);
            self.pending = Some(Pending::Quit);
        }
    }

    /// *Apply to my data…*: the preset is open, ask for the file of its main input; forget the
    /// request if opening it was cancelled.
    pub(crate) fn apply_to_my_data(&mut self) {
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
    pub(crate) fn picked(&mut self, purpose: Purpose, path: &Path) {
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
    pub(crate) fn dropped_files(&mut self, ui: &Ui) {
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
}
