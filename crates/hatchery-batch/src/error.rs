//! The one error type of batch rendering: which part failed is the variant, the message is the
//! one line the command line prints.

use hatchery_nodes::SessionError;

#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// A job file that cannot be read, parsed or expanded (the message names the file).
    #[error("{0}")]
    Job(String),
    /// A shard that is malformed or out of range (`--shard`, the scheduler's variables).
    #[error("{0}")]
    Shard(String),
    /// Manifests that cannot be read, or outputs that do not merge.
    #[error("{0}")]
    Manifest(String),
    /// An animation that cannot be encoded or written.
    #[error("{0}")]
    Animation(String),
    /// A folder or file that cannot be made or written.
    #[error("{0}")]
    Io(String),
    /// The graph or the GPU cannot be opened.
    #[error(transparent)]
    Session(#[from] SessionError),
}
