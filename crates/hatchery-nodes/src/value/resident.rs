//! The level of detail a GPU node renders (issue 30): the volume itself where its grid fits one
//! texture or a brick pool, else the finest coarser level (hatchery_data::pyramid) that fits.
//! The choice depends on the grid's dims and the device's limits only, so a volume and a label
//! map on one grid always land on the same level.

use super::{Labels, Volume};
use hatchery_gpu::{GpuContext, GpuError};
use std::sync::Arc;

/// Whether a grid of `dims` fits the device as one texture of `texel` bytes a voxel (against
/// `max_buffer_size`) or in a brick pool.
fn fits(gpu: &GpuContext, dims: [u32; 3], texel: u64) -> Result<bool, GpuError> {
    let limits = gpu.volume_limits()?;
    let device = gpu.device.limits();
    let bytes = Some((texel, device.max_buffer_size));
    Ok(crate::brick_pool::plan_on(dims, &limits, device.max_texture_dimension_3d, bytes).is_ok())
}

/// Walks down the levels from `top` until one fits; `coarser` makes the next level; `texel`:
/// bytes of a texel of its texture (at most: 8-bit data may be widened to 16 bits).
fn finest_fitting<'a, T>(
    gpu: &GpuContext,
    top: &'a T,
    dims: impl Fn(&T) -> [u32; 3],
    texel: u64,
    coarser: impl Fn(&'a T) -> Result<&'a T, String>,
) -> Result<&'a T, GpuError> {
    let mut level = top;
    let mut k = 0;
    while !fits(gpu, dims(level), texel)? {
        let d = dims(level);
        if !hatchery_data::pyramid::has_coarser(d) {
            // Report why the coarsest level does not fit either.
            let limits = gpu.volume_limits()?;
            let device_max = gpu.device.limits().max_texture_dimension_3d;
            return crate::brick_pool::plan(d, &limits, device_max).map(|_| level);
        }
        level = coarser(level).map_err(|message| GpuError::Setting { message })?;
        k += 1;
    }
    if k > 0 {
        let [x, y, z] = dims(top);
        let [cx, cy, cz] = dims(level);
        tracing::warn!(
            "a {x}×{y}×{z} grid does not fit the brick pool (HATCHERY_GPU_POOL_MB, \
             max_texture_dimension_3d): rendering level {k} of detail ({cx}×{cy}×{cz} voxels)"
        );
    }
    Ok(level)
}

impl Volume {
    /// The level of detail GPU nodes render: this volume where it fits one texture or a brick
    /// pool, else the finest coarser level that does (each voxel the mean of a 2×2×2 block,
    /// placed where the block lies; made once). Errors: not even the coarsest level fits, a
    /// malformed limit setting.
    pub fn resident(&self, gpu: &GpuContext) -> Result<&Volume, GpuError> {
        finest_fitting(gpu, self, |v| v.data.dims, self.texel(), |v| v.coarser())
    }

    /// [`Self::resident`] for a volume of label ids (Raycast's `labels`): coarser levels keep
    /// the id most of each 2×2×2 block holds instead of the mean.
    pub fn resident_labels(&self, gpu: &GpuContext) -> Result<&Volume, GpuError> {
        finest_fitting(
            gpu,
            self,
            |v| v.data.dims,
            self.texel(),
            |v| v.coarser_labels(),
        )
    }

    /// Bytes of a texel of this volume's texture, at most (see `volume_texture`: 8-bit data may
    /// be widened to 16 bits, f32 kept).
    fn texel(&self) -> u64 {
        (self.data.voxels.bytes_per_voxel() as u64).max(2)
    }

    fn coarser(&self) -> Result<&Volume, String> {
        if let Some(c) = self.coarser.get() {
            return Ok(c);
        }
        let data = hatchery_data::pyramid::coarser_volume(&self.data).map_err(|e| e.to_string())?;
        Ok(self.coarser.get_or_init(|| Arc::new(Volume::new(data))))
    }

    fn coarser_labels(&self) -> Result<&Volume, String> {
        if let Some(c) = self.coarser_labels.get() {
            return Ok(c);
        }
        let data =
            hatchery_data::pyramid::coarser_label_volume(&self.data).map_err(|e| e.to_string())?;
        Ok(self
            .coarser_labels
            .get_or_init(|| Arc::new(Volume::new(data))))
    }
}

impl Labels {
    /// The level of detail GPU nodes render, as [`Volume::resident`] (each voxel the id most of
    /// its 2×2×2 block holds).
    pub fn resident(&self, gpu: &GpuContext) -> Result<&Labels, GpuError> {
        // Ids are R16Uint texels.
        finest_fitting(gpu, self, |l| l.data.dims, 2, |l| l.coarser())
    }

    fn coarser(&self) -> Result<&Labels, String> {
        if let Some(c) = self.coarser.get() {
            return Ok(c);
        }
        let data = hatchery_data::pyramid::coarser_labels(&self.data).map_err(|e| e.to_string())?;
        Ok(self.coarser.get_or_init(|| Arc::new(Labels::new(data))))
    }
}
