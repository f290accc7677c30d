//! Bricked volumes (issue 30): a grid texture larger than one 3-D texture may be (the adapter's
//! `max_texture_dimension_3d`, or `HATCHERY_MAX_TEXTURE_3D`) is cut into bricks, each stored
//! with a one-voxel apron on every side, packed into a 3-D atlas (the brick pool), and found
//! through a page table: brick → atlas slot. Shaders read every grid texture through
//! `grid_uv`/`grid_texel` of shaders/ray_common.wgsl.
//!
//! Why an apron suffices: a filtered sample at voxel-space `p` is read from the brick
//! `floor(p / inner)`, whose own voxels span `[brick · inner, brick · inner + inner)`; the
//! sample's trilinear footprint `floor(p) … floor(p) + 1` then lies within the brick and its
//! apron (also when rounding puts `p` a hair on the other side of a brick face), so the
//! bricked sample equals the whole texture's. Gradients are differences of such samples.
//!
//! The layout depends only on the grid's dims and the [`VolumeLimits`]: every texture on one
//! grid (the volume, its labels, their masks) is bricked alike and shares one page table.

use hatchery_gpu::{GpuContext, GpuError, VolumeLimits};

/// Bricks of a grid in an atlas: `pages` bricks per axis (x fastest), each stored as
/// `inner + 2` voxels per side, in an atlas of `slots` bricks per axis. Brick `i` (linear)
/// lies in slot `i` (linear, x fastest).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BrickLayout {
    /// The grid's own voxels per brick side.
    pub inner: u32,
    pub pages: [u32; 3],
    pub slots: [u32; 3],
}

impl BrickLayout {
    /// Stored brick side: its own voxels and an apron voxel on each side.
    pub fn stored(&self) -> u32 {
        self.inner + 2
    }
    /// The atlas's size in texels.
    pub fn atlas_dims(&self) -> [u32; 3] {
        self.slots.map(|s| s * self.stored())
    }
    pub fn brick_count(&self) -> u32 {
        self.pages.iter().product()
    }
    /// The atlas slot (per axis) of brick `index` (linear, x fastest).
    pub fn slot(&self, index: u32) -> [u32; 3] {
        let [sx, sy, _] = self.slots;
        [index % sx, (index / sx) % sy, index / (sx * sy)]
    }
    /// Bytes of one atlas at `texel` bytes a voxel.
    pub fn atlas_bytes(&self, texel: u64) -> u64 {
        self.atlas_dims().iter().map(|&d| d as u64).product::<u64>() * texel
    }
    /// One line for `-v`: brick size, bricks, atlas.
    pub fn describe(&self) -> String {
        let [px, py, pz] = self.pages;
        let [ax, ay, az] = self.atlas_dims();
        format!(
            "{} bricks ({px}×{py}×{pz}) of {}³ voxels with a one-voxel apron, in a {ax}×{ay}×{az} atlas",
            self.brick_count(),
            self.inner,
        )
    }
}

/// How a grid of `dims` voxels is held on a device allowing `device_max` voxels per 3-D texture
/// side: `None` as one texture, or bricked. Errors: the bricks do not fit the pool (too many
/// for an atlas within the side limit, or for `pool_bytes` at 4 bytes a voxel) — the caller
/// can render a coarser level instead (see [`crate::value::Volume::resident`]).
pub fn plan(
    dims: [u32; 3],
    limits: &VolumeLimits,
    device_max: u32,
) -> Result<Option<BrickLayout>, GpuError> {
    plan_on(dims, limits, device_max, None)
}

/// [`plan`] where one texture must also hold at most `bytes.1` bytes at `bytes.0` bytes a
/// texel (the device's `max_buffer_size`: a 1024³ 16-bit grid is 2³¹ bytes, one more than
/// lavapipe allows), else the grid is bricked.
pub fn plan_on(
    dims: [u32; 3],
    limits: &VolumeLimits,
    device_max: u32,
    bytes: Option<(u64, u64)>,
) -> Result<Option<BrickLayout>, GpuError> {
    let side = limits.texture_side(device_max);
    let voxels = dims.iter().map(|&d| d as u64).product::<u64>();
    let fits_bytes = bytes.is_none_or(|(texel, max)| voxels.saturating_mul(texel) <= max);
    if dims.iter().all(|&d| d <= side) && fits_bytes {
        return Ok(None);
    }
    let stored = limits.brick.min(device_max).max(hatchery_gpu::MIN_BRICK);
    let inner = stored - 2;
    let pages = dims.map(|d| d.div_ceil(inner));
    let total = pages.iter().map(|&p| p as u64).product::<u64>();
    // The atlas is bounded by the device's own side limit and the pool budget, not by the
    // forced limit: that one says which volumes are bricked (a test forces it below a volume
    // whose bricks still fit a pool).
    let per_axis = (device_max / stored) as u64;
    let by_budget = limits.pool_bytes / (stored as u64).pow(3) / 4;
    let capacity = per_axis.pow(3).min(by_budget);
    let too_large = || GpuError::TooLarge {
        what: format!("a {}×{}×{} volume", dims[0], dims[1], dims[2]),
        size: format!("{total} bricks of {stored}³ voxels"),
        limit: format!(
            "{capacity} in one brick pool ({device_max} voxels per atlas side: \
             max_texture_dimension_3d; {} MiB: HATCHERY_GPU_POOL_MB)",
            limits.pool_bytes >> 20
        ),
    };
    if total > capacity || per_axis == 0 {
        return Err(too_large());
    }
    // A near-cubic atlas: texture coordinates stay as small as the grid's own, so samples keep
    // the precision of the whole texture's (a 4096-wide atlas moved curvature pixels by 36/255).
    let side_slots = |n: u64, root: f64| ((n as f64).powf(root).ceil() as u64).clamp(1, per_axis);
    let mut sx = side_slots(total, 1.0 / 3.0);
    let mut sy = side_slots(total.div_ceil(sx), 0.5);
    if total.div_ceil(sx * sy) > per_axis {
        (sx, sy) = (per_axis, per_axis);
    }
    let sz = total.div_ceil(sx * sy);
    if sz > per_axis {
        return Err(too_large());
    }
    Ok(Some(BrickLayout {
        inner,
        pages,
        slots: [sx as u32, sy as u32, sz as u32],
    }))
}

/// A texture on a volume's grid: the whole grid, or its bricks in an atlas (`layout`).
pub struct GridTexture {
    pub texture: wgpu::Texture,
    pub layout: Option<BrickLayout>,
}

/// Uploads a grid texture of `dims` voxels in `format`: one texture where the grid fits
/// ([`plan`]), else bricks in an atlas. `fill(z0, z1, out)` appends slices `z0..z1` (texels x
/// fastest, `format`'s bytes each), as for `GpuContext::volume_texture_by_slabs`; bricking asks
/// for one layer of bricks (and its apron slices) at a time, so no second copy of the grid is
/// held. Errors: the grid fits neither way, a malformed limit setting.
pub fn grid_texture(
    gpu: &GpuContext,
    label: &str,
    dims: [u32; 3],
    format: wgpu::TextureFormat,
    mut fill: impl FnMut(u32, u32, &mut Vec<u8>),
) -> Result<GridTexture, GpuError> {
    let limits = gpu.volume_limits()?;
    let device_max = gpu.device.limits().max_texture_dimension_3d;
    let texel = format.block_copy_size(None).unwrap_or(4) as u64;
    let max_bytes = gpu.device.limits().max_buffer_size;
    let Some(layout) = plan_on(dims, &limits, device_max, Some((texel, max_bytes)))? else {
        let texture = gpu.volume_texture_by_slabs(label, dims, format, fill)?;
        return Ok(GridTexture {
            texture,
            layout: None,
        });
    };
    tracing::debug!(label, ?dims, bricks = %layout.describe(), "bricked grid texture");
    let texel = texel as usize;
    let atlas = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: extent(layout.atlas_dims()),
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D3,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let (inner, stored) = (layout.inner as i64, layout.stored() as usize);
    let [nx, ny, nz] = dims.map(|d| d as i64);
    // Grid coordinate of a brick's stored voxel `l` (apron first), clamped to the grid: the
    // apron outside the grid repeats the edge, as the whole texture's clamped sampling does.
    let clamped =
        |brick: u32, l: usize, n: i64| (brick as i64 * inner - 1 + l as i64).clamp(0, n - 1);
    let mut slab = Vec::new();
    let mut brick_bytes = vec![0u8; stored.pow(3) * texel];
    let [px, py, pz] = layout.pages;
    for bz in 0..pz {
        let z0 = clamped(bz, 0, nz);
        let z1 = clamped(bz, stored - 1, nz);
        slab.clear();
        fill(z0 as u32, z1 as u32 + 1, &mut slab);
        let row = nx as usize * texel;
        let slice = row * ny as usize;
        for by in 0..py {
            for bx in 0..px {
                let xs: Vec<usize> = (0..stored).map(|l| clamped(bx, l, nx) as usize).collect();
                let mut at = 0;
                for lz in 0..stored {
                    let z = (clamped(bz, lz, nz) - z0) as usize;
                    for ly in 0..stored {
                        let y = clamped(by, ly, ny) as usize;
                        let line = &slab[z * slice + y * row..][..row];
                        for &x in &xs {
                            brick_bytes[at..at + texel]
                                .copy_from_slice(&line[x * texel..x * texel + texel]);
                            at += texel;
                        }
                    }
                }
                let index = bx + px * (by + py * bz);
                let origin = layout.slot(index).map(|s| s * layout.stored());
                gpu.queue.write_texture(
                    wgpu::TexelCopyTextureInfo {
                        texture: &atlas,
                        mip_level: 0,
                        origin: wgpu::Origin3d {
                            x: origin[0],
                            y: origin[1],
                            z: origin[2],
                        },
                        aspect: wgpu::TextureAspect::All,
                    },
                    &brick_bytes,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some((stored * texel) as u32),
                        rows_per_image: Some(stored as u32),
                    },
                    extent([layout.stored(); 3]),
                );
            }
        }
    }
    Ok(GridTexture {
        texture: atlas,
        layout: Some(layout),
    })
}

fn extent([width, height, depth]: [u32; 3]) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: depth,
    }
}

/// The page table of `layout` (R32Uint, a texel per brick: its slot `x | y << 10 | z << 20`),
/// or a 1×1×1 stand-in for a grid held as one texture.
pub fn page_table(gpu: &GpuContext, layout: Option<&BrickLayout>) -> wgpu::Texture {
    let Some(l) = layout else {
        return gpu.texture_3d_init(
            "page table",
            [1, 1, 1],
            wgpu::TextureFormat::R32Uint,
            &[0; 4],
        );
    };
    let entries: Vec<u32> = (0..l.brick_count())
        .map(|i| {
            let [x, y, z] = l.slot(i);
            x | (y << 10) | (z << 20)
        })
        .collect();
    gpu.texture_3d_init(
        "page table",
        l.pages,
        wgpu::TextureFormat::R32Uint,
        bytemuck::cast_slice(&entries),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits(max: u32, brick: u32, pool_mb: u64) -> VolumeLimits {
        VolumeLimits {
            max_texture_3d: Some(max),
            brick,
            pool_bytes: pool_mb << 20,
            ..VolumeLimits::default()
        }
    }

    #[test]
    fn grids_within_the_limit_stay_whole_and_larger_ones_are_packed_densely() {
        assert_eq!(plan([64, 64, 64], &limits(64, 16, 64), 2048).unwrap(), None);
        // The device's own limit applies where none is forced.
        assert_eq!(
            plan([300, 20, 20], &VolumeLimits::default(), 256)
                .unwrap()
                .unwrap()
                .inner,
            62
        );
        // The atlas may be larger than the forced limit (that one only says what is bricked),
        // not larger than the device's: 8 × 8 × 8 slots cannot hold 1728 bricks.
        assert!(plan([160, 160, 160], &limits(128, 16, 64), 128).is_err());
        let l = plan([160, 160, 160], &limits(128, 16, 64), 2048)
            .unwrap()
            .unwrap();
        assert_eq!(l.inner, 14);
        assert_eq!(l.pages, [12, 12, 12]);
        assert_eq!(l.slots, [12, 12, 12]);
        let l = plan([100, 30, 30], &limits(64, 16, 64), 2048)
            .unwrap()
            .unwrap();
        assert_eq!(l.pages, [8, 3, 3]);
        assert!(l.slots.iter().product::<u32>() >= 72);
        assert!(
            l.atlas_dims().iter().all(|&d| d <= 2048),
            "{:?}",
            l.atlas_dims()
        );
        // Every brick has its own slot.
        let slots: std::collections::HashSet<[u32; 3]> =
            (0..l.brick_count()).map(|i| l.slot(i)).collect();
        assert_eq!(slots.len(), 72);
    }

    #[test]
    fn a_grid_beyond_the_device_buffer_size_is_bricked() {
        let l = limits(2048, 64, 8192);
        let lavapipe = Some((2, (1u64 << 31) - 1));
        // (17³ bricks of 62³ take 4913 × 1 MiB of pool at 4 bytes a voxel: 8 GiB holds them.)
        // 1024³ 16-bit texels are 2³¹ bytes: one more than lavapipe's max_buffer_size.
        assert!(plan_on([1024; 3], &l, 2048, lavapipe).unwrap().is_some());
        assert_eq!(
            plan_on([1024, 1024, 1023], &l, 2048, lavapipe).unwrap(),
            None
        );
        assert_eq!(
            plan([1024; 3], &l, 2048).unwrap(),
            None,
            "no byte limit given"
        );
    }

    #[test]
    fn bricks_beyond_the_pool_are_refused_with_the_settings_named() {
        // The device's side limit: 16³ slots of 16³ hold 4096 bricks, a 256³ grid needs 6859.
        let e = plan([256, 256, 256], &limits(64, 16, 1024), 256)
            .unwrap_err()
            .to_string();
        assert!(e.contains("4096 in one brick pool"), "{e}");
        assert!(e.contains("max_texture_dimension_3d"), "{e}");
        // The budget binds before the side limit: 1 MiB holds 64 bricks of 16³ at 4 bytes.
        let e = plan([160, 160, 160], &limits(128, 16, 1), 2048)
            .unwrap_err()
            .to_string();
        assert!(e.contains("64 in one brick pool"), "{e}");
    }
}
