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

/// The whole file at `path`. Errors: as `std::fs::read`, and `InvalidInput` for what is not a
/// regular file (a device such as /dev/zero, a pipe: reading them would never end); in the
/// browser, a path the figure did not fetch is `NotFound`.
pub fn read(path: &Path) -> io::Result<Vec<u8>> {
    #[cfg(target_arch = "wasm32")]
    {
        let mounted = MOUNTED.lock().unwrap_or_else(|e| e.into_inner());
        match mounted.as_ref().and_then(|m| m.get(&normal(path))) {
            Some(bytes) => Ok(bytes.to_vec()),
            None => Err(io::Error::new(
                io::ErrorKind::NotFound,
                "not one of the files this figure fetched (export it with `hatchery export-web`)",
            )),
        }
    }
    #[cfg(not(target_arch = "wasm32"))]
    {
        if !std::fs::metadata(path)?.is_file() {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                "is not a regular file",
            ));
        }
        std::fs::read(path)
    }
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
