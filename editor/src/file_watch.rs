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
    /// The files to watch, each with the stamp the editor last saw.
    files: Arc<Mutex<Vec<(PathBuf, Stamp)>>>,
}

impl FileWatch {
    /// Starts watching nothing; `ctx` is asked to repaint on a change.
    pub fn spawn(ctx: egui::Context) -> Self {
        let files: Arc<Mutex<Vec<(PathBuf, Stamp)>>> = Arc::default();
        let weak: Weak<Mutex<Vec<(PathBuf, Stamp)>>> = Arc::downgrade(&files);
        let _ = std::thread::Builder::new()
            .name("hatchery-file-watch".into())
            .spawn(move || {
                let mut seen: Vec<(PathBuf, Stamp)> = Vec::new();
                while let Some(files) = weak.upgrade() {
                    // Copied out first: a slow file system must not hold the UI's lock.
                    let watched = files.lock().map(|f| f.clone()).unwrap_or_default();
                    drop(files);
                    let now: Vec<(PathBuf, Stamp)> =
                        watched.iter().map(|(p, _)| (p.clone(), stamp(p))).collect();
                    // Against the stamp this thread saw last, or for a file new to it the
                    // editor's: a file newly watched wakes nobody unless it changed since the
                    // editor looked (waking on the list alone woke tests mid-frame).
                    let changed = now.iter().zip(&watched).any(|((path, now), (_, editor))| {
                        let before = seen
                            .iter()
                            .find(|(p, _)| p == path)
                            .map_or(editor, |(_, s)| s);
                        now != before
                    });
                    seen = now;
                    if changed {
                        ctx.request_repaint();
                    }
                    std::thread::sleep(INTERVAL);
                }
            });
        Self { files }
    }

    /// The files to watch with the stamps the editor saw (called every frame with the graph's
    /// current list).
    pub fn set(&self, paths: Vec<(PathBuf, Stamp)>) {
        if let Ok(mut files) = self.files.lock()
            && *files != paths
        {
            *files = paths;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A watcher on a new context, and how often it asked for a repaint (egui calls back once
    /// until a frame runs; none runs here, so each watcher shows whether it woke at all).
    fn watcher() -> (FileWatch, Arc<AtomicUsize>) {
        let ctx = egui::Context::default();
        let woken = Arc::new(AtomicUsize::new(0));
        let counter = woken.clone();
        ctx.set_request_repaint_callback(move |_| {
            counter.fetch_add(1, Ordering::SeqCst);
        });
        (FileWatch::spawn(ctx), woken)
    }

    fn after_a_few_polls(woken: &AtomicUsize) -> usize {
        std::thread::sleep(INTERVAL * 4);
        woken.load(Ordering::SeqCst)
    }

    #[test]
    fn a_changed_file_wakes_the_editor_and_a_newly_watched_one_does_not() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.wgsl"), dir.path().join("b.wgsl"));
        std::fs::write(&a, "// a").unwrap();
        std::fs::write(&b, "// b").unwrap();
        // Watched as the editor last saw it: nothing to wake for; then changed on disk: a wake.
        let (watch, woken) = watcher();
        watch.set(vec![(a.clone(), stamp(&a))]);
        assert_eq!(
            after_a_few_polls(&woken),
            0,
            "an unchanged file woke the editor"
        );
        std::fs::write(&a, "// a, longer").unwrap();
        assert!(
            after_a_few_polls(&woken) >= 1,
            "a changed file did not wake the editor"
        );
        // Newly watched but changed since the editor looked (its stamp is another's): a wake.
        let (watch, woken) = watcher();
        watch.set(vec![(b.clone(), stamp(&a))]);
        assert!(
            after_a_few_polls(&woken) >= 1,
            "a file changed before it was watched did not wake the editor"
        );
    }
}
