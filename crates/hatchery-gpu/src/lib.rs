//! hatchery's GPU layer: one headless wgpu device (a real GPU, or Mesa's software drivers on a
//! machine without one), render-target and upload helpers, read-back, and per-node GPU timing.
#![forbid(unsafe_code)]

mod context;
mod error;
mod readback;
mod timing;
mod volume_limits;
pub mod web_readback;

pub use context::{GpuContext, NO_DATA_TEXEL};
pub use error::GpuError;
pub use readback::TextureData;
pub use timing::GpuTimer;
pub use volume_limits::{MIN_BRICK, VolumeLimits};
pub use wgpu;
