//! The Inspector's editors for parameters that are more than a number: the curve editors of
//! `TransferFunction1D` and `StyleTransferFunction`, the object table of `ObjectStyles` and the
//! style picker of `StyleSet` (chosen by kind in [`super::inspector`]).

use super::node_param;
use crate::app::EditorApp;
use egui::{Color32, Id, Ui};
use hatchery_graph::ParamValue;

/// The curve editor of a `TransferFunction1D` node. Editing a preset turns it into `custom`
/// points (the preset's points over the range it spans now), so the look does not jump.
pub(crate) fn transfer_function_section(
    app: &mut EditorApp,
    ui: &mut Ui,
    id: &str,
    node: &hatchery_graph::NodeDoc,
) {
    let value = |name: &str| node_param(&app.state, node, name);
    let text = |v: Option<ParamValue>| match v {
        Some(ParamValue::Text(t) | ParamValue::Choice(t)) => t,
        _ => String::new(),
    };
    let float = |v: Option<ParamValue>| match v {
        Some(ParamValue::Float(x)) => x as f32,
        _ => 0.0,
    };
    let preset = text(value("preset"));
    let range = app
        .preview
        .tf_domains
        .get(id)
        .copied()
        .unwrap_or([float(value("range_min")), float(value("range_max"))]);
    ui.label("Transfer function").on_hover_text(
        "drag a point to move it, double-click to add one, right-click a point to remove it",
    );
    let Some(written) = resolved_text(app, id, "points", text(value("points"))) else {
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
    let context = app.preview.tf_domains.get(id).copied();
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
        let _ = app.state.set_params(id, &values, "transfer function edit");
    }
    ui.separator();
}

/// The curve editor of a `StyleTransferFunction` node's `nodes` (per-label rows stay text),
/// its points named and coloured after the connected `StyleSet`.
pub(crate) fn style_function_section(
    app: &mut EditorApp,
    ui: &mut Ui,
    id: &str,
    node: &hatchery_graph::NodeDoc,
) {
    let Some(ParamValue::Text(text)) = node_param(&app.state, node, "nodes") else {
        return;
    };
    ui.label("Style transfer function").on_hover_text(
        "drag a point to move it, double-click to add one, right-click a point to remove it; \
         click a point to pick its style",
    );
    let Some(text) = resolved_text(app, id, "nodes", text) else {
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
    let doc = app.state.doc();
    let styles = doc
        .edges
        .iter()
        .find(|e| e.to.0 == id && e.to.1 == "styles")
        .and_then(|e| doc.nodes.iter().find(|n| n.id == e.from.0))
        .and_then(|set| match node_param(&app.state, set, "styles") {
            Some(ParamValue::Text(styles)) => Some(crate::style_picker::style_looks(&styles)),
            _ => None,
        })
        .unwrap_or_default();
    let context = app.preview.tf_domains.get(id).copied();
    let editor_id = Id::new(("style tf editor", id));
    if crate::curve_editor::style_curve_editor(ui, editor_id, &mut nodes, context, &styles) {
        let text = hatchery_data::style::StyleTransferFunction::format(&nodes);
        let _ = app.state.set_params(
            id,
            &[("nodes", ParamValue::Text(text))],
            "style function edit",
        );
    }
    ui.separator();
}

/// The object table of an `ObjectStyles` node, its objects named after the connected labels.
pub(crate) fn object_styles_section(
    app: &mut EditorApp,
    ui: &mut Ui,
    id: &str,
    node: &hatchery_graph::NodeDoc,
) {
    let Some(ParamValue::Text(text)) = node_param(&app.state, node, "objects") else {
        return;
    };
    ui.label("Objects");
    let doc = app.state.doc();
    let names: Vec<(u16, String)> = doc
        .edges
        .iter()
        .find(|e| e.to.0 == id && e.to.1 == "labels")
        .and_then(|e| app.preview.object_names.get(&e.from.0))
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
        let _ = app.state.set_params(
            id,
            &[("objects", ParamValue::Text(text))],
            "object table edit",
        );
    }
    ui.separator();
}

/// The lit-sphere style picker of a `StyleSet` node.
pub(crate) fn styles_section(
    app: &mut EditorApp,
    ui: &mut Ui,
    id: &str,
    node: &hatchery_graph::NodeDoc,
) {
    let Some(ParamValue::Text(styles)) = node_param(&app.state, node, "styles") else {
        return;
    };
    ui.label("Styles");
    if let Some(new) = crate::style_picker::style_picker(ui, &mut app.style_thumbnails, &styles) {
        let _ = app
            .state
            .set_params(id, &[("styles", ParamValue::Text(new))], "styles edit");
    }
    ui.separator();
}

/// The text of a point list as a curve editor draws it: as written when every value is a
/// number; with values relative to the data (`range(30/255): …`) as the last render
/// resolved them (`None` before it ran). Editing the curve then writes numbers.
fn resolved_text(app: &EditorApp, node: &str, param: &str, written: String) -> Option<String> {
    let relative = written.split(';').any(|e| {
        e.split_once(':')
            .is_some_and(|(v, _)| !v.trim().is_empty() && v.trim().parse::<f32>().is_err())
    });
    if !relative {
        return Some(written);
    }
    app.preview.resolved.get(node)?.get(param).cloned()
}
