//! A volume file as a [`BrickSource`] (streaming, issue 30): the reader that reads it brick by
//! brick, chosen by format as [`crate::volume_file`] chooses the loader.

use std::path::Path;
use std::sync::Arc;

use crate::DataError;
use crate::brick_source::BrickSource;

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
