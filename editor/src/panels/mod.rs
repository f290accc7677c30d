//! The editor's panels, each in its own module behind [`Panel`]:
//!
//! - [`menu`]: the menu bar and the status line ([`menu::MenuBar`], [`menu::StatusLine`]), and
//!   the keyboard shortcuts;
//! - [`canvas`]: the node canvas ([`canvas::Canvas`]; its snarl viewer in [`canvas_viewer`], its
//!   zoom, *Frame all* and zoomed-out drawing in [`canvas_zoom`]);
//! - [`inspector`]: the Inspector ([`inspector::Inspector`]; the kind-specific editors in
//!   [`inspector_sections`]);
//! - [`viewport`]: the picture and the camera it drives ([`viewport::Viewport`]).
//!
//! [`EditorApp::ui`] places them in the window; their state lives in [`EditorApp`]. The panel
//! modules use this one (the trait, `node_param`) and [`crate::app`], not each other (but for
//! a panel and its own helper module).

pub mod canvas;
pub mod canvas_viewer;
pub mod canvas_zoom;
pub mod inspector;
pub mod inspector_sections;
pub mod menu;
pub mod viewport;

use crate::app::EditorApp;
use crate::state::EditorState;
use egui::Ui;
use hatchery_graph::ParamValue;

/// One part of the editor's window, drawn into the `ui` it is placed in (an `egui::Panel`, the
/// central panel) from the editor's state, which it may change.
pub trait Panel {
    fn show(&mut self, app: &mut EditorApp, ui: &mut Ui);
}

/// A node's parameter as the graph will use it: the file's value, else the schema's default.
fn node_param(
    state: &EditorState,
    node: &hatchery_graph::NodeDoc,
    name: &str,
) -> Option<ParamValue> {
    let schema = hatchery_graph::node_schema(&state.registry, state.doc(), node)?;
    let spec = schema.param(name)?;
    match node.params.get(name) {
        Some(raw) => spec.convert(raw).ok(),
        None => Some(spec.default.clone()),
    }
}
