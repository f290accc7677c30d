//! The widget of one plain parameter (number, switch, choice, colour, vector, text), shared
//! by the Inspector and the data-relative value editor.

use egui::Ui;
use hatchery_graph::{ParamKind, ParamSpec, ParamValue};

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
