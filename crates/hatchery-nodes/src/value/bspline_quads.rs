//! The volume as x-quads for the tricubic B-spline on CPU adapters (shaders/ray_bspline.wgsl,
//! `RAY_BSPLINE_QUADS`): texel (i, j, k) holds voxels i … i+3 of its row, so a sample's 4×4×4
//! neighbourhood is 16 loads instead of the 32 filtered fetches of its value and gradient.
//! llvmpipe/lavapipe run every fetch as a loop in software, filtered or not; there this makes
//! B-spline ray casting about 1.5× faster (docs/benchmarks.md). Real GPUs filter in hardware
//! and keep the fetches (Sigg & Hadwiger's trick), and the single-voxel texture.

use super::Volume;
use crate::volume_texture::{Texels, upload_texels};
use hatchery_gpu::{GpuContext, GpuError};

impl Volume {
    /// The x-quads texture, uploaded on first use, where the B-spline should read it: a CPU
    /// adapter, the volume in one texture (not bricked) without "no data" (the quads' sums
    /// have no guard), and the quads within the device's `VolumeLimits::quads_bytes` and
    /// buffer limit. `None` elsewhere: the caller binds
    /// [`Volume::texture`] and the fetches. Errors: the upload's.
    pub fn bspline_quads(&self, gpu: &GpuContext) -> Result<Option<&wgpu::Texture>, GpuError> {
        if let Some(t) = self.bspline_quads.get() {
            return Ok(t.as_ref());
        }
        let single = self.texture(gpu)?;
        let texel = single.texture.format().block_copy_size(None).unwrap_or(4) as u64;
        let voxels: u64 = self.data.dims.iter().map(|&d| d as u64).product();
        let bytes = 4 * texel * voxels;
        let wanted =
            single.layout.is_none() && !self.has_no_data() && super::read_ahead_fits(gpu, bytes)?;
        let quads = if wanted {
            let t = upload_texels(gpu, "volume x-quads", &self.data, Texels::XQuads)?;
            // Bricked (beyond one texture's limits at four channels): the fetches instead.
            t.layout.is_none().then_some(t.texture)
        } else {
            None
        };
        Ok(self.bspline_quads.get_or_init(|| quads).as_ref())
    }
}
