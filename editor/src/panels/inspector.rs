//! The Inspector: the Data panel, then the parameters of the node clicked last (with the
//! editors of [`super::inspector_sections`] that its parameters ask for above them).

use super::Panel;
use super::inspector_sections as sections;
use crate::app::EditorApp;
use crate::files::{FileKind, Purpose};
use crate::param_widget::param_widget;
use egui::{Color32, Ui};
use hatchery_graph::{InputKind, ParamKind, ParamSpec, ParamValue, Widget};
use std::path::{Path, PathBuf};

/// The Inspector (the right-hand panel).
pub struct Inspector;

impl Panel for Inspector {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui) {
        app.data_rows = crate::data_panel::show(&mut app.state, ui, &mut app.picker);
        for (name, rect) in &app.data_rows {
            app.layout.record(format!("input:{name}"), *rect);
        }
        ui.separator();
        ui.heading("Inspector");
        let Some(id) = app.state.inspected().map(str::to_owned) else {
            ui.label("Click a node to edit its parameters.");
            return;
        };
        if crate::groups::inspector(&mut app.state, ui, &id) {
            return;
        }
        if app.state.selection.len() > 1 {
            ui.weak(format!(
                "{} nodes selected; showing the last clicked",
                app.state.selection.len()
            ));
        }
        let Some(node) = app.state.doc().nodes.iter().find(|n| n.id == id).cloned() else {
            return;
        };
        ui.label(format!("{} ({})", node.id, node.kind));
        if let Some(e) = app.state.node_error(&id) {
            ui.colored_label(Color32::LIGHT_RED, e);
        }
        let doc = app.state.doc();
        let Some(schema) =
            hatchery_graph::node_schema(&app.state.registry, doc, &node).map(|s| (*s).clone())
        else {
            ui.label("unknown kind: no parameters to show");
            return;
        };
        ui.label(schema.doc).on_hover_text(schema.category);
        // Editors for the parameters that are more than a number, as their specs ask.
        for widget in schema.params.iter().filter_map(|spec| spec.widget) {
            match widget {
                Widget::TransferFunction => {
                    sections::transfer_function_section(app, ui, &id, &node)
                }
                Widget::StyleTransferFunction => {
                    sections::style_function_section(app, ui, &id, &node)
                }
                Widget::StyleList => sections::styles_section(app, ui, &id, &node),
                Widget::ObjectTable => sections::object_styles_section(app, ui, &id, &node),
                Widget::ShaderFile => {}
            }
        }
        egui::Grid::new("params").num_columns(3).show(ui, |ui| {
            for spec in &schema.params {
                let current = node
                    .params
                    .get(spec.name)
                    .and_then(|raw| spec.convert(raw).ok())
                    .unwrap_or_else(|| spec.default.clone());
                ui.label(spec.name).on_hover_text(spec.doc);
                let resolved = app
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
                app.layout.record(format!("param:{}", spec.name), rect);
                let widget = egui::InnerResponse::new(value, widget.response);
                if let Some(value) = widget.inner {
                    let dragging =
                        ui.input(|i| i.pointer.any_down()) || ui.ctx().egui_wants_keyboard_input();
                    let _ = app.state.set_param(&id, spec.name, value, dragging);
                }
                // A third column: the file dialog button of path parameters.
                if spec.kind == ParamKind::Path
                    && ui
                        .button("📂")
                        .on_hover_text(format!("choose {} with the file dialog", spec.name))
                        .clicked()
                {
                    choose_path(app, &node, spec, &current);
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
                        let _ = app.state.apply(None, |d, _| {
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
}

/// Opens the file dialog for a path parameter, in the folder of its current file.
fn choose_path(
    app: &mut EditorApp,
    node: &hatchery_graph::NodeDoc,
    spec: &ParamSpec,
    current: &ParamValue,
) {
    let base = app.state.base_dir();
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
    // The file filter follows what the parameter reads (label maps are volume files).
    let kind = match (spec.widget, spec.reads) {
        (Some(Widget::ShaderFile), _) => Some(FileKind::Shader),
        (_, Some(InputKind::Volume | InputKind::Labels)) => Some(FileKind::Volume),
        (_, Some(InputKind::Mesh)) => Some(FileKind::Mesh),
        _ => None,
    };
    let purpose = Purpose::Param {
        node: node.id.clone(),
        param: spec.name.to_owned(),
    };
    app.picker.open(purpose, kind, folder);
}
