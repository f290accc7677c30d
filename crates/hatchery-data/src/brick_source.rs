//! Bricks read on demand (issue 30, streaming): a multi-resolution grid that hands out any box of
//! voxels of any level without holding the whole in memory ([`BrickSource`]: an OME-Zarr
//! pyramid, or a volume in memory and its coarser levels), a host cache of bricks under a byte
//! budget that evicts the least recently used ([`BrickCache`]), and worker threads that read
//! requested bricks ([`BrickLoader`]).
//!
//! A brick is the GPU brick pool's unit (crates/hatchery-nodes/src/brick_pool.rs): `inner`
//! voxels of its level per side plus a one-voxel apron copied from the neighbours (the grid's
//! edge repeated outside it), so trilinear samples and gradients are seamless across bricks.

use std::collections::HashSet;
use std::sync::Arc;
use std::thread::JoinHandle;

use crossbeam_channel::{Receiver, Sender};
use lru::LruCache;

use crate::DataError;
use crate::geometry::Geometry;
use crate::volume::VolumeData;
use crate::voxels::Voxels;

/// One level of a [`BrickSource`]: its grid and where it lies.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelGrid {
    pub dims: [u32; 3],
    pub geometry: Geometry,
}

/// A multi-resolution grid read box by box. Level 0 is the finest.
pub trait BrickSource: Send + Sync {
    /// The levels, finest first (at least one).
    fn levels(&self) -> &[LevelGrid];
    /// Voxels `lo .. lo + size` of `level` (x fastest) in the stored type; the box lies within the
    /// level's grid. Errors: a read failure naming the file.
    fn read_box(&self, level: usize, lo: [u32; 3], size: [u32; 3]) -> Result<Voxels, DataError>;
}

/// Errors unless box `lo .. lo + size` lies within level `level` of `grids`.
pub fn check_box(
    grids: &[LevelGrid],
    level: usize,
    lo: [u32; 3],
    size: [u32; 3],
) -> Result<(), DataError> {
    let Some(g) = grids.get(level) else {
        return Err(DataError::Invalid(format!(
            "no level {level} (there are {})",
            grids.len()
        )));
    };
    if (0..3).any(|a| lo[a] as u64 + size[a] as u64 > g.dims[a] as u64) {
        return Err(DataError::Invalid(format!(
            "box {lo:?} + {size:?} lies outside level {level} ({:?} voxels)",
            g.dims
        )));
    }
    Ok(())
}

/// Voxels `lo .. lo + size` of `level` of `source` as a volume placed where they lie in the world
/// (the level's voxel → world transform moved to voxel `lo`), its value range `value_range` when
/// given (the whole source's, so a transfer function maps values the same in every region),
/// else the region's own. Errors: the box outside the level, under 2 voxels along an axis, a
/// read failure.
pub fn region_volume(
    source: &dyn BrickSource,
    level: usize,
    lo: [u32; 3],
    size: [u32; 3],
    value_range: Option<[f32; 2]>,
) -> Result<VolumeData, DataError> {
    check_box(source.levels(), level, lo, size)?;
    let grid = &source.levels()[level];
    let mut geometry = grid.geometry;
    let shift = glam::DVec3::from_array(lo.map(f64::from));
    geometry.origin =
        grid.geometry.origin + grid.geometry.direction * (grid.geometry.spacing * shift);
    let voxels = source.read_box(level, lo, size)?;
    let mut v = VolumeData::from_voxels(size, geometry, voxels)?;
    if let Some(r) = value_range {
        v.value_range = r;
    }
    Ok(v)
}

/// A brick: its level and its index in that level's brick grid (`ceil(dims / inner)` per axis).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct BrickId {
    pub level: u32,
    pub brick: [u32; 3],
}

/// Bricks per axis of a level of `dims` voxels, `inner` voxels per brick side.
pub fn brick_grid(dims: [u32; 3], inner: u32) -> [u32; 3] {
    dims.map(|d| d.div_ceil(inner))
}

/// Brick `id` of `source` with its apron: `(inner + 2)³` voxels, x fastest, stored voxel
/// `l` along an axis being level voxel `brick · inner − 1 + l` clamped to the grid. Reads one
/// box (the clamped extent) and repeats its edges. Errors: no such level or brick, a read failure.
pub fn read_brick(source: &dyn BrickSource, id: BrickId, inner: u32) -> Result<Voxels, DataError> {
    let levels = source.levels();
    let Some(level) = levels.get(id.level as usize) else {
        return Err(DataError::Invalid(format!(
            "brick {id:?}: no level {} (there are {})",
            id.level,
            levels.len()
        )));
    };
    let grid = brick_grid(level.dims, inner);
    if inner == 0 || (0..3).any(|a| id.brick[a] >= grid[a]) {
        return Err(DataError::Invalid(format!(
            "brick {:?} of level {} is outside its {grid:?} bricks of {inner}³",
            id.brick, id.level
        )));
    }
    let stored = inner as usize + 2;
    // Level coordinate of stored voxel `l` along axis `a`, clamped to the grid.
    let coord = |a: usize, l: usize| {
        (id.brick[a] as i64 * inner as i64 - 1 + l as i64).clamp(0, level.dims[a] as i64 - 1) as u32
    };
    let lo = [0, 1, 2].map(|a| coord(a, 0));
    let hi = [0, 1, 2].map(|a| coord(a, stored - 1));
    let size = [0, 1, 2].map(|a| hi[a] - lo[a] + 1);
    let boxed = source.read_box(id.level as usize, lo, size)?;
    let (sx, sy) = (size[0] as usize, size[1] as usize);
    let index: Vec<usize> = {
        let axis = |a: usize| -> Vec<usize> {
            (0..stored)
                .map(|l| (coord(a, l) - lo[a]) as usize)
                .collect()
        };
        let (xs, ys, zs) = (axis(0), axis(1), axis(2));
        let mut index = Vec::with_capacity(stored.pow(3));
        for &z in &zs {
            for &y in &ys {
                index.extend(xs.iter().map(|&x| x + sx * (y + sy * z)));
            }
        }
        index
    };
    Ok(match &boxed {
        Voxels::U8(v) => Voxels::U8(index.iter().map(|&i| v[i]).collect()),
        Voxels::I8(v) => Voxels::I8(index.iter().map(|&i| v[i]).collect()),
        Voxels::U16(v) => Voxels::U16(index.iter().map(|&i| v[i]).collect()),
        Voxels::I16(v) => Voxels::I16(index.iter().map(|&i| v[i]).collect()),
        Voxels::F32(v) => Voxels::F32(index.iter().map(|&i| v[i]).collect()),
    })
}

/// Volumes in memory as a [`BrickSource`]: a volume and its coarser levels (pyramid.rs).
pub struct MemorySource {
    volumes: Vec<VolumeData>,
    grids: Vec<LevelGrid>,
}

impl MemorySource {
    /// `volume` with `coarser` levels below it (fewer where the grid cannot be halved further).
    /// Errors: as [`crate::pyramid::coarser_volume`].
    pub fn new(volume: VolumeData, coarser: usize) -> Result<Self, DataError> {
        let mut volumes = vec![volume];
        while volumes.len() <= coarser {
            let last = volumes.last().expect("a level");
            if !crate::pyramid::has_coarser(last.dims) {
                break;
            }
            let next = crate::pyramid::coarser_volume(last)?;
            volumes.push(next);
        }
        let grids = volumes
            .iter()
            .map(|v| LevelGrid {
                dims: v.dims,
                geometry: v.geometry,
            })
            .collect();
        Ok(MemorySource { volumes, grids })
    }
}

impl BrickSource for MemorySource {
    fn levels(&self) -> &[LevelGrid] {
        &self.grids
    }

    fn read_box(&self, level: usize, lo: [u32; 3], size: [u32; 3]) -> Result<Voxels, DataError> {
        check_box(&self.grids, level, lo, size)?;
        let v = &self.volumes[level];
        let [nx, ny, _] = v.dims.map(|d| d as usize);
        let rows = move |out: &mut dyn FnMut(usize, usize)| {
            for z in lo[2]..lo[2] + size[2] {
                for y in lo[1]..lo[1] + size[1] {
                    let start = lo[0] as usize + nx * (y as usize + ny * z as usize);
                    out(start, start + size[0] as usize);
                }
            }
        };
        macro_rules! copy {
            ($values:expr, $variant:ident) => {{
                let mut out = Vec::with_capacity(size.iter().map(|&s| s as usize).product());
                rows(&mut |a, b| out.extend_from_slice(&$values[a..b]));
                Voxels::$variant(out)
            }};
        }
        Ok(match &v.voxels {
            Voxels::U8(x) => copy!(x, U8),
            Voxels::I8(x) => copy!(x, I8),
            Voxels::U16(x) => copy!(x, U16),
            Voxels::I16(x) => copy!(x, I16),
            Voxels::F32(x) => copy!(x, F32),
        })
    }
}

/// Bytes a brick's voxels take.
fn bytes(v: &Voxels) -> u64 {
    (v.len() * v.bytes_per_voxel()) as u64
}

/// Bricks in host memory under a byte budget; inserting past it evicts the least recently used.
pub struct BrickCache {
    budget: u64,
    used: u64,
    bricks: LruCache<BrickId, Arc<Voxels>>,
}

impl BrickCache {
    /// A cache of at most `budget` bytes of voxels.
    pub fn new(budget: u64) -> Self {
        BrickCache {
            budget,
            used: 0,
            bricks: LruCache::unbounded(),
        }
    }

    /// The brick, marked as just used.
    pub fn get(&mut self, id: &BrickId) -> Option<Arc<Voxels>> {
        self.bricks.get(id).cloned()
    }

    /// Keeps `voxels` as brick `id`, evicting the least recently used bricks until it fits; a
    /// brick larger than the whole budget is not kept. Returns the evicted bricks' ids.
    pub fn insert(&mut self, id: BrickId, voxels: Arc<Voxels>) -> Vec<BrickId> {
        let size = bytes(&voxels);
        let mut evicted = Vec::new();
        if let Some(old) = self.bricks.pop(&id) {
            self.used -= bytes(&old);
        }
        if size > self.budget {
            return evicted;
        }
        while self.used + size > self.budget {
            let Some((old_id, old)) = self.bricks.pop_lru() else {
                break;
            };
            self.used -= bytes(&old);
            evicted.push(old_id);
        }
        self.used += size;
        self.bricks.put(id, voxels);
        evicted
    }

    /// Bytes held.
    pub fn used(&self) -> u64 {
        self.used
    }

    /// Bricks held.
    pub fn len(&self) -> usize {
        self.bricks.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bricks.is_empty()
    }
}

/// What a worker hands back: the brick or why it could not be read.
pub type Loaded = (BrickId, Result<Arc<Voxels>, DataError>);

/// Worker threads reading requested bricks of one source ([`read_brick`]); results arrive in
/// the order they finish. A brick requested again while pending is read once.
pub struct BrickLoader {
    requests: Option<Sender<BrickId>>,
    results: Receiver<Loaded>,
    pending: HashSet<BrickId>,
    workers: Vec<JoinHandle<()>>,
}

impl BrickLoader {
    /// `threads` workers (at least one) reading bricks of `inner`³ voxels from `source`.
    pub fn new(source: Arc<dyn BrickSource>, inner: u32, threads: usize) -> Self {
        let (requests, inbox) = crossbeam_channel::unbounded::<BrickId>();
        let (outbox, results) = crossbeam_channel::unbounded::<Loaded>();
        let workers = (0..threads.max(1))
            .map(|n| {
                let (inbox, outbox, source) = (inbox.clone(), outbox.clone(), source.clone());
                std::thread::Builder::new()
                    .name(format!("hatchery-bricks-{n}"))
                    .spawn(move || {
                        for id in inbox {
                            let brick = read_brick(source.as_ref(), id, inner).map(Arc::new);
                            if outbox.send((id, brick)).is_err() {
                                return;
                            }
                        }
                    })
                    .expect("spawn a brick reader thread")
            })
            .collect();
        BrickLoader {
            requests: Some(requests),
            results,
            pending: HashSet::new(),
            workers,
        }
    }

    /// Asks for brick `id` unless it is already pending.
    pub fn request(&mut self, id: BrickId) {
        if self.pending.insert(id)
            && let Some(r) = &self.requests
        {
            // The workers live as long as the loader, so the channel is open.
            let _ = r.send(id);
        }
    }

    /// Bricks requested and not yet handed back.
    pub fn pending(&self) -> usize {
        self.pending.len()
    }

    /// The bricks read since the last call, without waiting.
    pub fn poll(&mut self) -> Vec<Loaded> {
        let done: Vec<Loaded> = self.results.try_iter().collect();
        for (id, _) in &done {
            self.pending.remove(id);
        }
        done
    }

    /// Waits for every pending brick.
    pub fn wait_all(&mut self) -> Vec<Loaded> {
        let mut done = Vec::new();
        while !self.pending.is_empty() {
            let Ok(loaded) = self.results.recv() else {
                break;
            };
            self.pending.remove(&loaded.0);
            done.push(loaded);
        }
        done
    }
}

impl Drop for BrickLoader {
    fn drop(&mut self) {
        // Closing the request channel ends the workers' loops.
        self.requests = None;
        for w in self.workers.drain(..) {
            let _ = w.join();
        }
    }
}
