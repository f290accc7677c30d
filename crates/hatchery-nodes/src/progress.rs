//! What a render pass is doing, shared with the thread that asked for it: the steps planned,
//! the one running and since when (the editor draws it over the picture), and a cancel flag a
//! newer request sets (the executor stops between steps; what ran stays cached).

use std::collections::HashMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;
use web_time::Instant;

/// A pass's progress, as last reported.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PassProgress {
    /// The steps that execute in this pass, in order (a fused pass by its last member).
    pub planned: Vec<String>,
    /// How many of them have finished.
    pub done: usize,
    /// The step running now and when it started.
    pub current: Option<(String, Instant)>,
    /// How long the running step took the last time it ran, GPU work included.
    pub estimate: Option<Duration>,
}

/// Shared between a [`crate::RenderContext`] ([`crate::RenderContext::set_progress`]) and
/// whoever watches or cancels its passes.
#[derive(Default)]
pub struct Progress {
    /// Called when a step starts or ends (the editor asks for a repaint).
    notify: Option<Box<dyn Fn() + Send + Sync>>,
    pass: Mutex<PassProgress>,
    cancel: AtomicBool,
    /// When the request being rendered (one or more passes) started; `None` when idle.
    request: Mutex<Option<Instant>>,
    /// Each step's last duration, from its start to its end (after its GPU work).
    durations: Mutex<HashMap<String, Duration>>,
}

impl Progress {
    /// A progress that calls `notify` whenever a step starts or ends.
    pub fn notifying(notify: impl Fn() + Send + Sync + 'static) -> Self {
        Progress {
            notify: Some(Box::new(notify)),
            ..Progress::default()
        }
    }

    fn changed(&self) {
        if let Some(notify) = &self.notify {
            notify();
        }
    }

    /// The latest report.
    pub fn snapshot(&self) -> PassProgress {
        self.pass.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// A request starts rendering: passes run again (a cancel was for an older request).
    pub fn begin_request(&self) {
        self.cancel.store(false, Ordering::Relaxed);
        *self.request.lock().unwrap_or_else(|e| e.into_inner()) = Some(Instant::now());
    }

    /// The request is done (rendered, failed or cancelled).
    pub fn end_request(&self) {
        *self.request.lock().unwrap_or_else(|e| e.into_inner()) = None;
        *self.pass.lock().unwrap_or_else(|e| e.into_inner()) = PassProgress::default();
    }

    /// How long the request being rendered has been running; `None` when idle.
    pub fn busy_for(&self) -> Option<Duration> {
        self.request
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .map(|t| t.elapsed())
    }

    /// Asks the running pass to stop at its next step (and every pass after, until the next
    /// [`Self::begin_request`]).
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    pub fn is_cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    pub(crate) fn begin_pass(&self, planned: &[&str]) {
        *self.pass.lock().unwrap_or_else(|e| e.into_inner()) = PassProgress {
            planned: planned.iter().map(|s| (*s).to_owned()).collect(),
            done: 0,
            current: None,
            estimate: None,
        };
    }

    pub(crate) fn begin_node(&self, node: &str) {
        let mut pass = self.pass.lock().unwrap_or_else(|e| e.into_inner());
        if pass.planned.iter().any(|p| p == node) {
            pass.current = Some((node.to_owned(), Instant::now()));
            pass.estimate = self
                .durations
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .get(node)
                .copied();
            drop(pass);
            self.changed();
        }
    }

    pub(crate) fn end_node(&self, node: &str) {
        let mut pass = self.pass.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, since)) = pass.current.as_ref().filter(|(n, _)| n == node) {
            self.durations
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .insert(node.to_owned(), since.elapsed());
            pass.current = None;
            pass.estimate = None;
            pass.done += 1;
            drop(pass);
            self.changed();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_run_again_is_estimated_by_its_last_duration() {
        let progress = Progress::default();
        for run in 0..2 {
            progress.begin_pass(&["load", "ray"]);
            progress.begin_node("load");
            progress.end_node("load");
            progress.begin_node("ray");
            let shown = progress.snapshot();
            assert_eq!(shown.done, 1);
            assert_eq!(shown.current.as_ref().map(|(n, _)| n.as_str()), Some("ray"));
            match run {
                0 => assert_eq!(shown.estimate, None, "never ran before"),
                _ => assert!(
                    shown
                        .estimate
                        .is_some_and(|e| e >= Duration::from_millis(20)),
                    "{:?}",
                    shown.estimate
                ),
            }
            std::thread::sleep(Duration::from_millis(20));
            progress.end_node("ray");
            assert_eq!(progress.snapshot().done, 2);
        }
    }
}
