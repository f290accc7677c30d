//! hatchery's visual node editor: an egui-snarl canvas over a [`hatchery_graph::GraphDocument`].
//!
//! - [`state::EditorState`]: the document, undo/redo, selection, validation errors, autosave
//!   recovery — no egui types, testable on its own.
//! - [`app::EditorApp`]: the egui user interface (canvas, inspector, viewport, menus).
//! - [`preview::Preview`]: renders the previewed output through `hatchery_nodes::Session`.

pub mod app;
pub mod preview;
pub mod state;

pub use app::EditorApp;
pub use state::EditorState;
