//! A label map as 2×2 id quads for CPU adapters (shaders/ray_objects.wgsl, `TL_ID_QUADS`):
//! texel (i, j, k) holds the ids of voxels (i, j), (i+1, j), (i, j+1) and (i+1, j+1) of slice
//! k, clamped to the grid, so the 8 corners of a trilinear footprint — boundary filtering
//! (Hadwiger et al. §2.3) and every object mask — are 2 loads instead of 8. llvmpipe/lavapipe
//! run every texture load as a loop in software; there this makes segmented ray casting about
//! twice as fast (docs/benchmarks.md). `.r` is the voxel's own id, so every other read of the
//! id binding is unchanged. Real GPUs keep the one-id texture.

use super::Labels;
use hatchery_gpu::{GpuContext, GpuError};

impl Labels {
    /// The id-quads texture (Rgba8Uint where every id is below 256, else Rgba16Uint), uploaded
    /// on first use, where segmented ray casters should read it: a CPU adapter, the ids in one
    /// texture (not bricked) and the quads within the device's `VolumeLimits::quads_bytes` and
    /// buffer limit.
    /// `None` elsewhere: the caller binds [`Labels::texture`]. Errors: the upload's.
    pub fn id_quads(&self, gpu: &GpuContext) -> Result<Option<&wgpu::Texture>, GpuError> {
        if let Some(t) = self.id_quads.get() {
            return Ok(t.as_ref());
        }
        let bricked = self.texture(gpu)?.layout.is_some();
        let narrow = self.data.ids.iter().all(|&id| id < 256);
        let (format, texel) = if narrow {
            (wgpu::TextureFormat::Rgba8Uint, 4)
        } else {
            (wgpu::TextureFormat::Rgba16Uint, 8)
        };
        let voxels: u64 = self.data.dims.iter().map(|&d| d as u64).product();
        let bytes = texel * voxels;
        let wanted = !bricked && super::read_ahead_fits(gpu, bytes)?;
        let quads = if wanted {
            let [nx, ny, _] = self.data.dims.map(|d| d as usize);
            let ids = &self.data.ids;
            let t = gpu.volume_texture_by_slabs(
                "label id quads",
                self.data.dims,
                format,
                |z0, z1, out| {
                    for k in z0 as usize..z1 as usize {
                        for j in 0..ny {
                            let (row, next) =
                                (k * nx * ny + j * nx, k * nx * ny + (j + 1).min(ny - 1) * nx);
                            for i in 0..nx {
                                let i1 = (i + 1).min(nx - 1);
                                for id in
                                    [ids[row + i], ids[row + i1], ids[next + i], ids[next + i1]]
                                {
                                    if narrow {
                                        out.push(id as u8);
                                    } else {
                                        out.extend_from_slice(&id.to_le_bytes());
                                    }
                                }
                            }
                        }
                    }
                },
            )?;
            Some(t)
        } else {
            None
        };
        Ok(self.id_quads.get_or_init(|| quads).as_ref())
    }
}
