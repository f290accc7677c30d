//! The fuzz targets' shared code: what each target does with one input. The same files are
//! compiled into the replay tests of hatchery-data and hatchery-graph (see `docs/fuzzing.md`).

pub mod data_targets;
pub mod graph_target;

use std::sync::OnceLock;

/// The process's scratch folder (the fuzzer runs one input at a time).
pub fn scratch() -> &'static data_targets::Scratch {
    static SCRATCH: OnceLock<data_targets::Scratch> = OnceLock::new();
    SCRATCH.get_or_init(data_targets::Scratch::new)
}
