//! Volume files of any supported format, chosen by file name.

use std::path::Path;

use crate::nifti_file::load_nifti;
use crate::vti_file::load_vti;
use crate::{DataError, VolumeData};

/// File name endings [`load_volume`] reads (matched case-insensitively).
pub const VOLUME_ENDINGS: [&str; 3] = [".nii", ".nii.gz", ".vti"];

/// Loads a volume, choosing the format by the (case-insensitive) end of the file name:
/// `.nii` and `.nii.gz` with [`load_nifti`], `.vti` with [`load_vti`].
pub fn load_volume(path: &Path) -> Result<VolumeData, DataError> {
    // The whole name, not `extension()`: `.nii.gz` has two parts.
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    if name.ends_with(".nii") || name.ends_with(".nii.gz") {
        load_nifti(path)
    } else if name.ends_with(".vti") {
        load_vti(path)
    } else {
        Err(DataError::unsupported(
            path,
            format!(
                "unknown volume file type, supported endings are {}",
                VOLUME_ENDINGS.join(", ")
            ),
        ))
    }
}
