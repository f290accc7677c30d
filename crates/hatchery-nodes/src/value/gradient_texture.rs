//! The volume's world-space gradients at the voxel centres (central differences, one-sided at
//! the faces; `hatchery_data::gradient::voxel_gradients`) as an Rgba32Float texture, for
//! volume thinning's key on CPU adapters (shaders/two_level_raycast.wgsl, `TL_THIN_GRADIENTS`).
//! Central differences commute with trilinear interpolation, so one filtered fetch of it gives
//! the gradient that six fetches of the volume give (`central_gradient`), the same inside the
//! grid; within a voxel of a face the texture's one-sided differences are interpolated
//! instead. The key's Hessian (six gradients) then costs 6 fetches instead of 36.

use super::Volume;
use hatchery_gpu::{GpuContext, GpuError};

impl Volume {
    /// The gradient texture, made on first use, where the thinning key should read it: a CPU
    /// adapter with filterable 32-bit float textures, the volume in one texture (not bricked),
    /// without "no data", and the texture (16 bytes a voxel) within the device's
    /// `VolumeLimits::quads_bytes` and buffer limit. `None` elsewhere. Errors: the upload's.
    pub fn gradient_texture(&self, gpu: &GpuContext) -> Result<Option<&wgpu::Texture>, GpuError> {
        if let Some(t) = self.gradients.get() {
            return Ok(t.as_ref());
        }
        let bricked = self.texture(gpu)?.layout.is_some();
        let voxels: u64 = self.data.dims.iter().map(|&d| d as u64).product();
        let wanted = gpu
            .device
            .features()
            .contains(wgpu::Features::FLOAT32_FILTERABLE)
            && !bricked
            && !self.has_no_data()
            && super::read_ahead_fits(gpu, 16 * voxels)?;
        let texture = if wanted {
            let d = &self.data;
            let t = gpu.volume_texture_by_slabs(
                "volume gradients",
                d.dims,
                wgpu::TextureFormat::Rgba32Float,
                |z0, z1, out| {
                    for g in hatchery_data::gradient::voxel_gradients(d, z0, z1) {
                        out.extend_from_slice(bytemuck::cast_slice(&g.extend(0.0).to_array()));
                    }
                },
            )?;
            Some(t)
        } else {
            None
        };
        Ok(self.gradients.get_or_init(|| texture).as_ref())
    }
}
