//! What Raycast reads besides the rendered field for Svakhine et al. 2005's Table 1 (§3.2–3.3):
//! a vector field U, and a second scalar field's gradient and value. Both go to the GPU as one
//! Rgba16Float 3-D texture on their grid (8 bytes per voxel), filtered trilinearly like the
//! volume.

use super::Volume;
use hatchery_data::vector_field::VectorFieldData;
use hatchery_gpu::{GpuContext, GpuError};
use std::sync::{Arc, OnceLock};

/// A vector field on a grid (see [`VectorFieldData`]), uploaded on first use.
pub struct VectorField {
    pub data: Arc<VectorFieldData>,
    texture: OnceLock<(wgpu::Texture, f32)>,
}

impl VectorField {
    pub fn new(data: VectorFieldData) -> Self {
        Self {
            data: Arc::new(data),
            texture: OnceLock::new(),
        }
    }

    /// The field as an Rgba16Float texture: xyz = U / max |U| (so |xyz| ≤ 1; 0 where U is "no
    /// data"), w = 0; and max |U|. Uploaded once.
    pub fn texture(&self, gpu: &GpuContext) -> Result<(&wgpu::Texture, f32), GpuError> {
        if let Some((t, m)) = self.texture.get() {
            return Ok((t, *m));
        }
        let d = &self.data;
        let max = d.max_magnitude();
        let scale = if max > 0.0 { 1.0 / max } else { 0.0 };
        let slice = d.dims[0] as usize * d.dims[1] as usize;
        let t = rgba16f_texture(gpu, "vector field", d.dims, |z0, z1, push| {
            for v in &d.vectors[z0 as usize * slice..z1 as usize * slice] {
                let finite = v.iter().all(|c| c.is_finite());
                let [x, y, z] = if finite {
                    v.map(|c| c * scale)
                } else {
                    [0.0; 3]
                };
                push([x, y, z, 0.0]);
            }
        })?;
        let (t, m) = self.texture.get_or_init(|| (t, max));
        Ok((t, *m))
    }
}

impl Volume {
    /// This volume as a *second field* of another one's rendering: an Rgba16Float texture with
    /// xyz = ∇f / max |∇f| (world-space central differences, as [`Volume::max_gradient`] takes
    /// them; 0 across "no data") and w = (f − min) / (max − min) over the value range (−1 for
    /// "no data", so a filtered w below 0 marks a sample next to it). Uploaded once.
    pub fn second_field_texture(&self, gpu: &GpuContext) -> Result<&wgpu::Texture, GpuError> {
        if let Some(t) = self.second_field.get() {
            return Ok(t);
        }
        let d = &self.data;
        let max = self.max_gradient();
        let scale = if max > 0.0 { 1.0 / max } else { 0.0 };
        let [lo, hi] = d.value_range;
        let span = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
        let slice = d.dims[0] as usize * d.dims[1] as usize;
        let t = rgba16f_texture(gpu, "second field", d.dims, |z0, z1, push| {
            let gradients = hatchery_data::gradient::voxel_gradients(d, z0, z1);
            for (k, g) in gradients.iter().enumerate() {
                let v = d.voxels.get(z0 as usize * slice + k);
                let w = if v.is_finite() { (v - lo) * span } else { -1.0 };
                push((*g * scale).extend(w).to_array());
            }
        })?;
        Ok(self.second_field.get_or_init(|| t))
    }
}

/// An Rgba16Float 3-D texture of `dims`, filled a slab of slices z0..z1 at a time by `fill`,
/// which hands each texel (x fastest) to `push`.
fn rgba16f_texture(
    gpu: &GpuContext,
    label: &str,
    dims: [u32; 3],
    mut fill: impl FnMut(u32, u32, &mut dyn FnMut([f32; 4])),
) -> Result<wgpu::Texture, GpuError> {
    let format = wgpu::TextureFormat::Rgba16Float;
    gpu.volume_texture_by_slabs(label, dims, format, |z0, z1, out| {
        fill(z0, z1, &mut |texel| {
            for c in texel {
                out.extend_from_slice(&half::f16::from_f32(c).to_le_bytes());
            }
        })
    })
}
