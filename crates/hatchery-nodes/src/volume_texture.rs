//! A volume's 3-D texture in a format matching its voxel type, uploaded slab by slab without a
//! CPU copy of the whole volume.
//!
//! | voxels | texture | texel → value |
//! |---|---|---|
//! | u8 | R8Unorm | `255 n` (exact) |
//! | i8 | R8Unorm of `v + 128` | `−128 + 255 n` (exact) |
//! | u16 | R16Unorm (`TEXTURE_FORMAT_16BIT_NORM`) | `65535 n` (exact) |
//! | i16 | R16Unorm of `v + 32768` | `−32768 + 65535 n` (exact) |
//! | f32 | R32Float (`FLOAT32_FILTERABLE`) of `(v − lo) / (hi − lo)` | `lo + (hi − lo) n` |
//!
//! On CPU adapters (llvmpipe/lavapipe) 8-bit volumes are uploaded as R16Float of the normalised
//! value `(v − lo) / (hi − lo)` instead: their sampler filters 8-bit textures in 8-bit arithmetic
//! and rounds the result to 1/255 (measured: up to 0.05 colour error against the same data in a
//! float texture), while interpolating in the shader instead made ray casting 3–5× slower there.
//! R16Float rather than R16Unorm of `257 v`: it needs no adapter feature, its 11 significant bits
//! keep every 8-bit level distinct (error ≤ 2⁻¹² of the range), and it is the encoding every
//! volume had before voxel types were kept, so the presets render as they did then (R16Unorm moved
//! single pixels at steep transfer functions by up to 5/255). The second byte per voxel is spent
//! only up to `WIDEN_8BIT_BUDGET` (64 Mi voxels, e.g. 400³): larger 8-bit volumes stay R8Unorm
//! there too, so peak memory stays ≤ 2× the voxel bytes plus a fixed part (the widening adds at
//! most the budget). `HATCHERY_LOW_MEMORY=1` never widens, `HATCHERY_LOW_MEMORY=0` always does.
//! Fallbacks where the adapter lacks the feature: 16-bit integers and f32 become R16Float of
//! `(v − lo) / (hi − lo)` over the value range (11 significant bits: a relative precision of
//! 2⁻¹¹ of the range). "No data" (non-finite f32) texels hold `NO_DATA_TEXEL` (−1000) in the
//! normalised formats; shaders treat a sample below −0.5 as no data.

use crate::brick_pool::grid_texture;
use hatchery_data::VolumeData;
use hatchery_data::voxels::Voxels;
use hatchery_gpu::{GpuContext, GpuError, NO_DATA_TEXEL};
use wgpu::TextureFormat;

/// A volume texture and how its texels map to data values: `value = lo + (hi − lo) · texel`;
/// bricked where the grid exceeds one texture (`layout`, see [`crate::brick_pool`]), with its
/// page table (a 1×1×1 stand-in otherwise).
pub struct VolumeTexture {
    pub texture: wgpu::Texture,
    pub texel_range: [f32; 2],
    pub layout: Option<crate::brick_pool::BrickLayout>,
    pub page_table: wgpu::Texture,
}

/// Voxels up to which 8-bit volumes are widened to R16Float on CPU adapters (64 Mi: 64 MiB more
/// memory at most, a fixed overhead).
pub const WIDEN_8BIT_BUDGET: u64 = 64 << 20;

/// Whether an 8-bit volume of `voxels` voxels is widened on a CPU adapter, given the value of
/// `HATCHERY_LOW_MEMORY` (`1`: never, `0`: always, unset/other: up to `WIDEN_8BIT_BUDGET`).
pub fn widen_8bit_wanted(voxels: u64, low_memory: Option<&str>) -> bool {
    match low_memory {
        Some("1") => false,
        Some("0") => true,
        _ => voxels <= WIDEN_8BIT_BUDGET,
    }
}

/// Uploads `data` in the format of the table above.
pub fn upload(gpu: &GpuContext, label: &str, data: &VolumeData) -> Result<VolumeTexture, GpuError> {
    upload_texels(gpu, label, data, Texels::Voxels)
}

/// What each texel of a volume texture holds.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Texels {
    /// One voxel (the table above).
    Voxels,
    /// Voxels i … i+3 of the row, clamped to the row's end, in the four channels of the
    /// table's format (R8Unorm → Rgba8Unorm, R16Float → Rgba16Float, R16Unorm → Rgba16Unorm,
    /// R32Float → Rgba32Float): the B-spline's loads on CPU adapters (`value/bspline_quads.rs`).
    XQuads,
}

/// Uploads `data` with `texels` per texel in the format of the table above (four channels of it
/// for [`Texels::XQuads`]); the texture is bricked where it exceeds the device's limits.
pub fn upload_texels(
    gpu: &GpuContext,
    label: &str,
    data: &VolumeData,
    texels: Texels,
) -> Result<VolumeTexture, GpuError> {
    let features = gpu.device.features();
    let norm16 = features.contains(wgpu::Features::TEXTURE_FORMAT_16BIT_NORM);
    let float32 = features.contains(wgpu::Features::FLOAT32_FILTERABLE);
    let [lo, hi] = data.value_range;
    let scale = if hi > lo { 1.0 / (hi - lo) } else { 0.0 };
    let normalise = move |v: f32| {
        if v.is_finite() {
            (v - lo) * scale
        } else {
            NO_DATA_TEXEL
        }
    };
    let dims = data.dims;
    let slice = dims[0] as usize * dims[1] as usize;
    let (row, quads) = (dims[0] as usize, texels == Texels::XQuads);
    let half = |v: f32| half::f16::from_f32(v).to_le_bytes();
    let voxels = dims.iter().map(|&d| d as u64).product::<u64>();
    let widen_8bit = gpu.adapter_info.device_type == wgpu::DeviceType::Cpu
        && widen_8bit_wanted(voxels, std::env::var("HATCHERY_LOW_MEMORY").ok().as_deref());
    // The table's format, or its four-channel sibling for quads.
    let stored = |single: TextureFormat| if quads { four_channels(single) } else { single };
    let (format, range, texture) = match &data.voxels {
        Voxels::U8(v) if widen_8bit => {
            let fill = slabs(v, slice, row, quads, |x: u8| half(normalise(x as f32)));
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Float), fill)?;
            ("R16Float (8-bit widened, normalised)", [lo, hi], t)
        }
        Voxels::I8(v) if widen_8bit => {
            let fill = slabs(v, slice, row, quads, |x: i8| half(normalise(x as f32)));
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Float), fill)?;
            ("R16Float (8-bit widened, normalised)", [lo, hi], t)
        }
        Voxels::U8(v) => {
            let fill = slabs(v, slice, row, quads, |x: u8| [x]);
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R8Unorm), fill)?;
            ("R8Unorm", [0.0, 255.0], t)
        }
        Voxels::I8(v) => {
            let fill = slabs(v, slice, row, quads, |x: i8| [(x as i16 + 128) as u8]);
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R8Unorm), fill)?;
            ("R8Unorm (+128)", [-128.0, 127.0], t)
        }
        Voxels::U16(v) if norm16 => {
            let fill = slabs(v, slice, row, quads, |x: u16| x.to_le_bytes());
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Unorm), fill)?;
            ("R16Unorm", [0.0, 65535.0], t)
        }
        Voxels::I16(v) if norm16 => {
            let fill = slabs(v, slice, row, quads, |x: i16| {
                ((x as i32 + 32768) as u16).to_le_bytes()
            });
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Unorm), fill)?;
            ("R16Unorm (+32768)", [-32768.0, 32767.0], t)
        }
        Voxels::U16(v) => {
            let fill = slabs(v, slice, row, quads, |x: u16| half(normalise(x as f32)));
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Float), fill)?;
            ("R16Float (normalised)", [lo, hi], t)
        }
        Voxels::I16(v) => {
            let fill = slabs(v, slice, row, quads, |x: i16| half(normalise(x as f32)));
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Float), fill)?;
            ("R16Float (normalised)", [lo, hi], t)
        }
        Voxels::F32(v) if float32 => {
            let fill = slabs(v, slice, row, quads, |x: f32| normalise(x).to_le_bytes());
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R32Float), fill)?;
            ("R32Float (normalised)", [lo, hi], t)
        }
        Voxels::F32(v) => {
            let fill = slabs(v, slice, row, quads, |x: f32| half(normalise(x)));
            let t = grid_texture(gpu, label, dims, stored(TextureFormat::R16Float), fill)?;
            ("R16Float (normalised)", [lo, hi], t)
        }
    };
    let (texture, layout) = (texture.texture, texture.layout);
    if let Some(l) = &layout {
        let side = gpu
            .volume_limits()?
            .texture_side(gpu.device.limits().max_texture_dimension_3d);
        let [x, y, z] = dims;
        tracing::info!(
            "{label}: {x}×{y}×{z} voxels exceed one texture ({side} per axis): bricked, {}, {} MiB",
            l.describe(),
            l.atlas_bytes(texture.format().block_copy_size(None).unwrap_or(4) as u64) >> 20
        );
    }
    let page_table = crate::brick_pool::page_table(gpu, layout.as_ref());
    // A constant volume: every texel is 0 and means `lo`.
    let texel_range = if range[1] > range[0] {
        range
    } else {
        [lo, lo + 1.0]
    };
    tracing::debug!(label, format, quads, ?dims, "volume texture");
    Ok(VolumeTexture {
        texture,
        texel_range,
        layout,
        page_table,
    })
}

/// Copies slices z0..z1 of `values` (rows of `row` voxels, `slice` voxels per slice), each
/// texel converted by `texel`; with `quads`, each texel holds voxels i … i+3 of its row (the
/// last voxel repeated past the row's end).
fn slabs<T: Copy, const N: usize>(
    values: &[T],
    slice: usize,
    row: usize,
    quads: bool,
    texel: impl Fn(T) -> [u8; N],
) -> impl FnMut(u32, u32, &mut Vec<u8>) {
    move |z0, z1, out| {
        let slab = &values[z0 as usize * slice..z1 as usize * slice];
        if !quads {
            for &v in slab {
                out.extend_from_slice(&texel(v));
            }
            return;
        }
        for voxels in slab.chunks(row) {
            for i in 0..row {
                for k in 0..4 {
                    out.extend_from_slice(&texel(voxels[(i + k).min(row - 1)]));
                }
            }
        }
    }
}

/// The four-channel format with `single`'s channel encoding.
fn four_channels(single: TextureFormat) -> TextureFormat {
    match single {
        TextureFormat::R8Unorm => TextureFormat::Rgba8Unorm,
        TextureFormat::R16Unorm => TextureFormat::Rgba16Unorm,
        TextureFormat::R16Float => TextureFormat::Rgba16Float,
        TextureFormat::R32Float => TextureFormat::Rgba32Float,
        other => unreachable!(
            "volume textures are R8Unorm, R16Unorm, R16Float or R32Float, not {other:?}"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eight_bit_widening_is_bounded_by_the_budget_unless_overridden() {
        assert!(widen_8bit_wanted(256 * 256 * 256, None));
        assert!(widen_8bit_wanted(WIDEN_8BIT_BUDGET, None));
        assert!(!widen_8bit_wanted(800 * 800 * 800, None));
        assert!(!widen_8bit_wanted(64, Some("1")));
        assert!(widen_8bit_wanted(800 * 800 * 800, Some("0")));
    }
}
