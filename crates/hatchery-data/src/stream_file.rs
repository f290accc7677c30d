//! A volume file as a [`BrickSource`] (streaming, issue 30): the reader that reads it brick by
//! brick, chosen by format as [`crate::volume_file`] chooses the loader.

use std::path::Path;
use std::sync::Arc;

use crate::brick_source::{BrickSource, region_volume};
use crate::derived_levels::DerivedLevels;
use crate::voxels::MAX_VOXELS;
use crate::{DataError, VolumeData};

/// The formats [`open_stream`] streams, for messages and docs.
pub const STREAMED_FORMATS: &str = "OME-Zarr (.zarr), uncompressed NIfTI (.nii), raw NRRD (.nrrd, \
     .nhdr) and uncompressed MetaImage (.mha, .mhd)";

/// A file's voxels as a [`BrickSource`], read brick by brick: an OME-Zarr pyramid from its
/// chunks, the raw formats from the memory-mapped file (one level). Errors: another format, or
/// compressed data in a raw format (the error says to `hatchery convert` it to OME-Zarr).
pub fn open_stream(path: &Path) -> Result<Arc<dyn BrickSource>, DataError> {
    let path = crate::ome_zarr::group_of(path);
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    Ok(
        if crate::ome_zarr::is_zarr(path) || name.ends_with(".zarr") {
            Arc::new(crate::ome_zarr::Multiscale::open(path)?)
        } else if name.ends_with(".nii") {
            Arc::new(crate::nifti_file::nifti_source(path)?)
        } else if name.ends_with(".nrrd") || name.ends_with(".nhdr") {
            Arc::new(crate::nrrd_file::nrrd_source(path)?)
        } else if name.ends_with(".mha") || name.ends_with(".mhd") {
            Arc::new(crate::metaimage_file::metaimage_source(path)?)
        } else {
            return Err(DataError::unsupported(
                path,
                format!(
                    "not read a brick at a time; streamed formats: {STREAMED_FORMATS} \
                 (`hatchery convert` makes an OME-Zarr)"
                ),
            ));
        },
    )
}

/// The host memory budget for volumes in bytes: `HATCHERY_HOST_BUDGET_MB` (default 4096).
/// A volume whose finest level would need more (loading and framing it peak at about 4 × its
/// stored bytes: a 1024³ uint16 OME-Zarr took 10 GiB) is
/// streamed ([`open_beyond_budget`]). Errors: a value that is not a whole number ≥ 1
/// ([`DataError::Invalid`], naming the variable).
pub fn host_budget() -> Result<u64, DataError> {
    match std::env::var("HATCHERY_HOST_BUDGET_MB") {
        Err(_) => Ok(4096 << 20),
        Ok(text) => match text.trim().parse::<u64>() {
            Ok(n) if n >= 1 => Ok(n.saturating_mul(1 << 20)),
            _ => Err(DataError::Invalid(format!(
                "HATCHERY_HOST_BUDGET_MB={text:?}: expected a whole number of MiB, at least 1"
            ))),
        },
    }
}

/// A volume file opened for streaming: its levels (coarser ones derived where the file stores
/// fewer, [`DerivedLevels`]) and the level held in memory.
pub struct Streamed {
    pub source: Arc<dyn BrickSource>,
    pub preview_level: usize,
    pub preview: VolumeData,
    /// Bytes of one voxel as stored.
    pub voxel_bytes: u64,
}

/// Opens `path` (`array`: an OME-Zarr label image) for streaming when its format streams and
/// its finest level is beyond `budget` bytes (4 × its stored bytes, or more voxels than a
/// volume in memory may hold); `None` otherwise (load it whole). The preview is the finest
/// level of at most `budget / 8` bytes, read whole; `labels`: derive coarser levels by
/// majority. Errors: the file's metadata or preview cannot be read.
pub fn open_beyond_budget(
    path: &Path,
    array: Option<&str>,
    budget: u64,
    labels: bool,
) -> Result<Option<Streamed>, DataError> {
    let group = crate::ome_zarr::group_of(path);
    let base: Arc<dyn BrickSource> = if crate::ome_zarr::is_zarr(group) {
        let image = crate::ome_zarr::resolve(group, array)?;
        Arc::new(crate::ome_zarr::Multiscale::open(&image)?)
    } else {
        match open_stream(path) {
            Ok(s) => s,
            // Not a streamed format or a compressed raw file: loaded whole as before.
            Err(_) => return Ok(None),
        }
    };
    let top = base.levels()[0].clone();
    use crate::derived_levels::voxels;
    let probe = base.read_box(0, [0; 3], [1; 3])?;
    let voxel_bytes = probe.bytes_per_voxel() as u64;
    let bytes = voxels(top.dims).saturating_mul(voxel_bytes);
    if bytes.saturating_mul(4) <= budget && voxels(top.dims) <= MAX_VOXELS {
        return Ok(None);
    }
    let source: Arc<dyn BrickSource> = Arc::new(DerivedLevels::new(base, labels));
    let levels = source.levels();
    let preview_level = (0..levels.len())
        .find(|&k| voxels(levels[k].dims).saturating_mul(voxel_bytes) <= budget / 8)
        .unwrap_or(levels.len() - 1);
    let dims = levels[preview_level].dims;
    let preview = region_volume(source.as_ref(), preview_level, [0; 3], dims, None)?;
    Ok(Some(Streamed {
        source,
        preview_level,
        preview,
        voxel_bytes,
    }))
}
