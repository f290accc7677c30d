//! Batch rendering (issue 27): a job file names a graph, a frame size and the work — data sets
//! for the graph's inputs × a parameter sweep × a camera path — expanded into a deterministic
//! list of items. A process renders its shard of the items in one session, skipping those
//! already done, writing outputs atomically and a manifest after each item; `merge` checks that
//! every item is there once. Schedulers (Slurm arrays, Kubernetes Indexed Jobs, Dask) only start
//! processes: this crate is what each one runs.
#![forbid(unsafe_code)]

pub mod animation;
pub mod error;
pub mod files;
pub mod job;
pub mod manifest;
pub mod run;

pub use error::BatchError;
pub use job::{Item, Job, load};
pub use run::{Outcome, Shard, Summary, run};
