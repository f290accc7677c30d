//! Writing outputs so that a killed process leaves the old file or none.

use crate::BatchError;
use std::path::{Path, PathBuf};

/// Writes `bytes` to `path` atomically (hatchery_graph::atomic), making its folder first. A
/// killed process leaves the old file or none, never half of one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), BatchError> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(dir) = dir {
        std::fs::create_dir_all(dir)
            .map_err(|e| BatchError::Io(format!("cannot create {}: {e}", dir.display())))?;
    }
    hatchery_graph::atomic::write_bytes_atomically(path, bytes)
        .map_err(|e| BatchError::Io(format!("cannot write {}: {e}", path.display())))
}

/// A temporary name beside `path` (hidden, with this process's id).
pub fn temp_beside(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp-{}", std::process::id()))
}
