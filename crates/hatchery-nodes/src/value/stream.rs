//! Volumes streamed from a file (issue 30): a volume too large for the host memory budget is
//! held as a preview level in memory (what CPU nodes and the label-map ray casters read) plus its
//! file as a multi-resolution [`BrickSource`]; each view reads only the region it shows, at the
//! level whose voxels match its pixels (screen-space error), and renders that.
//!
//! The region: the blocks (at most 64 per axis) of the finest level not wholly outside one clip
//! plane of the view (frustum culling), with a margin for trilinear samples and gradients. The level: the
//! coarsest whose finest spacing is at most the footprint of a pixel at the nearest visible
//! point, and coarser still while the region holds more voxels than the budgets allow
//! (a warning says so). Regions are cached (LRU) so a still view reads nothing twice.

use super::Volume;
use super::camera::Camera;
use glam::{Vec3, Vec4};
use hatchery_data::DataError;
use hatchery_data::brick_source::{BrickSource, LevelGrid, region_volume};
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

/// Regions kept per stream (a view and the one before it, a volume and its label map).
const CACHED_REGIONS: usize = 3;

/// Regions snap outwards to multiples of this many voxels of their level, so small camera
/// moves reuse the cached region.
const SNAP: u32 = 16;

/// A box of voxels of one level.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Region {
    pub level: usize,
    pub lo: [u32; 3],
    pub size: [u32; 3],
}

impl Region {
    pub fn voxels(&self) -> u64 {
        self.size.iter().map(|&s| s as u64).product()
    }
}

/// A file read level by level and region by region.
pub struct Stream {
    pub source: Arc<dyn BrickSource>,
    pub path: PathBuf,
    /// The value range transfer functions map (the preview level's, as napari takes contrast
    /// limits from a pyramid's smallest level: the whole finest level is never read).
    pub value_range: [f32; 2],
    /// The level held in memory as the volume's `data`.
    pub preview_level: usize,
    /// The most voxels one view's region may hold (host budget / 8 bytes a voxel: the stored
    /// voxels, their texture and its staging copy).
    pub max_region_voxels: u64,
    regions: Mutex<lru::LruCache<Region, Arc<Volume>>>,
}

impl Stream {
    pub fn new(
        source: Arc<dyn BrickSource>,
        path: PathBuf,
        value_range: [f32; 2],
        preview_level: usize,
        max_region_voxels: u64,
    ) -> Self {
        let cap = std::num::NonZeroUsize::new(CACHED_REGIONS).expect("a positive constant");
        Stream {
            source,
            path,
            value_range,
            preview_level,
            max_region_voxels,
            regions: Mutex::new(lru::LruCache::new(cap)),
        }
    }

    /// Region `r` when it has been read already.
    pub fn cached(&self, r: Region) -> Option<Arc<Volume>> {
        self.regions.lock().ok()?.get(&r).cloned()
    }

    /// Region `r` as a volume (read once, then cached), its value range the stream's.
    /// Errors: a read failure, naming the file.
    pub fn region(&self, r: Region) -> Result<Arc<Volume>, DataError> {
        if let Some(v) = self.cached(r) {
            return Ok(v);
        }
        let started = web_time::Instant::now();
        let data = region_volume(
            self.source.as_ref(),
            r.level,
            r.lo,
            r.size,
            Some(self.value_range),
        )
        .map_err(|e| e.in_file(&self.path))?;
        tracing::info!(
            path = %self.path.display(),
            lod = r.level,
            lo = ?r.lo,
            size = ?r.size,
            seconds = started.elapsed().as_secs_f32(),
            "streamed region read"
        );
        let v = Arc::new(Volume::new(data));
        // A poisoned cache (a panic while it was held) only loses the caching.
        if let Ok(mut regions) = self.regions.lock() {
            regions.put(r, v.clone());
        }
        Ok(v)
    }
}

/// A volume as one view reads it: the volume itself, or the region of its stream the view needs.
pub enum ViewVolume<'a> {
    Held(&'a Volume),
    /// A region and the whole level it is cut from.
    Region(Arc<Volume>, LevelGrid),
}

impl ViewVolume<'_> {
    /// The whole level a region is cut from; `None` for a volume as it is.
    pub fn whole(&self) -> Option<&LevelGrid> {
        match self {
            ViewVolume::Held(_) => None,
            ViewVolume::Region(_, whole) => Some(whole),
        }
    }
}

impl std::ops::Deref for ViewVolume<'_> {
    type Target = Volume;
    fn deref(&self) -> &Volume {
        match self {
            ViewVolume::Held(v) => v,
            ViewVolume::Region(v, _) => v,
        }
    }
}

impl Volume {
    /// A volume streamed from `stream`, `preview` (its level `stream.preview_level`) in memory.
    pub fn streamed(preview: hatchery_data::VolumeData, stream: Arc<Stream>) -> Volume {
        let mut v = Volume::new(preview);
        v.stream = Some(stream);
        v
    }

    /// The stream behind this volume, when it is streamed.
    pub fn stream(&self) -> Option<&Stream> {
        self.stream.as_deref()
    }

    /// What a ray caster renders for `camera`: this volume, or for a streamed volume the region
    /// and level the view needs ([`view_region`]) under the host budget and the GPU pool
    /// (`pool_bytes`, 4 bytes a voxel), with a message when the budget made it coarser.
    /// Gradients are normalised by the whole volume's largest (its preview's) unless the region
    /// is a whole level. With `coarse_first`, a region not read yet is not read: the preview is
    /// returned and `coarse` set. Errors: a read failure naming the file.
    pub fn for_view(
        &self,
        camera: &Camera,
        pool_bytes: u64,
        coarse_first: bool,
        coarse: &mut bool,
    ) -> Result<(ViewVolume<'_>, Option<String>), DataError> {
        let Some(stream) = &self.stream else {
            return Ok((ViewVolume::Held(self), None));
        };
        let levels = stream.source.levels();
        let max_voxels = stream.max_region_voxels.min(pool_bytes / 4).max(8);
        let (region, why) = view_region(levels, camera, max_voxels);
        tracing::debug!(?region, "streamed view");
        // At or below the preview's resolution the preview in memory serves: a coarser level
        // would be derived from the file (a whole raw file read for a far view).
        if region.level >= stream.preview_level {
            return Ok((ViewVolume::Held(self), why));
        }
        let v = match stream.cached(region) {
            Some(v) => v,
            None if coarse_first => {
                *coarse = true;
                return Ok((ViewVolume::Held(self), None));
            }
            None => stream.region(region)?,
        };
        if region.size != levels[region.level].dims {
            let _ = v.max_gradient.set(self.max_gradient());
        }
        Ok((ViewVolume::Region(v, levels[region.level].clone()), why))
    }
}

/// The world-space size of a pixel at view depth `depth` (perspective) or anywhere (orthographic).
fn pixel_footprint(camera: &Camera, depth: f32) -> f32 {
    let per_unit = 2.0 / (camera.proj.y_axis.y.abs() * camera.height.max(1) as f32);
    if camera.orthographic {
        per_unit
    } else {
        per_unit * depth
    }
}

/// Whether the box of world-space `corners` lies wholly outside one plane of `view_proj`'s
/// frustum (wgpu clip space: −w ≤ x, y ≤ w, 0 ≤ z ≤ w).
fn outside(view_proj: glam::Mat4, corners: &[Vec3; 8]) -> bool {
    // An array, not a Vec: this runs for up to 64³ blocks on every frame of a streamed view.
    let clip: [Vec4; 8] = corners.map(|c| view_proj * c.extend(1.0));
    let planes: [fn(Vec4) -> f32; 6] = [
        |c| c.x + c.w,
        |c| c.w - c.x,
        |c| c.y + c.w,
        |c| c.w - c.y,
        |c| c.z,
        |c| c.w - c.z,
    ];
    planes.iter().any(|p| clip.iter().all(|&c| p(c) < 0.0))
}

/// The world corners of voxels `lo ..= hi` of `grid` (voxel centres ± half a voxel).
fn corners(grid: &LevelGrid, lo: Vec3, hi: Vec3) -> [Vec3; 8] {
    let (a, b) = (lo - 0.5, hi + 0.5);
    std::array::from_fn(|i| {
        let v = Vec3::new(
            if i & 1 == 0 { a.x } else { b.x },
            if i & 2 == 0 { a.y } else { b.y },
            if i & 4 == 0 { a.z } else { b.z },
        );
        grid.geometry.voxel_to_world(v)
    })
}

/// Blocks per axis the finest level is cut into for culling (at most; blocks have at least 4
/// voxels a side): 64³ corner tests at most, a few milliseconds.
const CULL_BLOCKS: u32 = 64;

/// The region of `levels` (finest first) `camera` needs: see the module docs. Also returns why
/// the level is coarser than the pixels ask for, when it is. With nothing in view: the coarsest
/// level, whole.
pub fn view_region(
    levels: &[LevelGrid],
    camera: &Camera,
    max_voxels: u64,
) -> (Region, Option<String>) {
    let top = &levels[0];
    let view_proj = camera.view_proj();
    let step = top.dims.map(|d| d.div_ceil(CULL_BLOCKS).max(4));
    // The visible blocks' world corners and the nearest view depth among them.
    let mut world_lo = Vec3::splat(f32::INFINITY);
    let mut world_hi = Vec3::splat(f32::NEG_INFINITY);
    let mut nearest = f32::INFINITY;
    for bz in 0..top.dims[2].div_ceil(step[2]) {
        for by in 0..top.dims[1].div_ceil(step[1]) {
            for bx in 0..top.dims[0].div_ceil(step[0]) {
                let b = [bx, by, bz];
                let lo = Vec3::from_array([0, 1, 2].map(|a| (b[a] * step[a]) as f32));
                let hi = Vec3::from_array(
                    [0, 1, 2].map(|a| (((b[a] + 1) * step[a]).min(top.dims[a]) - 1) as f32),
                );
                let c = corners(top, lo, hi);
                if outside(view_proj, &c) {
                    continue;
                }
                for p in c {
                    world_lo = world_lo.min(p);
                    world_hi = world_hi.max(p);
                    let depth = -(camera.view * p.extend(1.0)).z;
                    nearest = nearest.min(depth);
                }
            }
        }
    }
    let coarsest = levels.len() - 1;
    if !nearest.is_finite() {
        let whole = Region {
            level: coarsest,
            lo: [0; 3],
            size: levels[coarsest].dims,
        };
        return (whole, None);
    }
    // The eye inside the volume: the nearest point is at the near plane.
    let footprint = pixel_footprint(camera, nearest.max(camera.near));
    let finest_spacing = |g: &LevelGrid| g.geometry.spacing.min_element() as f32;
    let wanted = (0..levels.len())
        .rev()
        .find(|&k| finest_spacing(&levels[k]) <= footprint * 1.0001)
        .unwrap_or(0);
    let mut level = wanted;
    loop {
        let region = region_in(&levels[level], level, world_lo, world_hi);
        if region.voxels() <= max_voxels || level == coarsest {
            let why = (level > wanted).then(|| {
                format!(
                    "level {wanted} of detail matches the pixels, but its region holds more than \
                     {max_voxels} voxels (HATCHERY_HOST_BUDGET_MB / 8): rendering level {level}"
                )
            });
            return (region, why);
        }
        level += 1;
    }
}

/// The voxels of `grid` within world box `lo .. hi`, two voxels of margin (trilinear samples
/// and central-difference gradients reach one voxel out), snapped outwards to [`SNAP`], at
/// least 2 voxels per axis.
fn region_in(grid: &LevelGrid, level: usize, lo: Vec3, hi: Vec3) -> Region {
    let mut v_lo = Vec3::splat(f32::INFINITY);
    let mut v_hi = Vec3::splat(f32::NEG_INFINITY);
    for i in 0..8 {
        let p = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let v = grid.geometry.world_to_voxel(p);
        v_lo = v_lo.min(v);
        v_hi = v_hi.max(v);
    }
    let mut r_lo = [0u32; 3];
    let mut size = [0u32; 3];
    for a in 0..3 {
        let n = grid.dims[a];
        // (A level of under 2 voxels along an axis gives a box the read refuses, not a panic.)
        let first =
            ((v_lo[a].floor() - 2.0).max(0.0) as u32 / SNAP * SNAP).min(n.saturating_sub(2));
        let last = (v_hi[a].ceil() + 2.0).max(0.0) as u32;
        let end = (last.div_ceil(SNAP) * SNAP).max(first + 2).min(n);
        r_lo[a] = first;
        size[a] = end.saturating_sub(first);
    }
    Region {
        level,
        lo: r_lo,
        size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hatchery_data::geometry::Geometry;
    use hatchery_data::pyramid::{coarser_dims, coarser_geometry};

    fn pyramid(dims: [u32; 3], n: usize) -> Vec<LevelGrid> {
        let mut levels = vec![LevelGrid {
            dims,
            geometry: Geometry::axis_aligned([1.0; 3], [0.0; 3]),
        }];
        while levels.len() < n {
            let l = levels.last().unwrap();
            levels.push(LevelGrid {
                dims: coarser_dims(l.dims),
                geometry: coarser_geometry(l.dims, &l.geometry),
            });
        }
        levels
    }

    fn camera(target: Vec3, distance: f32, size: u32) -> Camera {
        Camera::orbit(
            target, 0.0, 0.0, distance, 30.0, false, 1.0, 5000.0, false, size, size,
        )
    }

    #[test]
    fn a_whole_view_takes_the_level_whose_voxels_match_its_pixels() {
        let levels = pyramid([512; 3], 5);
        let centre = Vec3::splat(255.5);
        // Nearest face 1000 − 256 = 744 away: a pixel spans 2·744·tan 15° / h.
        let (r, why) = view_region(&levels, &camera(centre, 1000.0, 1024), u64::MAX);
        assert_eq!(
            (r.level, r.lo, r.size),
            (0, [0; 3], [512; 3]),
            "0.39 voxels a pixel"
        );
        assert!(why.is_none());
        let (r, _) = view_region(&levels, &camera(centre, 1000.0, 128), u64::MAX);
        assert_eq!(
            r.level, 1,
            "3.1 voxels a pixel: level 1 (2) fits, level 2 (4) does not"
        );
        assert_eq!(r.size, [256; 3]);
        let (r, _) = view_region(&levels, &camera(centre, 1000.0, 16), u64::MAX);
        assert_eq!(r.level, 4, "25 voxels a pixel: the coarsest level");
    }

    #[test]
    fn a_close_view_reads_only_what_it_sees_and_the_budget_coarsens_it() {
        let levels = pyramid([512; 3], 5);
        // Looking along −z at the corner region near (64, 64, 511) from 100 above the top face.
        let cam = camera(Vec3::new(64.0, 64.0, 511.0), 100.0, 512);
        let (r, _) = view_region(&levels, &cam, u64::MAX);
        assert_eq!(r.level, 0);
        assert_eq!(
            r.lo,
            [0, 0, 0],
            "the frustum reaches down to the bottom face"
        );
        // At the bottom face (611 below the eye) the cone reaches x, y ≤ 64 + 611·tan 15° = 228:
        // 29 culling blocks of 8 voxels (to 232), 2 of margin, snapped to 16.
        assert_eq!((r.size[0], r.size[1], r.size[2]), (240, 240, 512), "{r:?}");
        // The same view under a small budget renders a coarser level, and says why.
        let (small, why) = view_region(&levels, &cam, r.voxels() / 4);
        assert!(small.level > 0 && small.voxels() <= r.voxels() / 4);
        assert!(why.unwrap().contains("HATCHERY_HOST_BUDGET_MB"));
        // Looking away from the volume: nothing in view, the coarsest level.
        let away = Camera::orbit(
            Vec3::new(256.0, 256.0, -2000.0),
            0.0,
            0.0,
            100.0,
            30.0,
            false,
            1.0,
            5000.0,
            false,
            64,
            64,
        );
        assert_eq!(view_region(&levels, &away, u64::MAX).0.level, 4);
    }
}
