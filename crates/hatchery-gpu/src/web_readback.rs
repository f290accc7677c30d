//! Read-back in the browser, between passes.
//!
//! A few nodes read GPU results on the CPU mid-graph (AnnotationLayout reads the silhouette it
//! places labels around). Natively the pass waits for the copy. A page cannot wait: a buffer's
//! mapping resolves only after the running task returns. So in the browser a read-back that has
//! not arrived yet starts the copy and fails the node with a message saying so; the page then
//! awaits the copies (`GpuContext::collect_readbacks`) and runs the pass again. The executor
//! keeps every node that succeeded, so the second pass re-runs only the node that read and what
//! follows it, and its read finds the copy by what it read (the same texture or buffer, since
//! the nodes before it were not run again). The copies are forgotten when a new picture starts
//! (`GpuContext::forget_readbacks`): a changed view renders new contents.

/// What a read-back copied: a texture, or the first bytes of a buffer.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum ReadKey {
    Texture(wgpu::Texture),
    Buffer(wgpu::Buffer, u64),
}

#[cfg(target_arch = "wasm32")]
pub use web::WebReadbacks;

#[cfg(target_arch = "wasm32")]
mod web {
    use super::ReadKey;
    use std::collections::HashMap;
    use std::sync::{Arc, Mutex};

    type Mapped = Arc<Mutex<Option<Result<(), String>>>>;

    struct Pending {
        key: ReadKey,
        staging: wgpu::Buffer,
        mapped: Mapped,
    }

    #[derive(Default)]
    struct State {
        ready: HashMap<ReadKey, Vec<u8>>,
        pending: Vec<Pending>,
    }

    /// The copies asked for and arrived (shared by the clones of a context).
    #[derive(Clone, Default)]
    pub struct WebReadbacks {
        state: Arc<Mutex<State>>,
    }

    impl WebReadbacks {
        fn state(&self) -> std::sync::MutexGuard<'_, State> {
            self.state.lock().unwrap_or_else(|e| e.into_inner())
        }

        /// The bytes of `staging` (a copy of `key`) once arrived; until then an error asking
        /// for the pass to be run again, after the mapping has been requested.
        pub(crate) fn read(&self, key: ReadKey, staging: &wgpu::Buffer) -> Result<Vec<u8>, String> {
            let mut state = self.state();
            if let Some(bytes) = state.ready.get(&key) {
                return Ok(bytes.clone());
            }
            if !state.pending.iter().any(|p| p.key == key) {
                let mapped: Mapped = Default::default();
                let sink = mapped.clone();
                staging.map_async(wgpu::MapMode::Read, .., move |result| {
                    *sink.lock().unwrap_or_else(|e| e.into_inner()) =
                        Some(result.map_err(|e| e.to_string()));
                });
                state.pending.push(Pending {
                    key,
                    staging: staging.clone(),
                    mapped,
                });
            }
            Err(READ_AGAIN.into())
        }
    }

    /// The message of a read-back that has not arrived (the page recognises none: it asks
    /// `GpuContext::readbacks_pending`).
    const READ_AGAIN: &str = "waiting for a GPU read-back (in the browser these arrive between passes; run the pass again)";

    impl WebReadbacks {
        /// Whether the last pass asked for read-backs that have not been collected.
        pub(crate) fn pending(&self) -> bool {
            !self.state().pending.is_empty()
        }

        /// Keeps the read-backs that have arrived for the next pass. Returns whether every one
        /// has. Errors: a failed mapping, as (what was read, why).
        pub(crate) fn collect(&self) -> Result<bool, (String, String)> {
            let mut state = self.state();
            let pending = std::mem::take(&mut state.pending);
            for p in pending {
                let outcome = p.mapped.lock().unwrap_or_else(|e| e.into_inner()).take();
                match outcome {
                    None => state.pending.push(p),
                    Some(Err(message)) => return Err((format!("{:?}", p.key), message)),
                    Some(Ok(())) => {
                        let bytes = p
                            .staging
                            .get_mapped_range(..)
                            .map_err(|e| (format!("{:?}", p.key), e.to_string()))?
                            .to_vec();
                        p.staging.unmap();
                        state.ready.insert(p.key, bytes);
                    }
                }
            }
            Ok(state.pending.is_empty())
        }

        /// Forgets the arrived read-backs: the next picture reads afresh.
        pub(crate) fn forget(&self) {
            let mut state = self.state();
            state.ready.clear();
            state.pending.clear();
        }
    }
}
