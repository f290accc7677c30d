//! The Inspector's widget for a data value that may be given relative to the data (issue 25):
//! iso values and map floors.

use egui::Ui;
use hatchery_graph::{ParamSpec, ParamValue};

/// A data value that may be given relative to the data (issue 25): a number field or the
/// relative form as text, a menu to switch between the forms, and what the last render
/// resolved it to.
pub fn widget(
    ui: &mut Ui,
    spec: &ParamSpec,
    current: &ParamValue,
    resolved: Option<&str>,
) -> (Option<ParamValue>, egui::Rect) {
    let mut changed = None;
    let mut field_rect = egui::Rect::NOTHING;
    ui.horizontal(|ui| {
        match current {
            ParamValue::Relative(_, written) => {
                let id = ui.id().with(("relative", spec.name));
                let mut text = ui
                    .data(|d| d.get_temp::<String>(id))
                    .unwrap_or_else(|| written.clone());
                let field = ui.add(egui::TextEdit::singleline(&mut text).desired_width(110.0));
                if field.lost_focus() {
                    ui.data_mut(|d| d.remove::<String>(id));
                    match spec.parse_cli(&text) {
                        Ok(v) if &v != current => changed = Some(v),
                        _ => {}
                    }
                } else if field.has_focus() {
                    ui.data_mut(|d| d.insert_temp(id, text));
                }
                field_rect = field.rect;
                field.on_hover_text(format!(
                    "{}: a number, percentile(P), range(F) or otsu",
                    spec.doc
                ));
            }
            _ => {
                let r = ui.scope(|ui| crate::param_widget::param_widget(ui, spec, current));
                field_rect = r.response.rect;
                changed = r.inner;
            }
        }
        let number = resolved
            .and_then(|t| t.rsplit("= ").next())
            .and_then(|t| t.parse::<f64>().ok())
            .or(match current {
                ParamValue::Float(x) => Some(*x),
                _ => None,
            });
        egui::ComboBox::from_id_salt(("relative-form", spec.name))
            .selected_text(match current {
                ParamValue::Relative(..) => "relative",
                _ => "value",
            })
            .width(70.0)
            .show_ui(ui, |ui| {
                let forms = [
                    ("value", number.map(ParamValue::Float)),
                    (
                        "percentile(50)",
                        Some(ParamValue::relative(
                            hatchery_graph::RelativeValue::Percentile(50.0),
                        )),
                    ),
                    (
                        "range(0.5)",
                        Some(ParamValue::relative(hatchery_graph::RelativeValue::Range(
                            0.5,
                        ))),
                    ),
                    (
                        "otsu",
                        Some(ParamValue::relative(hatchery_graph::RelativeValue::Otsu)),
                    ),
                ];
                for (label, value) in forms {
                    if let Some(value) = value
                        && ui.selectable_label(false, label).clicked()
                    {
                        changed = Some(value);
                    }
                }
            })
            .response
            .on_hover_text("give the value in data units, or relative to the connected volume");
        if let (ParamValue::Relative(..), Some(number)) = (current, number) {
            ui.weak(format!("= {number}"))
                .on_hover_text("what the last render resolved it to, in data units");
        }
    });
    (changed, field_rect)
}
