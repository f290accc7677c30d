//! The GPU layer's error type (its own module: the context and the volume limits both use it).

/// Errors of the GPU layer. Messages are one line and say what to do.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "no GPU adapter found (tried {tried}). On a machine without a GPU install Mesa's software \
         Vulkan driver: `apt-get install mesa-vulkan-drivers` (or run scripts/install-deps.sh)"
    )]
    NoAdapter { tried: String },
    #[error("cannot open the GPU device on {adapter}: {message}")]
    Device { adapter: String, message: String },
    #[error("{what}: {message}")]
    Validation { what: String, message: String },
    #[error("reading back {what} from the GPU failed: {message}")]
    Readback { what: String, message: String },
    #[error("{message}")]
    Setting { message: String },
    #[error("{what} is {size} but this GPU allows at most {limit}")]
    TooLarge {
        what: String,
        size: String,
        limit: String,
    },
}
