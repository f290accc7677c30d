//! `hatchery-editor [graph.ron]`: the visual node editor.

use eframe::egui_wgpu;
use hatchery_editor::{EditorApp, EditorState};
use hatchery_gpu::GpuContext;
use std::path::PathBuf;
use std::sync::Arc;

fn main() -> anyhow::Result<()> {
    tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .init();
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        // Mesa prints a false "error:" line without it. Set before any other thread starts.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir()) };
    }
    let path = std::env::args_os().nth(1).map(PathBuf::from);
    // The window's device is asked for what graphs need (volume-sized 3-D textures, timestamps),
    // so that previews can render on it and be shown without copies.
    let mut setup = egui_wgpu::WgpuSetupCreateNew::without_display_handle();
    setup.device_descriptor = Arc::new(GpuContext::device_descriptor);
    let options = eframe::NativeOptions {
        renderer: eframe::Renderer::Wgpu,
        viewport: eframe::egui::ViewportBuilder::default()
            .with_title("hatchery editor")
            .with_inner_size([1400.0, 900.0]),
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: egui_wgpu::WgpuSetup::CreateNew(setup),
            ..Default::default()
        },
        ..Default::default()
    };
    eframe::run_native(
        "hatchery editor",
        options,
        Box::new(move |cc| {
            let mut app = EditorApp::with_creation_context(EditorState::new(), cc)
                .with_settings_file(hatchery_editor::settings::Settings::default_path());
            if let Some(path) = &path {
                app.open(path);
            }
            Ok(Box::new(app))
        }),
    )
    .map_err(|e| anyhow::anyhow!("{e}"))
}
