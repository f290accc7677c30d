//! `hatchery-editor [graph.ron]`: the visual node editor.

use hatchery_editor::{EditorApp, EditorState};
use std::path::PathBuf;

fn main() -> anyhow::Result<()> {
    tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .init();
    let mut app = EditorApp::new(EditorState::new());
    if let Some(path) = std::env::args_os().nth(1).map(PathBuf::from) {
        app.open(&path);
    }
    let options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    eframe::run_native(
        "hatchery editor",
        options,
        Box::new(move |_cc| Ok(Box::new(app))),
    )
    .map_err(|e| anyhow::anyhow!("{e}"))
}
