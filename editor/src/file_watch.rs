//! Wakes the editor when a file a node reads its ports from (a custom shader) changes on disk.
//!
//! A thread looks at the files' modification stamps a few times a second and asks egui for a
//! repaint when one changed; the frame that follows notices the change itself
//! (`EditorState::poll_watched_files`) and re-reads, re-validates and re-renders. Polling a
//! handful of `stat`s is simpler than an OS notification crate and works on every file system
//! (network and container mounts included); an idle editor repaints only on a change.

use std::path::PathBuf;
use std::sync::{Arc, Mutex, Weak};
use std::time::Duration;

/// How often the thread looks.
const INTERVAL: Duration = Duration::from_millis(250);

type Stamp = Option<hatchery_nodes::custom_shader::Stamp>;

/// What identifies a version of the file (the same stamp the node's cache uses).
pub fn stamp(path: &std::path::Path) -> Stamp {
    hatchery_nodes::custom_shader::stamp(path)
}

/// The watching thread's handle; the thread ends when this is dropped.
pub struct FileWatch {
    files: Arc<Mutex<Vec<PathBuf>>>,
}

impl FileWatch {
    /// Starts watching nothing; `ctx` is asked to repaint on a change.
    pub fn spawn(ctx: egui::Context) -> Self {
        let files: Arc<Mutex<Vec<PathBuf>>> = Arc::default();
        let weak: Weak<Mutex<Vec<PathBuf>>> = Arc::downgrade(&files);
        let _ = std::thread::Builder::new()
            .name("hatchery-file-watch".into())
            .spawn(move || {
                let mut seen: Vec<(PathBuf, Stamp)> = Vec::new();
                while let Some(files) = weak.upgrade() {
                    // Copied out first: a slow file system must not hold the UI's lock.
                    let paths: Vec<PathBuf> = files.lock().map(|f| f.clone()).unwrap_or_default();
                    drop(files);
                    let now: Vec<(PathBuf, Stamp)> =
                        paths.into_iter().map(|p| (p.clone(), stamp(&p))).collect();
                    if now != seen {
                        seen = now;
                        ctx.request_repaint();
                    }
                    std::thread::sleep(INTERVAL);
                }
            });
        Self { files }
    }

    /// The files to watch (called every frame with the graph's current list).
    pub fn set(&self, paths: Vec<PathBuf>) {
        if let Ok(mut files) = self.files.lock()
            && *files != paths
        {
            *files = paths;
        }
    }
}
