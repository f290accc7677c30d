//! The *Data* panel (issue 25): a graph's inputs — the files it reads — with a button to pick
//! another file for each, and drop targets: a file dropped on an input's row replaces that
//! input, and the whole graph re-runs on it.

use crate::files::{FileKind, FilePicker, Purpose};
use crate::state::EditorState;
use egui::{Rect, Ui};
use hatchery_graph::InputKind;
use std::path::Path;

/// Gives input `name` the file `path` (checked as the command line's `--input` checks it),
/// stored relative to the graph's folder; one undo step. Errors name the input.
pub fn set_input(state: &mut EditorState, name: &str, path: &Path) -> Result<(), String> {
    let input = state
        .doc()
        .inputs
        .iter()
        .find(|i| i.name == name)
        .cloned()
        .ok_or_else(|| format!("no input `{name}`"))?;
    let kind =
        InputKind::parse(&input.kind).ok_or_else(|| format!("input `{name}`: unknown type"))?;
    hatchery_nodes::graph_inputs::check_input_file(name, kind, path).map_err(|e| e.to_string())?;
    let stored = crate::files::path_for_graph(state.base_dir().as_deref(), path);
    state.apply(None, |d, _| {
        hatchery_graph::inputs::set_in_document(d, name, &stored).map_err(|e| e.to_string())
    })?;
    state.status = format!("input `{name}`: {}", path.display());
    Ok(())
}

/// The file kind the picker offers for an input.
fn file_kind(kind: &str) -> Option<FileKind> {
    match InputKind::parse(kind)? {
        InputKind::Volume | InputKind::Labels => Some(FileKind::Volume),
        InputKind::Mesh => Some(FileKind::Mesh),
        InputKind::Names => None,
    }
}

/// Draws the panel; returns each input's row (screen rectangle) for drops and scripted checks.
pub fn show(state: &mut EditorState, ui: &mut Ui, picker: &mut FilePicker) -> Vec<(String, Rect)> {
    let mut rows = Vec::new();
    let inputs = state.doc().inputs.clone();
    egui::CollapsingHeader::new("Data")
        .default_open(true)
        .show(ui, |ui| {
            if inputs.is_empty() {
                ui.weak("This graph declares no inputs (it reads no data file, or says none).");
                return;
            }
            ui.weak("Drop a file on an input, or pick one: the whole graph re-runs on it.");
            for input in &inputs {
                let current = input
                    .to
                    .first()
                    .and_then(|(n, p)| state.doc().node(n)?.params.get(p).cloned())
                    .and_then(|v| match v {
                        ron::Value::String(s) => Some(s),
                        _ => None,
                    })
                    .unwrap_or_default();
                let shown = Path::new(&current)
                    .file_name()
                    .map_or(current.clone(), |n| n.to_string_lossy().into_owned());
                let row = ui
                    .horizontal(|ui| {
                        ui.strong(&input.name).on_hover_text(&input.doc);
                        ui.weak(format!("({})", input.kind));
                        ui.label(shown).on_hover_text(&current);
                        if ui
                            .button("Pick…")
                            .on_hover_text("pick another file")
                            .clicked()
                        {
                            let folder =
                                Path::new(&current)
                                    .parent()
                                    .map(|p| match state.base_dir() {
                                        Some(base) if p.is_relative() => base.join(p),
                                        _ => p.to_path_buf(),
                                    });
                            picker.open(
                                Purpose::Input {
                                    name: input.name.clone(),
                                },
                                file_kind(&input.kind),
                                folder,
                            );
                        }
                    })
                    .response;
                rows.push((input.name.clone(), row.rect));
            }
        });
    rows
}
