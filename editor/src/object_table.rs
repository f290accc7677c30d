//! The object table of an `ObjectStyles` node in the Inspector: one row per object of the
//! segmented volume (names from the connected labels), with its on/off switch, rendering mode,
//! local compositing, transfer function, iso value and importance. Edits rewrite the node's
//! `objects` text, which stays the file format (hatchery_nodes::object_styles).

use egui::{ComboBox, DragValue, Grid, Ui};
use hatchery_nodes::object_styles::{
    Row, compositing_named, compositing_names, mode_named, mode_names,
};
use hatchery_nodes::value::{Compositing, RenderMode};

fn mode_name(mode: RenderMode) -> &'static str {
    mode_names()
        .into_iter()
        .find(|n| mode_named(n) == Some(mode))
        .unwrap_or("?")
}

fn compositing_name(c: Compositing) -> &'static str {
    compositing_names()
        .into_iter()
        .find(|n| compositing_named(n) == Some(c))
        .unwrap_or("?")
}

/// Draws the table; returns true when a row changed, was added or removed. `names`: the
/// objects of the connected labels (id, name), when the graph has run.
pub fn object_table(ui: &mut Ui, salt: &str, rows: &mut Vec<Row>, names: &[(u16, String)]) -> bool {
    let mut changed = false;
    let name_of = |id: u16| {
        names
            .iter()
            .find(|(i, _)| *i == id)
            .map_or_else(|| format!("object {id}"), |(_, n)| n.clone())
    };
    let mut remove = None;
    Grid::new(("object table", salt))
        .striped(true)
        .num_columns(7)
        .show(ui, |ui| {
            for label in [
                "object",
                "mode",
                "compositing",
                "tf",
                "iso",
                "importance",
                "",
            ] {
                ui.strong(label);
            }
            ui.end_row();
            for (i, row) in rows.iter_mut().enumerate() {
                let name = name_of(row.id);
                changed |= ui
                    .checkbox(&mut row.enabled, format!("{} {name}", row.id))
                    .on_hover_text("draw this object")
                    .changed();
                let mode = mode_name(row.mode);
                ComboBox::from_id_salt(("mode", salt, i))
                    .selected_text(mode)
                    .show_ui(ui, |ui| {
                        for m in mode_names() {
                            if ui.selectable_label(m == mode, m).clicked() {
                                row.mode = mode_named(m).unwrap_or(row.mode);
                                changed = true;
                            }
                        }
                    });
                let compositing = compositing_name(row.compositing);
                ComboBox::from_id_salt(("compositing", salt, i))
                    .selected_text(compositing)
                    .show_ui(ui, |ui| {
                        for c in compositing_names() {
                            if ui.selectable_label(c == compositing, c).clicked() {
                                row.compositing = compositing_named(c).unwrap_or(row.compositing);
                                changed = true;
                            }
                        }
                    });
                let mut tf = row.tf.clone().unwrap_or_default();
                if ui
                    .add(egui::TextEdit::singleline(&mut tf).desired_width(56.0))
                    .on_hover_text("a TransferFunction1D preset, 1–3 for inputs tf1–tf3, empty: tf")
                    .changed()
                {
                    row.tf = (!tf.trim().is_empty()).then(|| tf.trim().to_string());
                    changed = true;
                }
                if row.compositing == Compositing::Iso {
                    let mut iso = row.iso.unwrap_or(0.0);
                    if ui.add(DragValue::new(&mut iso).speed(0.5)).changed() {
                        row.iso = Some(iso);
                        changed = true;
                    }
                } else {
                    ui.label("");
                }
                if ui
                    .add(
                        DragValue::new(&mut row.importance)
                            .range(0.0..=10.0)
                            .speed(0.01),
                    )
                    .on_hover_text(
                        "importance-driven rendering: where a less important object occludes \
                         this one it is drawn sparser (ImportanceCompositing)",
                    )
                    .changed()
                {
                    changed = true;
                }
                if ui
                    .small_button("x")
                    .on_hover_text(format!("remove {name}"))
                    .clicked()
                {
                    remove = Some(i);
                }
                ui.end_row();
            }
        });
    if let Some(i) = remove {
        rows.remove(i);
        changed = true;
    }
    let missing: Vec<&(u16, String)> = names
        .iter()
        .filter(|(id, _)| !rows.iter().any(|r| r.id == *id))
        .collect();
    if !missing.is_empty() {
        ComboBox::from_id_salt(("add object", salt))
            .selected_text("+ Add object")
            .show_ui(ui, |ui| {
                for (id, name) in missing {
                    if ui.selectable_label(false, format!("{id} {name}")).clicked() {
                        rows.push(Row {
                            id: *id,
                            mode: RenderMode::ShadedDvr,
                            compositing: Compositing::Over,
                            tf: None,
                            iso: None,
                            importance: 1.0,
                            enabled: true,
                        });
                        changed = true;
                    }
                }
            });
    }
    changed
}
