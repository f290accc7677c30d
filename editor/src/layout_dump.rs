//! Where things are on screen, written to a file for scripted checks under a real X server
//! (`scripts/editor-smoke.sh` clicks with xdotool at these positions). Off unless the
//! `HATCHERY_EDITOR_LAYOUT` environment variable names a file.

use std::collections::BTreeMap;
use std::path::PathBuf;

#[derive(Default)]
pub struct LayoutDump {
    file: Option<PathBuf>,
    rects: BTreeMap<String, egui::Rect>,
    written: String,
}

impl LayoutDump {
    /// Reads `HATCHERY_EDITOR_LAYOUT`.
    pub fn from_env() -> Self {
        LayoutDump {
            file: std::env::var_os("HATCHERY_EDITOR_LAYOUT").map(PathBuf::from),
            ..Default::default()
        }
    }

    pub fn enabled(&self) -> bool {
        self.file.is_some()
    }

    /// Records a rectangle (screen points) under a name, e.g. `node:camera`, `param:iso`.
    pub fn record(&mut self, name: String, rect: egui::Rect) {
        if self.enabled() {
            self.rects.insert(name, rect);
        }
    }

    /// Writes `name x0 y0 x1 y1` lines in window pixels when they changed, then starts afresh.
    pub fn flush(&mut self, pixels_per_point: f32) {
        let Some(file) = &self.file else {
            return;
        };
        let mut text = String::new();
        for (name, r) in &self.rects {
            let r = *r * pixels_per_point;
            text += &format!(
                "{name} {:.0} {:.0} {:.0} {:.0}\n",
                r.min.x, r.min.y, r.max.x, r.max.y
            );
        }
        self.rects.clear();
        if text != self.written {
            // Atomically, so a reader never sees half a file.
            if hatchery_graph::atomic::write_bytes_atomically(file, text.as_bytes()).is_ok() {
                self.written = text;
            }
        }
    }
}
