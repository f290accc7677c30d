//! *File → Export image…*: any output port as a PNG at a chosen resolution, rendered off the UI
//! thread by a session of its own through `Session::export_png` — the function behind
//! `hatchery render --dump node.port=file.png`, so the file equals the command line's for the
//! same graph and size (for an Image port, also what `hatchery render -o` writes).

use hatchery_graph::{Graph, GraphDocument, PortType};
use hatchery_nodes::Session;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{Receiver, channel};

/// Port types that have a picture.
const PICTURE_TYPES: [PortType; 4] = [
    PortType::Image,
    PortType::Mask,
    PortType::GBuffer,
    PortType::Volume,
];

/// The dialog's state; `open` shows it.
pub struct ExportDialog {
    pub open: bool,
    /// `node.port` to export.
    pub port: Option<(String, String)>,
    pub width: u32,
    pub height: u32,
    pub path: String,
    /// Scale hatching cells, line widths and labels with the export size, so the file is the
    /// figure seen on screen at the export's resolution (`hatchery render --scale`).
    pub as_on_screen: bool,
    /// The size of the picture on screen when the dialog opened (pixels).
    pub screen: Option<[u32; 2]>,
    running: Option<Receiver<Result<PathBuf, String>>>,
    /// The last export's outcome, for the dialog and the status line.
    pub last: Option<Result<PathBuf, String>>,
}

impl Default for ExportDialog {
    fn default() -> Self {
        ExportDialog {
            open: false,
            port: None,
            width: 1024,
            height: 768,
            path: String::new(),
            as_on_screen: true,
            screen: None,
            running: None,
            last: None,
        }
    }
}

impl ExportDialog {
    /// Rendered pixels per pixel of the figure on screen: the export's height over the
    /// screen picture's (the camera's field of view is vertical), 1 when lengths stay in output
    /// pixels or the screen size is unknown.
    pub fn pixel_scale(&self) -> f64 {
        match self.screen {
            Some([_, h]) if self.as_on_screen && h > 0 => self.height as f64 / h as f64,
            _ => 1.0,
        }
    }

    /// Whether an export is being rendered.
    pub fn is_busy(&self) -> bool {
        self.running.is_some()
    }

    /// Starts rendering `graph` (whose relative paths resolve against `base`) on a thread; `None`
    /// when the graph has errors.
    pub fn start(&mut self, graph: Option<Graph>, base: Option<&Path>) {
        let Some(graph) = graph else {
            self.last = Some(Err(
                "the graph has errors (see the nodes): nothing exported".into(),
            ));
            return;
        };
        let Some((node, port)) = self.port.clone() else {
            self.last = Some(Err("choose a port to export".into()));
            return;
        };
        let path = PathBuf::from(self.path.trim());
        if path.as_os_str().is_empty() {
            self.last = Some(Err("choose a file to write".into()));
            return;
        }
        let path = match base {
            Some(base) if path.is_relative() => base.join(path),
            _ => path,
        };
        let size = (self.width, self.height);
        let scale = self.pixel_scale();
        let (send, receive) = channel();
        std::thread::spawn(move || {
            let result = (|| {
                let registry = hatchery_nodes::registry();
                let mut session = Session::with_graph(registry, graph, size.0, size.1)
                    .map_err(|e| e.to_string())?;
                session.ctx.set_pixel_scale(scale);
                session
                    .export_png(&node, &port, &path)
                    .map_err(|e| e.to_string())?;
                Ok(path)
            })();
            let _ = send.send(result);
        });
        self.running = Some(receive);
        self.last = None;
    }

    /// Picks up a finished export; returns it once.
    pub fn poll(&mut self) -> Option<Result<PathBuf, String>> {
        let done = self.running.as_ref()?.try_recv().ok()?;
        self.running = None;
        self.last = Some(done.clone());
        Some(done)
    }

    /// The dialog window, listing the picture ports of `doc`. Returns true when *Export* was
    /// clicked (the caller then calls [`Self::start`] with the validated graph).
    pub fn show(
        &mut self,
        ctx: &egui::Context,
        doc: &GraphDocument,
        schemas: &dyn hatchery_graph::SchemaLookup,
    ) -> bool {
        let mut requested = false;
        if !self.open {
            return false;
        }
        let ports: Vec<(String, String)> = doc
            .nodes
            .iter()
            .filter_map(|n| Some((n, hatchery_graph::node_schema(schemas, doc, n)?)))
            .flat_map(|(n, schema)| {
                schema
                    .outputs
                    .iter()
                    .filter(|o| PICTURE_TYPES.contains(&o.ty))
                    .map(|o| (n.id.clone(), o.name.to_owned()))
                    .collect::<Vec<_>>()
            })
            .collect();
        let mut open = self.open;
        // Below the menu bar, centred (by default egui put it over the menus).
        let top = ctx.content_rect().center_top() + egui::vec2(0.0, 80.0);
        egui::Window::new("Export image")
            .open(&mut open)
            .collapsible(false)
            .resizable(false)
            .pivot(egui::Align2::CENTER_TOP)
            .default_pos(top)
            .show(ctx, |ui| {
                egui::Grid::new("export").num_columns(2).show(ui, |ui| {
                    ui.label("port");
                    let shown = self
                        .port
                        .as_ref()
                        .map_or("choose…".to_owned(), |(n, p)| format!("{n}.{p}"));
                    egui::ComboBox::from_id_salt("export port")
                        .selected_text(shown)
                        .show_ui(ui, |ui| {
                            for (n, p) in &ports {
                                let chosen = self.port.as_ref() == Some(&(n.clone(), p.clone()));
                                if ui.selectable_label(chosen, format!("{n}.{p}")).clicked() {
                                    self.port = Some((n.clone(), p.clone()));
                                }
                            }
                        });
                    ui.end_row();
                    ui.label("width");
                    ui.add(egui::DragValue::new(&mut self.width).range(1..=16384));
                    ui.end_row();
                    ui.label("height");
                    ui.add(egui::DragValue::new(&mut self.height).range(1..=16384));
                    ui.end_row();
                    ui.label("lengths");
                    ui.vertical(|ui| {
                        let shown = self
                            .screen
                            .map_or("size unknown".to_owned(), |[w, h]| format!("{w}×{h}"));
                        ui.checkbox(&mut self.as_on_screen, format!("as on screen ({shown})"))
                            .on_hover_text(
                                "hatching cells, line widths and labels scale with the export \
                                 size, so the file is the figure on screen at a higher \
                                 resolution; off: they keep their sizes in output pixels \
                                 (finer at a larger size)",
                            );
                        ui.label(format!("× {:.2}", self.pixel_scale()));
                    });
                    ui.end_row();
                    ui.label("file");
                    ui.add(
                        egui::TextEdit::singleline(&mut self.path)
                            .hint_text("picture.png (relative to the graph)"),
                    );
                    ui.end_row();
                });
                ui.horizontal(|ui| {
                    let busy = self.is_busy();
                    if ui.add_enabled(!busy, egui::Button::new("Export")).clicked() {
                        requested = true;
                    }
                    if busy {
                        ui.spinner();
                        ui.label("rendering…");
                    }
                });
                match &self.last {
                    Some(Ok(path)) => {
                        ui.label(format!("wrote {}", path.display()));
                    }
                    Some(Err(e)) => {
                        ui.colored_label(egui::Color32::LIGHT_RED, e);
                    }
                    None => {}
                }
            });
        self.open = open;
        if self.is_busy() {
            ctx.request_repaint_after(std::time::Duration::from_millis(50));
        }
        requested
    }
}
