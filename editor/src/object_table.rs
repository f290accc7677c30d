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
                if let Some(tf) = tf_menu(ui, (salt, row.id), row.tf.as_deref()) {
                    row.tf = tf;
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

/// The transfer functions a row can use: the node's `tf` input, its inputs tf1–tf3, or a preset
/// (with its colour ramp drawn beside its name). Returns the choice when the user made one
/// (`None` inside: the default `tf` input).
fn tf_menu(
    ui: &mut Ui,
    salt: impl std::hash::Hash + std::fmt::Debug,
    current: Option<&str>,
) -> Option<Option<String>> {
    let shown = current.unwrap_or("tf");
    let mut chosen = None;
    egui::ComboBox::from_id_salt(("object-tf", salt))
        .selected_text(shown)
        .width(70.0)
        .show_ui(ui, |ui| {
            let inputs = [
                (None, "tf (the tf input)"),
                (Some("1"), "1 (input tf1)"),
                (Some("2"), "2 (input tf2)"),
                (Some("3"), "3 (input tf3)"),
            ];
            for (value, label) in inputs {
                if ui.selectable_label(current == value, label).clicked() {
                    chosen = Some(value.map(str::to_owned));
                }
            }
            ui.separator();
            for preset in hatchery_data::transfer_function::PRESETS {
                ui.horizontal(|ui| {
                    ramp(ui, preset);
                    if ui.selectable_label(current == Some(*preset), *preset).clicked() {
                        chosen = Some(Some((*preset).to_owned()));
                    }
                });
            }
        })
        .response
        .on_hover_text("this object's transfer function: an input of the node or a preset over the volume's range");
    chosen
}

/// A small preview of a preset: its colours over its range, on a checkerboard-free dark ground
/// (opacity darkens).
fn ramp(ui: &mut Ui, preset: &str) {
    use hatchery_data::transfer_function::TransferFunction1D;
    let (rect, _) = ui.allocate_exact_size(egui::vec2(48.0, 12.0), egui::Sense::hover());
    let Some(f) = TransferFunction1D::preset(preset, [0.0, 1.0])
        .and_then(|p| TransferFunction1D::from_points(&p).ok())
    else {
        return;
    };
    let steps = 24;
    for i in 0..steps {
        let v = (i as f32 + 0.5) / steps as f32;
        let [r, g, b, a] = f.lookup(v);
        let a = a.clamp(0.0, 1.0).sqrt();
        let c = egui::Color32::from_rgb(
            (r * a * 255.0) as u8,
            (g * a * 255.0) as u8,
            (b * a * 255.0) as u8,
        );
        let x0 = rect.left() + rect.width() * i as f32 / steps as f32;
        let x1 = rect.left() + rect.width() * (i + 1) as f32 / steps as f32;
        ui.painter().rect_filled(
            egui::Rect::from_min_max(egui::pos2(x0, rect.top()), egui::pos2(x1, rect.bottom())),
            0.0,
            c,
        );
    }
}
