//! OME-Zarr in the browser build: not read. Its arrays are folders of chunk files compressed
//! with C codecs (Blosc, zstd), and a page reads single files by URL. Every entry point the
//! native module has is here so that callers compile unchanged; those that would read a group
//! say so in one line. Convert the image first (`hatchery convert` writes NIfTI).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use crate::DataError;
use crate::brick_source::{BrickSource, LevelGrid};
use crate::volume::VolumeData;
use crate::voxels::Voxels;

const NOT_HERE: &str = "OME-Zarr is not read in the browser build (its codecs are C and it is a \
                        folder of chunks); export the figure with a NIfTI copy of the image";

/// Whether `path` names a Zarr group: by name only (a browser has no folders to look into).
pub fn is_zarr(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("zarr"))
}

/// The group a path means: as the native module, without looking at the disk.
pub fn group_of(path: &Path) -> &Path {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase());
    match (name.as_deref(), path.parent()) {
        (Some("zarr.json" | ".zattrs" | ".zgroup"), Some(parent)) => parent,
        _ => path,
    }
}

/// An OME-Zarr image; never opened in the browser build.
pub struct Multiscale {
    never: std::convert::Infallible,
}

impl Multiscale {
    /// Errors: always, naming the path (see the module doc).
    pub fn open(path: &Path) -> Result<Self, DataError> {
        Err(DataError::unsupported(path, NOT_HERE))
    }
}

impl BrickSource for Multiscale {
    fn levels(&self) -> &[LevelGrid] {
        match self.never {}
    }

    fn read_box(&self, _: usize, _: [u32; 3], _: [u32; 3]) -> Result<Voxels, DataError> {
        match self.never {}
    }
}

/// No label images are listed in the browser build.
pub fn label_images(_image: &Path) -> Vec<String> {
    Vec::new()
}

/// Errors: always (see the module doc).
pub fn resolve(path: &Path, _array: Option<&str>) -> Result<PathBuf, DataError> {
    Err(DataError::unsupported(path, NOT_HERE))
}

/// Errors: always (see the module doc).
pub fn load_label_image(
    path: &Path,
    _array: Option<&str>,
) -> Result<(VolumeData, BTreeMap<u16, String>), DataError> {
    Err(DataError::unsupported(path, NOT_HERE))
}

/// Errors: always (see the module doc).
pub fn load_ome_zarr(path: &Path, _array: Option<&str>) -> Result<VolumeData, DataError> {
    Err(DataError::unsupported(path, NOT_HERE))
}
