//! Coarser levels of detail made on demand from finer ones (streaming, issue 30). A source that
//! stores one level (a raw NIfTI, NRRD or MetaImage file) or a pyramid that stops early gets the
//! levels below its coarsest by averaging 2×2×2 blocks of the level above ([`crate::pyramid`]'s
//! rules, so they equal `coarser_volume` of the whole), a box at a time: a far view of a huge raw
//! file reads the file once at the level it needs and never holds it whole.

use std::sync::Arc;

use crate::DataError;
use crate::brick_source::{BrickSource, LevelGrid, check_box};
use crate::pyramid::{coarser_box, coarser_dims, coarser_geometry, halved, has_coarser};
use crate::voxels::Voxels;

/// Levels are derived down to a grid of at most this many voxels (64³).
pub const COARSEST_VOXELS: u64 = 64 * 64 * 64;

/// The most voxels of the finer level one step of a derived read holds (bounds memory: a slab
/// per level at a time, whatever the box).
const SLAB_VOXELS: u64 = 16 << 20;

/// Voxels of a grid of `dims` (saturating: absurd shapes from a file never overflow).
pub(crate) fn voxels(dims: [u32; 3]) -> u64 {
    dims.iter().fold(1u64, |n, &d| n.saturating_mul(d as u64))
}

/// A source with coarser levels derived below its stored ones.
pub struct DerivedLevels {
    base: Arc<dyn BrickSource>,
    stored: usize,
    grids: Vec<LevelGrid>,
    labels: bool,
    slab_voxels: u64,
}

impl DerivedLevels {
    /// `base`'s levels, then coarser ones down to [`COARSEST_VOXELS`]; `labels`: the voxels are
    /// label ids, derived by majority instead of the mean.
    pub fn new(base: Arc<dyn BrickSource>, labels: bool) -> Self {
        let mut grids = base.levels().to_vec();
        let stored = grids.len();
        while let Some(last) = grids.last()
            && voxels(last.dims) > COARSEST_VOXELS
            && has_coarser(last.dims)
        {
            let next = LevelGrid {
                dims: coarser_dims(last.dims),
                geometry: coarser_geometry(last.dims, &last.geometry),
            };
            grids.push(next);
        }
        DerivedLevels {
            base,
            stored,
            grids,
            labels,
            slab_voxels: SLAB_VOXELS,
        }
    }

    /// How many of the levels the base source stores (the rest are derived).
    pub fn stored(&self) -> usize {
        self.stored
    }
}

impl BrickSource for DerivedLevels {
    fn levels(&self) -> &[LevelGrid] {
        &self.grids
    }

    fn read_box(&self, level: usize, lo: [u32; 3], size: [u32; 3]) -> Result<Voxels, DataError> {
        check_box(&self.grids, level, lo, size)?;
        if size.contains(&0) {
            return Err(DataError::Invalid(format!(
                "an empty box {size:?} of level {level}"
            )));
        }
        if level < self.stored {
            return self.base.read_box(level, lo, size);
        }
        let fine = &self.grids[level - 1];
        let h = halved(fine.dims);
        // The finer level's voxels under coarse voxels a .. b along axis `axis`.
        let span = |axis: usize, a: u32, b: u32| {
            if h[axis] {
                (2 * a, (2 * b).min(fine.dims[axis]))
            } else {
                (a, b)
            }
        };
        let (x0, x1) = span(0, lo[0], lo[0] + size[0]);
        let (y0, y1) = span(1, lo[1], lo[1] + size[1]);
        let fine_row = (x1 - x0) as u64 * (y1 - y0) as u64 * if h[2] { 2 } else { 1 };
        let rows = (self.slab_voxels / fine_row.max(1)).clamp(1, size[2] as u64) as u32;
        let mut out: Option<Voxels> = None;
        let end = lo[2] + size[2];
        let mut z = lo[2];
        while z < end {
            let z_end = (z + rows).min(end);
            let (z0, z1) = span(2, z, z_end);
            let dims = [x1 - x0, y1 - y0, z1 - z0];
            let finer = self.read_box(level - 1, [x0, y0, z0], dims)?;
            let slab = coarser_box(&finer, dims, h, self.labels);
            match &mut out {
                Some(o) => o.append(slab),
                None => out = Some(slab),
            }
            z = z_end;
        }
        Ok(out.unwrap_or(Voxels::F32(Vec::new())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brick_source::MemorySource;
    use crate::geometry::Geometry;
    use crate::pyramid::{coarser_label_volume, coarser_volume};
    use crate::volume::VolumeData;

    fn ramp(dims: [u32; 3]) -> VolumeData {
        let n = voxels(dims) as usize;
        let values: Vec<u16> = (0..n).map(|i| ((i * 7919) % 1000) as u16).collect();
        let g = Geometry::axis_aligned([0.5, 1.0, 2.0], [3.0, -4.0, 5.0]);
        VolumeData::from_voxels(dims, g, Voxels::U16(values)).unwrap()
    }

    #[test]
    fn derived_levels_equal_the_coarser_volumes_of_the_whole_box_by_box() {
        // Odd sizes, so the last block along each axis is cut.
        let v = ramp([137, 130, 129]);
        let mut derived =
            DerivedLevels::new(Arc::new(MemorySource::new(v.clone(), 0).unwrap()), false);
        assert_eq!(derived.stored(), 1);
        // Slabs of a few rows, so every read takes several.
        derived.slab_voxels = 5000;
        let l1 = coarser_volume(&v).unwrap();
        let l2 = coarser_volume(&l1).unwrap();
        let levels = derived.levels();
        assert_eq!(levels.len(), 3, "137×130×129 → 69×65×65 → 35×33×33 (≤ 64³)");
        assert_eq!((levels[1].dims, levels[2].dims), (l1.dims, l2.dims));
        assert_eq!(levels[2].geometry, l2.geometry);
        // A box at an odd place of level 2 is the same box of the coarser volume.
        let (lo, size) = ([3, 5, 1], [17, 13, 31]);
        let got = derived.read_box(2, lo, size).unwrap();
        let want = MemorySource::new(l2, 0)
            .unwrap()
            .read_box(0, lo, size)
            .unwrap();
        assert_eq!(got, want);
        let whole = derived.read_box(1, [0; 3], l1.dims).unwrap();
        assert_eq!(whole, l1.voxels);
    }

    #[test]
    fn derived_label_levels_keep_the_majority() {
        let ids = match ramp([70, 66, 70]).voxels {
            Voxels::U16(x) => Voxels::U16(x.into_iter().map(|i| i % 3).collect()),
            _ => unreachable!("ramp makes uint16"),
        };
        let g = Geometry::axis_aligned([1.0; 3], [0.0; 3]);
        let labels = VolumeData::from_voxels([70, 66, 70], g, ids).unwrap();
        let source = MemorySource::new(labels.clone(), 0).unwrap();
        let derived = DerivedLevels::new(Arc::new(source), true);
        assert_eq!(derived.levels().len(), 2, "70×66×70 voxels → 35×33×35");
        let got = derived.read_box(1, [0; 3], [35, 33, 35]).unwrap();
        assert_eq!(got, coarser_label_volume(&labels).unwrap().voxels);
    }
}
