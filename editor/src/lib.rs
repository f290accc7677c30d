//! hatchery's visual node editor: an egui-snarl canvas over a [`hatchery_graph::GraphDocument`].
//!
//! - [`state::EditorState`]: the document, undo/redo, selection, validation errors, autosave
//!   recovery — no egui types, testable on its own.
//! - [`app::EditorApp`]: the egui user interface; its panels (canvas, inspector, viewport,
//!   menus) are in [`panels`].
//! - [`preview::Preview`]: what the viewport and the pin thumbnails show, as egui textures.
//! - [`render_worker::RenderWorker`]: the thread that runs the graph (`hatchery_nodes::Session`)
//!   so the UI never waits for a frame.

pub mod add_menu;
pub mod app;
pub mod arrange;
pub mod curve_editor;
pub mod data_panel;
pub mod export_dialog;
pub mod file_watch;
pub mod files;
pub mod fonts;
pub mod frames;
pub mod gallery;
pub mod groups;
pub mod history_text;
pub mod layout_dump;
pub mod object_table;
pub mod paint;
pub mod panels;
pub mod param_widget;
pub mod picture;
pub mod preview;
pub mod relative_value;
pub mod render_progress;
pub mod render_worker;
pub mod selection;
pub mod settings;
pub mod shell;
pub mod state;
pub mod style_picker;

pub use app::EditorApp;
pub use state::EditorState;
