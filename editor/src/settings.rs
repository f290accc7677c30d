//! What the editor keeps between runs and between graphs: the canvas view (pan and zoom) of
//! every graph and of every group inside it, and the widths of the picture and Inspector panels.
//!
//! They are kept in a settings file of the editor's own ([`Settings::default_path`]:
//! `$XDG_CONFIG_HOME/hatchery/editor.ron`, else `~/.config/hatchery/editor.ron`), written when
//! the window closes — not in the graph file: a view is the user's, not the graph's (two people
//! opening one preset keep their own), it changes with every wheel notch (which must not mark
//! the graph unsaved nor touch a preset in `graphs/`), and the graph format stays as it is.
//! Views are keyed by the graph file's canonical path and the group shown (`""` outside
//! groups); an untitled graph's views last for the session only.

use egui::emath::TSTransform;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A canvas view: scaling, then the translation (x, y) of the graph → screen transform.
pub type View = [f32; 3];

/// hatchery's folder in an XDG base directory: `$var/hatchery`, else `~/<home>/hatchery` (the
/// system's temporary folder without a home).
pub fn xdg_dir(var: &str, home: &str) -> PathBuf {
    let base = std::env::var_os(var)
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(home)))
        .unwrap_or_else(std::env::temp_dir);
    base.join("hatchery")
}

/// The settings file's contents.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Settings {
    /// Views by graph (canonical path; `""`: untitled, not written) and level (group id, `""`
    /// outside groups).
    #[serde(default)]
    pub views: BTreeMap<String, BTreeMap<String, View>>,
    /// Outer widths of the panels by their egui id (`inspector`, `viewport`), points.
    #[serde(default)]
    pub panels: BTreeMap<String, f32>,
}

impl Settings {
    /// `$XDG_CONFIG_HOME/hatchery/editor.ron`, else `~/.config/hatchery/editor.ron`.
    pub fn default_path() -> PathBuf {
        xdg_dir("XDG_CONFIG_HOME", ".config").join("editor.ron")
    }

    /// The file's settings; none (the defaults) when it is missing or unreadable.
    pub fn load(path: &Path) -> Settings {
        std::fs::read_to_string(path)
            .ok()
            .and_then(|text| ron::from_str(&text).ok())
            .unwrap_or_default()
    }

    /// Writes the settings (atomically: a temporary file renamed over the old one).
    pub fn save(&self, path: &Path) -> Result<(), String> {
        let mut kept = self.clone();
        kept.views.remove("");
        let text = ron::ser::to_string_pretty(&kept, ron::ser::PrettyConfig::default())
            .map_err(|e| e.to_string())?;
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
        }
        let tmp = path.with_extension("ron.tmp");
        std::fs::write(&tmp, text).map_err(|e| e.to_string())?;
        std::fs::rename(&tmp, path).map_err(|e| e.to_string())
    }

    fn view(&self, key: &ViewKey) -> Option<TSTransform> {
        let [scaling, x, y] = *self.views.get(&key.graph)?.get(&key.level)?;
        (scaling.is_finite() && scaling > 0.0 && x.is_finite() && y.is_finite()).then_some(
            TSTransform {
                scaling,
                translation: egui::vec2(x, y),
            },
        )
    }

    fn set_view(&mut self, key: &ViewKey, t: TSTransform) {
        let view = [t.scaling, t.translation.x, t.translation.y];
        self.views
            .entry(key.graph.clone())
            .or_default()
            .insert(key.level.clone(), view);
    }
}

/// Which view the canvas shows: a graph's (canonical path, `""` untitled) at a level.
#[derive(Clone, Debug, PartialEq)]
struct ViewKey {
    graph: String,
    level: String,
}

/// What the canvas does when it shows another graph or level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViewChange {
    /// The view this graph and level had.
    Restore(TSTransform),
    /// None was kept: fit every node in.
    FrameAll,
}

/// Follows the graph and level the canvas shows and keeps each one's view in [`Settings`].
#[derive(Debug, Default)]
pub struct CanvasViews {
    shown: Option<ViewKey>,
    /// The graph file last asked about and its key (canonicalised once per file).
    path: Option<PathBuf>,
    graph: String,
}

impl CanvasViews {
    /// Called every frame before the canvas is drawn with the graph file, the level shown and
    /// last frame's view. When the graph or level changed, keeps the view that was shown under
    /// its graph and level and says what to show now.
    pub fn update(
        &mut self,
        settings: &mut Settings,
        path: Option<&Path>,
        level: Option<&str>,
        current: TSTransform,
    ) -> Option<ViewChange> {
        if self.path.as_deref() != path {
            self.path = path.map(Path::to_path_buf);
            self.graph = path.map_or_else(String::new, |p| {
                let p = p.canonicalize().unwrap_or_else(|_| p.to_path_buf());
                p.display().to_string()
            });
        }
        let key = ViewKey {
            graph: self.graph.clone(),
            level: level.unwrap_or_default().to_owned(),
        };
        if self.shown.as_ref() == Some(&key) {
            return None;
        }
        if let Some(old) = self.shown.replace(key.clone()) {
            settings.set_view(&old, current);
        }
        Some(match settings.view(&key) {
            Some(t) => ViewChange::Restore(t),
            None => ViewChange::FrameAll,
        })
    }

    /// Keeps the view shown now (before the settings are written).
    pub fn remember(&self, settings: &mut Settings, current: TSTransform) {
        if let Some(key) = &self.shown {
            settings.set_view(key, current);
        }
    }
}
