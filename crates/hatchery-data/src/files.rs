//! Reading data files by path, on the desktop and in the browser.
//!
//! Natively this is the file system. A page has none: the browser build (crates/hatchery-web)
//! fetches the files a figure reads and [`mount`]s their bytes under the paths its graph names,
//! and the loaders read them here as they would from disk. Folders (DICOM series, TIFF stacks,
//! OME-Zarr) are not mounted; their loaders say so.

use std::io;
use std::path::Path;

#[cfg(target_arch = "wasm32")]
use std::{collections::HashMap, path::PathBuf, sync::Mutex};

#[cfg(target_arch = "wasm32")]
static MOUNTED: Mutex<Option<HashMap<PathBuf, std::sync::Arc<[u8]>>>> = Mutex::new(None);

/// Makes `bytes` the file at `path` for [`read`] (the browser build; natively files are on disk
/// and this does nothing).
pub fn mount(path: &Path, bytes: Vec<u8>) {
    #[cfg(target_arch = "wasm32")]
    {
        let mut mounted = MOUNTED.lock().unwrap_or_else(|e| e.into_inner());
        mounted
            .get_or_insert_with(HashMap::new)
            .insert(normal(path), bytes.into());
    }
    #[cfg(not(target_arch = "wasm32"))]
    let _ = (path, bytes);
}

/// `a/./b` and `a/b` are one file.
#[cfg(target_arch = "wasm32")]
fn normal(path: &Path) -> PathBuf {
    path.components()
        .filter(|c| !matches!(c, std::path::Component::CurDir))
        .collect()
}

/// The whole file at `path` (for formats read whole: meshes, `.vti`, name tables). Errors: as
/// `std::fs::read`; in the browser, a path the figure did not fetch is `NotFound`.
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    #[cfg(target_arch = "wasm32")]
    {
        mounted(path).map(|bytes| bytes.to_vec())
    }
    #[cfg(not(target_arch = "wasm32"))]
    std::fs::read(path)
}

/// An open data file: natively a `std::fs::File`; in the browser the mounted bytes. Loaders
/// read headers and voxels from it as they come, so natively nothing is read whole.
#[cfg(not(target_arch = "wasm32"))]
pub type DataFile = std::fs::File;
#[cfg(target_arch = "wasm32")]
pub type DataFile = io::Cursor<std::sync::Arc<[u8]>>;

/// Opens `path` for reading. Errors: as `std::fs::File::open`; in the browser `NotFound` for a
/// path the figure did not fetch.
pub fn open(path: &Path) -> io::Result<DataFile> {
    #[cfg(target_arch = "wasm32")]
    {
        mounted(path).map(io::Cursor::new)
    }
    #[cfg(not(target_arch = "wasm32"))]
    std::fs::File::open(path)
}

/// The length of an open file in bytes. Errors: as `std::fs::File::metadata`.
pub fn len_of(file: &DataFile) -> io::Result<u64> {
    #[cfg(target_arch = "wasm32")]
    {
        Ok(file.get_ref().len() as u64)
    }
    #[cfg(not(target_arch = "wasm32"))]
    Ok(file.metadata()?.len())
}

/// Whether `path` is a regular file, and its length in bytes (a device, a pipe or a folder is
/// not). Errors: as `std::fs::metadata`.
pub fn regular_file_len(path: &Path) -> io::Result<Option<u64>> {
    #[cfg(target_arch = "wasm32")]
    {
        mounted(path).map(|bytes| Some(bytes.len() as u64))
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        let metadata = std::fs::metadata(path)?;
        Ok(metadata.is_file().then_some(metadata.len()))
    }
}

#[cfg(target_arch = "wasm32")]
fn mounted(path: &Path) -> io::Result<std::sync::Arc<[u8]>> {
    let mounted = MOUNTED.lock().unwrap_or_else(|e| e.into_inner());
    mounted
        .as_ref()
        .and_then(|m| m.get(&normal(path)))
        .cloned()
        .ok_or_else(|| {
            // The page mounts dropped files under dropped/ (hatchery-web): a missing one is a
            // file another names (a MetaImage header's voxels) that was not dropped with it.
            let message = if path.starts_with("dropped") {
                "not dropped: drop it together with the file that names it"
            } else {
                "not one of the files this figure fetched (export it with `hatchery export-web`)"
            };
            io::Error::new(io::ErrorKind::NotFound, message)
        })
}

/// Whether `path` is a file [`read`] can read.
pub fn is_file(path: &Path) -> bool {
    #[cfg(target_arch = "wasm32")]
    {
        let mounted = MOUNTED.lock().unwrap_or_else(|e| e.into_inner());
        mounted
            .as_ref()
            .is_some_and(|m| m.contains_key(&normal(path)))
    }
    #[cfg(not(target_arch = "wasm32"))]
    path.is_file()
}
