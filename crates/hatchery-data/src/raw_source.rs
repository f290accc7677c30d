//! Raw voxel data read box by box from a memory-mapped file (streaming, issue 30): the bytes of a
//! header-plus-raw format (MetaImage, uncompressed NIfTI) stay in the page cache, and only the rows a brick
//! needs are decoded, so a volume larger than memory can be read a brick at a time.

use std::path::{Path, PathBuf};

use memmap2::Mmap;

use crate::DataError;
use crate::brick_source::{BrickSource, LevelGrid, check_box};
use crate::geometry::Geometry;
use crate::raw_voxels::{self, Element};
use crate::voxels::Voxels;

/// Turns the bytes of whole voxels into voxels (byte order, scaling: the format's rules).
pub(crate) type Decode = Box<dyn Fn(Vec<u8>) -> Voxels + Send + Sync>;

/// One level of raw voxels (x fastest) at `offset` bytes into a memory-mapped file.
pub struct RawSource {
    path: PathBuf,
    map: Mmap,
    offset: usize,
    voxel_bytes: usize,
    decode: Decode,
    grids: Vec<LevelGrid>,
}

impl RawSource {
    /// Maps `data_file`, whose voxels start at `offset` (`None`: they end the file). Errors: the
    /// file cannot be opened or is shorter than the voxels it should hold.
    pub(crate) fn open(
        data_file: &Path,
        offset: Option<u64>,
        element: Element,
        big_endian: bool,
        dims: [u32; 3],
        geometry: Geometry,
    ) -> Result<Self, DataError> {
        let decode: Decode = Box::new(move |b| raw_voxels::decode(&b, element, big_endian));
        Self::open_with(data_file, offset, element.size(), decode, dims, geometry)
    }

    /// [`Self::open`] for voxels of `voxel_bytes` bytes each, turned into voxels by `decode`.
    pub(crate) fn open_with(
        data_file: &Path,
        offset: Option<u64>,
        voxel_bytes: usize,
        decode: Decode,
        dims: [u32; 3],
        geometry: Geometry,
    ) -> Result<Self, DataError> {
        let file = std::fs::File::open(data_file).map_err(|e| DataError::io(data_file, e))?;
        // Safety: the map is read-only and private to this source; hatchery never writes the
        // file. Another program truncating it while it is mapped would fault the reads (as for
        // every reader that maps files, e.g. nibabel's mmap mode), so bounds are checked against
        // the length it had when mapped.
        #[allow(unsafe_code)]
        let map = unsafe { Mmap::map(&file) }.map_err(|e| DataError::io(data_file, e))?;
        let bytes = dims.iter().map(|&d| d as u64).product::<u64>() * voxel_bytes as u64;
        let len = map.len() as u64;
        let offset = match offset {
            Some(o) => o,
            None => len.checked_sub(bytes).unwrap_or(u64::MAX),
        };
        if offset.checked_add(bytes).is_none_or(|end| end > len) {
            return Err(DataError::format(
                data_file,
                format!(
                    "holds {len} bytes, too few for {bytes} bytes of voxels from byte {offset}"
                ),
            ));
        }
        Ok(RawSource {
            path: data_file.to_path_buf(),
            map,
            offset: offset as usize,
            voxel_bytes,
            decode,
            grids: vec![LevelGrid { dims, geometry }],
        })
    }
}

impl BrickSource for RawSource {
    fn levels(&self) -> &[LevelGrid] {
        &self.grids
    }

    fn read_box(&self, level: usize, lo: [u32; 3], size: [u32; 3]) -> Result<Voxels, DataError> {
        check_box(&self.grids, level, lo, size).map_err(|e| e.in_file(&self.path))?;
        let [nx, ny, _] = self.grids[0].dims.map(|d| d as usize);
        let e = self.voxel_bytes;
        let row = size[0] as usize * e;
        let mut bytes = Vec::with_capacity(row * size[1] as usize * size[2] as usize);
        for z in lo[2] as usize..(lo[2] + size[2]) as usize {
            for y in lo[1] as usize..(lo[1] + size[1]) as usize {
                let start = self.offset + e * (lo[0] as usize + nx * (y + ny * z));
                bytes.extend_from_slice(&self.map[start..start + row]);
            }
        }
        Ok((self.decode)(bytes))
    }
}
