//! The *Presets* menu as a gallery (issue 25): each preset with a thumbnail, its one-line
//! description and its inputs, and *Apply to my data…*, which opens the preset and asks for a
//! file for its main (first) input.
//!
//! Thumbnails are rendered once per preset file content, off the UI thread, and cached as PNGs
//! in the user's cache folder (`$XDG_CACHE_HOME/hatchery/thumbnails`, else
//! `~/.cache/hatchery/thumbnails`), so later runs show them at once.

use hatchery_graph::GraphDocument;
use std::collections::BTreeMap;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};
use std::sync::mpsc;

/// Thumbnail size in pixels.
pub const THUMB: (u32, u32) = (96, 72);

/// What the menu shows of one preset.
#[derive(Clone, Debug)]
pub struct PresetInfo {
    pub path: PathBuf,
    pub name: String,
    pub description: String,
    /// (name, type) of each input, in file order; the first is the main one.
    pub inputs: Vec<(String, String)>,
    /// The cached thumbnail's file (rendered when missing).
    thumbnail: PathBuf,
}

/// The presets in `dir`, sorted by name (files that do not parse are left out); their
/// thumbnails are cached in `cache`.
pub fn list(dir: &Path, cache: &Path) -> Vec<PresetInfo> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|d| {
            d.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "ron"))
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .filter_map(|path| {
            let text = std::fs::read_to_string(&path).ok()?;
            let (doc, _) = GraphDocument::parse(&text, Some(&path)).ok()?;
            let name = path.file_stem()?.to_string_lossy().into_owned();
            let mut h = DefaultHasher::new();
            text.hash(&mut h);
            let thumbnail = cache.join(format!("{name}-{:016x}.png", h.finish()));
            Some(PresetInfo {
                name,
                description: doc.description.clone(),
                inputs: doc
                    .inputs
                    .iter()
                    .map(|i| (i.name.clone(), i.kind.clone()))
                    .collect(),
                path,
                thumbnail,
            })
        })
        .collect()
}

/// Where thumbnails are cached by default.
pub fn cache_dir() -> PathBuf {
    crate::settings::xdg_dir("XDG_CACHE_HOME", ".cache").join("thumbnails")
}

/// Renders a preset's first SaveImage picture small (what the menu shows of it).
fn render(path: &Path) -> Result<image::RgbaImage, String> {
    let mut session =
        hatchery_nodes::Session::open(path, THUMB.0, THUMB.1).map_err(|e| e.to_string())?;
    let saver = session
        .graph
        .nodes()
        .find(|n| n.kind == "SaveImage")
        .map(|n| n.id.clone())
        .ok_or("no SaveImage node")?;
    let (node, port) = {
        let (n, p) = *session
            .graph
            .input_sources(&saver)
            .get(&0)
            .ok_or("unconnected saver")?;
        (n.to_owned(), p)
    };
    session.run(&[&node]).map_err(|e| e.to_string())?;
    let value = session
        .executor
        .output(&node, port)
        .ok_or("no picture")?
        .clone();
    hatchery_nodes::export::to_rgba8(&value, &session.ctx.gpu).map_err(|e| e.to_string())
}

/// Thumbnails: cached files loaded as textures, missing ones rendered by one background thread.
#[derive(Default)]
pub struct Thumbnails {
    textures: BTreeMap<PathBuf, egui::TextureHandle>,
    failed: BTreeMap<PathBuf, String>,
    started: bool,
    done: Option<mpsc::Receiver<(PathBuf, Result<(), String>)>>,
}

impl Thumbnails {
    /// Starts rendering the thumbnails of `presets` that are not cached (once).
    pub fn start(&mut self, presets: &[PresetInfo], ctx: &egui::Context) {
        if self.started {
            return;
        }
        self.started = true;
        let missing: Vec<(PathBuf, PathBuf)> = presets
            .iter()
            .filter(|p| !p.thumbnail.exists())
            .map(|p| (p.path.clone(), p.thumbnail.clone()))
            .collect();
        let (tx, rx) = mpsc::channel();
        self.done = Some(rx);
        let ctx = ctx.clone();
        std::thread::spawn(move || {
            for (preset, file) in missing {
                let result = render(&preset).and_then(|picture| {
                    std::fs::create_dir_all(file.parent().unwrap_or(Path::new(".")))
                        .map_err(|e| e.to_string())?;
                    // Atomically: a reader never sees half a picture.
                    hatchery_nodes::export::write_png(&picture, &file).map_err(|e| e.to_string())
                });
                if tx.send((file, result)).is_err() {
                    return;
                }
                ctx.request_repaint();
            }
        });
    }

    /// The texture of a preset's thumbnail, once it exists (`Err`: why there is none).
    pub fn get(
        &mut self,
        ctx: &egui::Context,
        preset: &PresetInfo,
    ) -> Option<Result<&egui::TextureHandle, &str>> {
        if let Some(rx) = &self.done {
            while let Ok((file, result)) = rx.try_recv() {
                if let Err(e) = result {
                    self.failed.insert(file, e);
                }
            }
        }
        if let Some(e) = self.failed.get(&preset.thumbnail) {
            return Some(Err(e));
        }
        if !self.textures.contains_key(&preset.thumbnail) {
            let picture = image::open(&preset.thumbnail).ok()?.to_rgba8();
            let size = [picture.width() as usize, picture.height() as usize];
            let color = egui::ColorImage::from_rgba_unmultiplied(size, picture.as_raw());
            let texture = ctx.load_texture(&preset.name, color, egui::TextureOptions::LINEAR);
            self.textures.insert(preset.thumbnail.clone(), texture);
        }
        self.textures.get(&preset.thumbnail).map(Ok)
    }
}

/// A thumbnail's place with a word in it (while it renders, or where it could not).
fn placeholder(ui: &mut egui::Ui, size: egui::Vec2, text: &str) -> egui::Response {
    let (r, response) = ui.allocate_exact_size(size, egui::Sense::hover());
    ui.painter().text(
        r.center(),
        egui::Align2::CENTER_CENTER,
        text,
        egui::FontId::proportional(11.0),
        ui.visuals().weak_text_color(),
    );
    response
}

/// What the user chose in the gallery.
pub enum Choice {
    Open(PathBuf),
    /// Open the preset and give its input (name, type) a file of the user's.
    Apply(PathBuf, String, String),
}

/// The gallery inside the *Presets* menu.
pub fn menu(ui: &mut egui::Ui, presets: &[PresetInfo], thumbs: &mut Thumbnails) -> Option<Choice> {
    thumbs.start(presets, ui.ctx());
    let mut choice = None;
    egui::ScrollArea::vertical()
        .max_height(560.0)
        .show(ui, |ui| {
            ui.set_min_width(440.0);
            for p in presets {
                ui.horizontal(|ui| {
                    let size = egui::vec2(THUMB.0 as f32, THUMB.1 as f32);
                    match thumbs.get(ui.ctx(), p) {
                        Some(Ok(t)) => {
                            ui.add(egui::Image::new((t.id(), size)));
                        }
                        Some(Err(e)) => {
                            placeholder(ui, size, "no picture").on_hover_text(e.to_owned());
                        }
                        None => {
                            placeholder(ui, size, "rendering…");
                        }
                    }
                    ui.vertical(|ui| {
                        if ui
                            .button(&p.name)
                            .on_hover_text(p.path.display().to_string())
                            .clicked()
                        {
                            choice = Some(Choice::Open(p.path.clone()));
                        }
                        ui.add(
                            egui::Label::new(egui::RichText::new(&p.description).small()).wrap(),
                        );
                        match p.inputs.first() {
                            Some((input, kind)) => {
                                let label = format!("Apply to my data… ({input}: {kind})");
                                if ui.small_button(label).clicked() {
                                    choice = Some(Choice::Apply(
                                        p.path.clone(),
                                        input.clone(),
                                        kind.clone(),
                                    ));
                                }
                            }
                            None => {
                                ui.weak("procedural: reads no data");
                            }
                        }
                    });
                });
                ui.separator();
            }
        });
    if choice.is_some() {
        ui.close();
    }
    choice
}
